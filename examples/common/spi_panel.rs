//! A display on a recording SPI bus, and a model of the panel that replays what was sent: for
//! `tests/all/display_driver.rs` and the `display_spi` example (included with `#[path]`).
//!
//! * [`Recorder`] hands out an embedded-hal 1.0 [`SpiDevice`] ([`RecordingSpi`]) and the
//!   data/command [`OutputPin`] ([`DcPin`]) of a 4-line serial interface; both share one log,
//!   which keeps each byte written with the level of D/C while it went out (low: a command,
//!   high: a parameter or pixel data) and the number of SPI transactions.
//! * [`Panel`] replays a log into a model of an ST7789 / ILI9341 controller's 240 × 320 frame
//!   memory. It is written from the MIPI DCS command descriptions of the ST7789V and ILI9341
//!   datasheets, not from a driver's code: CASET `0x2A` and RASET `0x2B` (start and end,
//!   each 16 bits, high byte first), RAMWR `0x2C` (pixel data into the window, row by row,
//!   from the start column and page), MADCTL `0x36` (row/column exchange, column and page
//!   order, RGB/BGR), COLMOD `0x3A` (16 bits a pixel only, 5-6-5, high byte first) and the
//!   commands of a power-up (SWRESET, SLPOUT, NORON, INVOFF/INVON, DISPON). Anything else
//!   panics: the model does not guess.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::convert::Infallible;
use std::rc::Rc;

use embedded_graphics::pixelcolor::raw::RawU16;
use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_hal::delay::DelayNs;
use embedded_hal::digital::{self, OutputPin};
use embedded_hal::spi::{self, Operation, SpiDevice};

/// One byte on the wire and the D/C level it went out with (`false`: command).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Byte {
    /// D/C high: data (a parameter or pixels).
    pub data: bool,
    /// The byte.
    pub value: u8,
}

/// What the bus saw.
#[derive(Debug, Default)]
pub struct Log {
    /// Every byte, in order.
    pub bytes: Vec<Byte>,
    /// Bytes of each SPI transaction (chip select low to high), in order.
    pub transactions: Vec<usize>,
    dc_high: bool,
}

/// The shared log of a [`RecordingSpi`] and its [`DcPin`].
#[derive(Debug, Clone, Default)]
pub struct Recorder(Rc<RefCell<Log>>);

impl Recorder {
    /// A recorder with an empty log.
    pub fn new() -> Self {
        Self::default()
    }

    /// The SPI device writing into this log.
    pub fn spi(&self) -> RecordingSpi {
        RecordingSpi(self.clone())
    }

    /// The D/C pin of this log.
    pub fn dc(&self) -> DcPin {
        DcPin(self.clone())
    }

    /// The log so far, leaving it empty (D/C keeps its level).
    pub fn take(&self) -> Log {
        let mut log = self.0.borrow_mut();
        Log {
            bytes: std::mem::take(&mut log.bytes),
            transactions: std::mem::take(&mut log.transactions),
            dc_high: log.dc_high,
        }
    }
}

/// An embedded-hal 1.0 SPI device that records what is written (it only writes: a display on
/// a 4-line serial interface is not read here).
#[derive(Debug)]
pub struct RecordingSpi(Recorder);

impl spi::ErrorType for RecordingSpi {
    type Error = Infallible;
}

impl SpiDevice for RecordingSpi {
    fn transaction(&mut self, operations: &mut [Operation<'_, u8>]) -> Result<(), Infallible> {
        let mut log = self.0 .0.borrow_mut();
        let mut n = 0;
        for op in operations {
            match op {
                Operation::Write(bytes) => {
                    let data = log.dc_high;
                    log.bytes
                        .extend(bytes.iter().map(|&value| Byte { data, value }));
                    n += bytes.len();
                }
                Operation::DelayNs(_) => {}
                _ => panic!("the recording SPI only writes"),
            }
        }
        log.transactions.push(n);
        Ok(())
    }
}

/// The D/C pin: its level goes into the log with each byte.
#[derive(Debug)]
pub struct DcPin(Recorder);

impl digital::ErrorType for DcPin {
    type Error = Infallible;
}

impl OutputPin for DcPin {
    fn set_low(&mut self) -> Result<(), Infallible> {
        self.0 .0.borrow_mut().dc_high = false;
        Ok(())
    }

    fn set_high(&mut self) -> Result<(), Infallible> {
        self.0 .0.borrow_mut().dc_high = true;
        Ok(())
    }
}

/// A delay that returns at once (the model has no timing).
#[derive(Debug)]
pub struct NoDelay;

impl DelayNs for NoDelay {
    fn delay_ns(&mut self, _ns: u32) {}
}

/// Columns of the controllers' frame memory (the portrait width).
pub const GRAM_WIDTH: u16 = 240;
/// Rows (pages) of the controllers' frame memory (the portrait height).
pub const GRAM_HEIGHT: u16 = 320;

// MADCTL bits (ST7789V datasheet 9.1.28, ILI9341 8.2.29).
const MY: u8 = 0x80; // page (row) address order
const MX: u8 = 0x40; // column address order
const MV: u8 = 0x20; // row/column exchange
const ML: u8 = 0x10; // vertical refresh order: not modelled
const BGR: u8 = 0x08; // colour filter order
const MH: u8 = 0x04; // horizontal refresh order: not modelled

/// What a stream held, beside the pixels.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct Counts {
    /// Bytes with D/C low.
    pub command_bytes: usize,
    /// Parameter bytes of commands other than RAMWR.
    pub parameter_bytes: usize,
    /// Pixel data bytes (after RAMWR).
    pub pixel_bytes: usize,
    /// How often each command came.
    pub commands: BTreeMap<u8, usize>,
}

impl Counts {
    /// All bytes on the wire.
    pub fn total(&self) -> usize {
        self.command_bytes + self.parameter_bytes + self.pixel_bytes
    }

    /// How often `command` came.
    pub fn count(&self, command: u8) -> usize {
        self.commands.get(&command).copied().unwrap_or(0)
    }
}

/// The controller: its frame memory and the state the commands set.
#[derive(Debug, Clone)]
pub struct Panel {
    /// The 16-bit words written, portrait row-major; `None` where nothing was written.
    gram: Vec<Option<u16>>,
    madctl: u8,
    /// COLMOD's parameter; `None` after a reset (18 bits a pixel on both controllers).
    colmod: Option<u8>,
    inverted: bool,
    sleeping: bool,
    display_on: bool,
    columns: (u16, u16),
    pages: (u16, u16),
    /// Extended (non-DCS) commands this panel accepts with their parameter count, none of
    /// which touches the frame memory.
    extended: &'static [(u8, usize)],
    counts: Counts,
}

/// The command being received: its code and its parameters so far.
struct Pending {
    command: u8,
    parameters: Vec<u8>,
}

impl Panel {
    /// An ST7789 as it powers up.
    pub fn st7789() -> Self {
        Self::with_extended(&[])
    }

    /// An ILI9341 as it powers up; it also takes `0xB4` (display inversion control, one
    /// parameter: how the liquid crystal is driven, not the memory).
    pub fn ili9341() -> Self {
        Self::with_extended(&[(0xB4, 1)])
    }

    fn with_extended(extended: &'static [(u8, usize)]) -> Self {
        Panel {
            gram: vec![None; usize::from(GRAM_WIDTH) * usize::from(GRAM_HEIGHT)],
            madctl: 0,
            colmod: None,
            inverted: false,
            sleeping: true,
            display_on: false,
            columns: (0, GRAM_WIDTH - 1),
            pages: (0, GRAM_HEIGHT - 1),
            extended,
            counts: Counts::default(),
        }
    }

    /// The counts of everything replayed so far.
    pub fn counts(&self) -> &Counts {
        &self.counts
    }

    /// MADCTL's bits.
    pub fn madctl(&self) -> u8 {
        self.madctl
    }

    /// Clears the counts (the panel keeps its state and memory).
    pub fn reset_counts(&mut self) {
        self.counts = Counts::default();
    }

    /// Awake, on, 16 bits a pixel: what a frame needs.
    pub fn ready(&self) -> bool {
        !self.sleeping && self.display_on && self.colmod.is_some()
    }

    /// Replays `bytes`: each byte with D/C low starts a command, the bytes with D/C high after
    /// it are its parameters (or, after RAMWR, pixel data).
    pub fn replay(&mut self, bytes: &[Byte]) {
        let mut pending: Option<Pending> = None;
        // RAMWR: the position of the next pixel and its first byte if only one came yet.
        let mut write: Option<((u16, u16), Option<u8>)> = None;
        for &Byte { data, value } in bytes {
            if !data {
                if let Some(p) = pending.take() {
                    self.execute(p);
                }
                if let Some((_, half)) = write.take() {
                    assert!(half.is_none(), "RAMWR ended in the middle of a pixel");
                }
                self.counts.command_bytes += 1;
                *self.counts.commands.entry(value).or_default() += 1;
                if value == 0x2C {
                    write = Some(self.start_write());
                } else {
                    pending = Some(Pending {
                        command: value,
                        parameters: Vec::new(),
                    });
                }
            } else if let Some((at, half)) = write.as_mut() {
                self.counts.pixel_bytes += 1;
                match half.take() {
                    None => *half = Some(value),
                    Some(high) => {
                        self.store(*at, u16::from_be_bytes([high, value]));
                        *at = self.next(*at);
                    }
                }
            } else {
                let p = pending
                    .as_mut()
                    .expect("a data byte with no command before it");
                self.counts.parameter_bytes += 1;
                p.parameters.push(value);
            }
        }
        if let Some(p) = pending.take() {
            self.execute(p);
        }
        if let Some((_, half)) = write {
            assert!(half.is_none(), "RAMWR ended in the middle of a pixel");
        }
    }

    /// Applies a command other than RAMWR with its parameters.
    fn execute(
        &mut self,
        Pending {
            command,
            parameters,
        }: Pending,
    ) {
        let expect = |n: usize| {
            assert_eq!(
                parameters.len(),
                n,
                "command {command:#04x} takes {n} parameters"
            )
        };
        let word = |i: usize| u16::from_be_bytes([parameters[i], parameters[i + 1]]);
        match command {
            0x00 => expect(0), // NOP
            0x01 => {
                // SWRESET: the registers to their reset values (the memory is kept).
                expect(0);
                let extended = self.extended;
                let (gram, counts) = (std::mem::take(&mut self.gram), self.counts.clone());
                *self = Self::with_extended(extended);
                self.gram = gram;
                self.counts = counts;
            }
            0x10 | 0x11 => {
                // SLPIN, SLPOUT
                expect(0);
                self.sleeping = command == 0x10;
            }
            0x13 => expect(0), // NORON: normal (not partial) mode
            0x20 | 0x21 => {
                // INVOFF, INVON
                expect(0);
                self.inverted = command == 0x21;
            }
            0x28 | 0x29 => {
                // DISPOFF, DISPON
                expect(0);
                self.display_on = command == 0x29;
            }
            0x2A | 0x2B => {
                // CASET, RASET: start, end; checked against the memory when RAMWR starts.
                expect(4);
                let range = (word(0), word(2));
                assert!(range.0 <= range.1, "{command:#04x}: start after end");
                if command == 0x2A {
                    self.columns = range;
                } else {
                    self.pages = range;
                }
            }
            0x36 => {
                expect(1);
                let bits = parameters[0];
                assert_eq!(
                    bits & (ML | MH | 0x03),
                    0,
                    "MADCTL {bits:#04x}: refresh order bits are not modelled"
                );
                self.madctl = bits;
            }
            0x3A => {
                expect(1);
                // The MCU interface format (low three bits): 0b101, 16 bits a pixel.
                assert_eq!(
                    parameters[0] & 0x07,
                    0x05,
                    "COLMOD {:#04x}: only 16 bits a pixel is modelled",
                    parameters[0]
                );
                self.colmod = Some(parameters[0]);
            }
            _ => match self.extended.iter().find(|&&(c, _)| c == command) {
                Some(&(_, n)) => expect(n),
                None => panic!("command {command:#04x} is not modelled"),
            },
        }
    }

    /// The column and page counts of the address space the host sees: the memory's, exchanged
    /// when MADCTL's MV is set.
    fn address_space(&self) -> (u16, u16) {
        if self.madctl & MV != 0 {
            (GRAM_HEIGHT, GRAM_WIDTH)
        } else {
            (GRAM_WIDTH, GRAM_HEIGHT)
        }
    }

    /// RAMWR: checks the window and the format, and starts at the window's first pixel.
    fn start_write(&mut self) -> ((u16, u16), Option<u8>) {
        assert!(
            self.colmod.is_some(),
            "RAMWR before COLMOD set 16 bits a pixel"
        );
        let (columns, pages) = self.address_space();
        assert!(
            self.columns.1 < columns && self.pages.1 < pages,
            "window {:?} × {:?} outside the {columns} × {pages} address space",
            self.columns,
            self.pages
        );
        ((self.columns.0, self.pages.0), None)
    }

    /// The pixel after `(column, page)`: the next column, at the window's end column the start
    /// column of the next page, after the last page the first again.
    fn next(&self, (column, page): (u16, u16)) -> (u16, u16) {
        if column < self.columns.1 {
            (column + 1, page)
        } else if page < self.pages.1 {
            (self.columns.0, page + 1)
        } else {
            (self.columns.0, self.pages.0)
        }
    }

    /// Where the host's `(column, page)` is in the memory: exchanged (MV), then the memory's
    /// column order (MX) and row order (MY) reversed. (Whether the mirrors act before or after
    /// the exchange does not change what the host reads back through [`Panel::frame`]; it
    /// decides which way a landscape picture is turned, which [`Panel::rotation`] accepts
    /// either way.)
    fn memory_index(&self, (column, page): (u16, u16)) -> usize {
        let (mut x, mut y) = if self.madctl & MV != 0 {
            (page, column)
        } else {
            (column, page)
        };
        if self.madctl & MX != 0 {
            x = GRAM_WIDTH - 1 - x;
        }
        if self.madctl & MY != 0 {
            y = GRAM_HEIGHT - 1 - y;
        }
        usize::from(y) * usize::from(GRAM_WIDTH) + usize::from(x)
    }

    fn store(&mut self, at: (u16, u16), word: u16) {
        let i = self.memory_index(at);
        self.gram[i] = Some(word);
    }

    /// The colour a memory word shows: 5-6-5 with red in the high bits, or blue with MADCTL's
    /// BGR; complemented under INVON. `None` where nothing was written.
    fn shown(&self, word: Option<u16>) -> Option<Rgb565> {
        let mut word = word?;
        if self.inverted {
            word = !word;
        }
        let (first, green, last) = (word >> 11, (word >> 5) & 0x3f, word & 0x1f);
        let (r, b) = if self.madctl & BGR != 0 {
            (last, first)
        } else {
            (first, last)
        };
        Some(Rgb565::new(r as u8, green as u8, b as u8))
    }

    /// The `width` × `height` picture at the host's address `(0, 0)` under the current MADCTL,
    /// row-major; `None` where nothing was written.
    pub fn frame(&self, width: u16, height: u16) -> Vec<Option<Rgb565>> {
        let (columns, pages) = self.address_space();
        assert!(width <= columns && height <= pages);
        (0..height)
            .flat_map(|page| (0..width).map(move |column| (column, page)))
            .map(|at| self.shown(self.gram[self.memory_index(at)]))
            .collect()
    }

    /// The memory as the portrait panel shows it, row-major, 240 wide.
    pub fn portrait(&self) -> Vec<Option<Rgb565>> {
        self.gram.iter().map(|&w| self.shown(w)).collect()
    }

    /// How the memory holds the landscape `frame` (320 × 240, row-major): turned a quarter
    /// clockwise (`Some(90)`) or anticlockwise (`Some(270)`) onto the portrait memory, or
    /// `None` if it is neither (mirrored, transposed, or other pixels).
    pub fn rotation(&self, frame: &[Rgb565]) -> Option<u32> {
        let (w, h) = (usize::from(GRAM_HEIGHT), usize::from(GRAM_WIDTH));
        assert_eq!(frame.len(), w * h);
        let memory = self.portrait();
        let at = |x: usize, y: usize| memory[y * usize::from(GRAM_WIDTH) + x];
        // Clockwise: the frame's top row down the memory's right column.
        let clockwise =
            (0..h).all(|fy| (0..w).all(|fx| at(h - 1 - fy, fx) == Some(frame[fy * w + fx])));
        // Anticlockwise: the frame's top row up the memory's left column.
        let anticlockwise =
            (0..h).all(|fy| (0..w).all(|fx| at(fy, w - 1 - fx) == Some(frame[fy * w + fx])));
        match (clockwise, anticlockwise) {
            (true, false) => Some(90),
            (false, true) => Some(270),
            _ => None,
        }
    }
}

/// The first pixel (x, y) where `got` is not `want` (`width` wide), if any.
pub fn first_difference(
    want: &[Rgb565],
    got: &[Option<Rgb565>],
    width: usize,
) -> Option<(usize, usize)> {
    assert_eq!(want.len(), got.len());
    want.iter()
        .zip(got)
        .position(|(&w, &g)| Some(w) != g)
        .map(|i| (i % width, i / width))
}

/// The big-endian bytes of 5-6-5 pixels as the panel takes them (COLMOD 16 bits, 8-bit serial
/// interface: the high byte first, red in its top five bits).
pub fn panel_bytes(pixels: &[Rgb565], bytes: &mut Vec<u8>) {
    bytes.clear();
    for &p in pixels {
        bytes.extend_from_slice(&RawU16::from(p).into_inner().to_be_bytes());
    }
}
