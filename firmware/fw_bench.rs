//! Firmware benchmark: instructions per covered pixel and per triangle, counted by SysTick (or
//! RISC-V's `minstret`) under
//! QEMU's `-icount` (every executed instruction advances the virtual clock by exactly 1 ns, so the
//! counts are deterministic), plus the stack depth of each draw call.
//!
//! ```text
//! cargo run --release --target thumbv7em-none-eabihf --example fw_bench   # mps2-an386
//! cargo run --release --target thumbv7m-none-eabi    --example fw_bench   # mps2-an385
//! cargo run --release --target thumbv6m-none-eabi    --example fw_bench   # micro:bit
//! ```
//!
//! Instructions are counted by SysTick or `minstret` (`firmware/common/clock.rs`). Each case draws a set of
//! triangles into a `SliceFramebuffer<Rgb565>`, repeated so that it runs for at least ~10⁵
//! instructions; the covered pixels are counted exactly in a separate, untimed pass through a counting draw target.
//! Vertices sit on pixel centres, so embedded-graphics' integer `Triangle` (filled with
//! `PrimitiveStyle`) gets the same triangles; it covers a few more pixels (it includes every
//! edge), which is why every row reports its own pixel count.
//!
//! The host build prints the cases and their pixel counts only.
#![cfg_attr(target_os = "none", no_std, no_main)]

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_graphics::primitives::{PrimitiveStyle, Triangle};
use embedded_raster::paint::{LinearGradient, RadialGradient, Stop, STOP_ONE};
use embedded_raster::{Coord, GouraudTriangle, PaintedTriangle, Polygon, SolidTriangle, Vertex};

#[allow(dead_code)]
#[path = "../examples/common/scene.rs"]
mod scene;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[path = "common/report_panic.rs"]
mod report_panic;

#[cfg(target_os = "none")]
#[path = "common/clock.rs"]
mod clock;

/// Most triangles in one set.
const MAX_SET: usize = 32;

/// A benchmark triangle: corners on pixel centres (pixel indices) and three colours.
#[derive(Debug, Clone, Copy)]
struct BenchTriangle {
    corners: [(i32, i32); 3],
    colors: [Rgb565; 3],
}

impl BenchTriangle {
    fn gouraud(&self) -> GouraudTriangle<Rgb565> {
        let centre = |i: i32| Coord::from_bits(i * 256 + 128);
        GouraudTriangle::new([0, 1, 2].map(|k| {
            let (x, y) = self.corners[k];
            Vertex::new(centre(x), centre(y), self.colors[k])
        }))
    }

    fn solid(&self) -> SolidTriangle<Rgb565> {
        let centre = |i: i32| Coord::from_bits(i * 256 + 128);
        SolidTriangle::new(
            self.corners.map(|(x, y)| (centre(x), centre(y))),
            self.colors[0],
        )
    }

    /// The solid triangle as a polygon: the same pixels, through the polygon's scan.
    fn polygon(&self) -> Polygon<3> {
        let mut polygon = Polygon::new();
        // Three vertices fit three slots.
        let _ = polygon.add_contour(&self.solid().points);
        polygon
    }

    fn painted<P: embedded_raster::Paint<Color = Rgb565> + Copy>(
        &self,
        paint: &P,
    ) -> PaintedTriangle<P> {
        let centre = |i: i32| Coord::from_bits(i * 256 + 128);
        PaintedTriangle::new(self.corners.map(|(x, y)| (centre(x), centre(y))), *paint)
    }

    fn eg(&self) -> Triangle {
        let [a, b, c] = self.corners.map(|(x, y)| Point::new(x, y));
        Triangle::new(a, b, c)
    }
}

/// A named set of triangles.
struct Set {
    name: &'static str,
    triangles: [BenchTriangle; MAX_SET],
    len: usize,
    /// Repetitions per measurement.
    reps: u32,
}

impl Set {
    fn triangles(&self) -> &[BenchTriangle] {
        self.triangles.get(..self.len).unwrap_or(&[])
    }
}

fn palette(k: usize) -> [Rgb565; 3] {
    let k = k as u8;
    [
        Rgb565::new(k.wrapping_mul(7) & 31, 63 - (k & 31), 5),
        Rgb565::new(31, k.wrapping_mul(11) & 63, 31 - (k & 15)),
        Rgb565::new(k & 31, 20, k.wrapping_mul(3) & 31),
    ]
}

/// Number of triangle sets.
const SETS: usize = 5;

/// Triangle set `index` (large, small, tiny, huge, medium) for a `w × h` screen. Sets are built one at a
/// time: all three would not fit the micro:bit's stack next to its framebuffer.
fn make_set(index: usize, w: i32, h: i32) -> Set {
    let mut set = Set {
        name: "",
        triangles: [BenchTriangle {
            corners: [(0, 0); 3],
            colors: [Rgb565::BLACK; 3],
        }; MAX_SET],
        len: MAX_SET,
        reps: 0,
    };
    match index {
        0 => {
            let corners = scene::large_triangles(w, h);
            (set.name, set.len, set.reps) = ("large", corners.len(), 4);
            for (k, (t, c)) in set.triangles.iter_mut().zip(corners).enumerate() {
                t.corners = c;
                t.colors = palette(k);
            }
        }
        3 => {
            // Vertices thousands of pixels apart (the general set-up, `i64` edge values and
            // exactly rounded planes), each crossing the screen: what they cost beyond their
            // pixels is that set-up.
            (set.name, set.len, set.reps) = ("huge", 4, 4);
            let corners = [
                [(-3000, -40), (w + 2500, h / 3), (w / 2, h + 2900)],
                [(w / 3, -2600), (w + 3100, h + 50), (-2700, h * 2 / 3)],
                [(-5000, h / 2), (w / 2, -4000), (w + 20, h - 3)],
                [(w + 4000, h / 4), (-1, h * 3 / 4), (w / 4, h + 6000)],
            ];
            for (k, (t, c)) in set.triangles.iter_mut().zip(corners).enumerate() {
                t.corners = c;
                t.colors = palette(k);
            }
        }
        4 => {
            // 1,000 px² each (a 44 × 46 box), four orientations, in the screen's corners (they
            // overlap on the micro:bit's 64 × 48).
            (set.name, set.len, set.reps) = ("medium", 4, 2);
            let shapes = [
                [(0, 0), (44, 4), (6, 46)],
                [(44, 0), (40, 46), (0, 6)],
                [(0, 46), (44, 42), (6, 0)],
                [(44, 46), (0, 42), (38, 0)],
            ];
            for (k, t) in set.triangles.iter_mut().take(4).enumerate() {
                let (x, y) = ((k % 2) as i32 * (w - 45), (k / 2) as i32 * (h - 47));
                t.corners = shapes[k].map(|(dx, dy)| (x + dx, y + dy));
                t.colors = palette(k);
            }
        }
        _ => {
            let shapes = if index == 1 {
                // About 16 px² each (areas 14.5 to 17.5), four orientations.
                (set.name, set.reps) = ("small", 8);
                [
                    [(0, 0), (6, 1), (1, 5)],
                    [(5, 0), (6, 6), (0, 3)],
                    [(0, 5), (3, 0), (6, 4)],
                    [(1, 1), (6, 5), (0, 6)],
                ]
            } else {
                // Half-pixel² triangles between neighbouring pixel centres: 0 or 1 pixel each.
                (set.name, set.reps) = ("tiny", 16);
                [
                    [(0, 0), (1, 0), (0, 1)],
                    [(1, 0), (1, 1), (0, 1)],
                    [(0, 0), (1, 1), (0, 1)],
                    [(0, 0), (1, 0), (1, 1)],
                ]
            };
            // Spread over an 8 × 4 grid of the screen.
            for (k, t) in set.triangles.iter_mut().enumerate() {
                let (x, y) = ((k % 8) as i32 * w / 8, (k / 8) as i32 * h / 4);
                t.corners = shapes[k % 4].map(|(dx, dy)| (x + dx, y + dy));
                t.colors = palette(k);
            }
        }
    }
    set
}

/// The renderers compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Renderer {
    SolidDraw,
    SolidDrawInto,
    GouraudDraw,
    GouraudDrawInto,
    /// `GouraudTriangle::dithered().draw_into`: ordered dithering to Rgb565.
    GouraudDitheredDrawInto,
    /// `SolidTriangle::with_opacity(OPACITY).draw_into`: a constant colour blended.
    OpacityDrawInto,
    /// `GouraudTriangle::with_alpha(ALPHAS).draw_into`: an alpha per vertex.
    AlphaDrawInto,
    /// `SolidTriangle::anti_aliased().draw_into`: edges blended with their exact coverage.
    AntiAliasedDrawInto,
    /// `Polygon::filled(color).draw` and `draw_into` of the triangle's three corners.
    PolygonDraw,
    PolygonDrawInto,
    /// `PaintedTriangle::draw_into` with a linear gradient of three stops across the screen.
    LinearDrawInto,
    /// The same gradient dithered.
    LinearDitheredDrawInto,
    /// `PaintedTriangle::draw_into` with a radial gradient of three stops.
    RadialDrawInto,
    /// The same gradient dithered.
    RadialDitheredDrawInto,
    EgTriangle,
}

const RENDERERS: [Renderer; 15] = [
    Renderer::SolidDraw,
    Renderer::SolidDrawInto,
    Renderer::GouraudDraw,
    Renderer::GouraudDrawInto,
    Renderer::GouraudDitheredDrawInto,
    Renderer::OpacityDrawInto,
    Renderer::AlphaDrawInto,
    Renderer::AntiAliasedDrawInto,
    Renderer::PolygonDraw,
    Renderer::PolygonDrawInto,
    Renderer::LinearDrawInto,
    Renderer::LinearDitheredDrawInto,
    Renderer::RadialDrawInto,
    Renderer::RadialDitheredDrawInto,
    Renderer::EgTriangle,
];

/// The gradients of the painted renderers, made once for a screen (their set-up divides).
struct Paints {
    linear: LinearGradient<Rgb565, 3>,
    radial: RadialGradient<Rgb565, 3>,
}

impl Paints {
    /// A diagonal gradient across the `w × h` screen and a radial one around a point left of its
    /// centre out to its width, each through red, green and blue.
    fn new(w: i32, h: i32) -> Self {
        let stops = [
            Stop::new(0, Rgb565::new(31, 8, 2)),
            Stop::new(STOP_ONE * 2 / 5, Rgb565::new(3, 60, 9)),
            Stop::new(STOP_ONE, Rgb565::new(1, 12, 30)),
        ];
        let at = |x: i32, y: i32| (Coord::from_bits(x * 256), Coord::from_bits(y * 256));
        Paints {
            linear: LinearGradient::new(at(0, 0), at(w, h), stops),
            radial: RadialGradient::new(at(w * 2 / 5, h / 2), Coord::from_bits(w * 256), stops),
        }
    }
}

/// The translucent renderers' opacity and alphas per vertex.
const OPACITY: u8 = 160;
const ALPHAS: [u8; 3] = [255, 96, 160];

impl Renderer {
    fn name(self) -> &'static str {
        match self {
            Renderer::SolidDraw => "SolidTriangle::draw",
            Renderer::SolidDrawInto => "SolidTriangle::draw_into",
            Renderer::GouraudDraw => "GouraudTriangle::draw",
            Renderer::GouraudDrawInto => "GouraudTriangle::draw_into",
            Renderer::GouraudDitheredDrawInto => "GouraudTriangle::dithered draw_into",
            Renderer::OpacityDrawInto => "SolidTriangle::with_opacity draw_into",
            Renderer::AlphaDrawInto => "GouraudTriangle::with_alpha draw_into",
            Renderer::AntiAliasedDrawInto => "SolidTriangle::anti_aliased draw_into",
            Renderer::PolygonDraw => "Polygon::filled draw",
            Renderer::PolygonDrawInto => "Polygon::filled draw_into",
            Renderer::LinearDrawInto => "PaintedTriangle linear draw_into",
            Renderer::LinearDitheredDrawInto => "PaintedTriangle linear dithered draw_into",
            Renderer::RadialDrawInto => "PaintedTriangle radial draw_into",
            Renderer::RadialDitheredDrawInto => "PaintedTriangle radial dithered draw_into",
            Renderer::EgTriangle => "e-g Triangle (fill)",
        }
    }

    /// Draws `t` through any draw target (`draw_into` needs a `SliceFramebuffer`; elsewhere it
    /// falls back to `draw`, which covers the same pixels).
    fn draw_generic<D: DrawTarget<Color = Rgb565>>(
        self,
        t: &BenchTriangle,
        paints: &Paints,
        target: &mut D,
    ) {
        let _ = match self {
            Renderer::SolidDraw | Renderer::SolidDrawInto => t.solid().draw(target),
            Renderer::GouraudDraw | Renderer::GouraudDrawInto => t.gouraud().draw(target),
            Renderer::GouraudDitheredDrawInto => t.gouraud().dithered().draw(target),
            Renderer::OpacityDrawInto => t
                .solid()
                .with_opacity(OPACITY)
                .over(Rgb565::BLACK)
                .draw(target),
            Renderer::AlphaDrawInto => t
                .gouraud()
                .with_alpha(ALPHAS)
                .over(Rgb565::BLACK)
                .draw(target),
            Renderer::AntiAliasedDrawInto => {
                t.solid().anti_aliased().over(Rgb565::BLACK).draw(target)
            }
            Renderer::PolygonDraw | Renderer::PolygonDrawInto => {
                t.polygon().filled(t.colors[0]).draw(target)
            }
            Renderer::LinearDrawInto => t.painted(&paints.linear).draw(target),
            Renderer::LinearDitheredDrawInto => t.painted(&paints.linear.dithered()).draw(target),
            Renderer::RadialDrawInto => t.painted(&paints.radial).draw(target),
            Renderer::RadialDitheredDrawInto => t.painted(&paints.radial.dithered()).draw(target),
            Renderer::EgTriangle => t
                .eg()
                .into_styled(PrimitiveStyle::with_fill(t.colors[0]))
                .draw(target),
        };
    }
}

/// A draw target that only counts the pixels it receives inside its bounds.
struct Counter {
    size: Size,
    pixels: u32,
}

impl OriginDimensions for Counter {
    fn size(&self) -> Size {
        self.size
    }
}

impl DrawTarget for Counter {
    type Color = Rgb565;
    type Error = core::convert::Infallible;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(
        &mut self,
        pixels: I,
    ) -> Result<(), Self::Error> {
        let bounds = self.bounding_box();
        for Pixel(p, _) in pixels {
            self.pixels += u32::from(bounds.contains(p));
        }
        Ok(())
    }
}

/// Covered pixels of one pass over `set` (untimed). Not inlined: keeps the counting draws' stack
/// frames out of the benchmark loop's.
#[inline(never)]
fn count_pixels(renderer: Renderer, set: &Set, paints: &Paints, (w, h): (u32, u32)) -> u32 {
    let mut counter = Counter {
        size: Size::new(w, h),
        pixels: 0,
    };
    for t in set.triangles() {
        renderer.draw_generic(t, paints, &mut counter);
    }
    counter.pixels
}

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;

    use crate::board::entry;
    use crate::board::hprintln;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::PrimitiveStyle;
    use embedded_raster::SliceFramebuffer;

    use super::*;
    use crate::clock::{calibrate, measure, Ratio};
    use crate::{board, clock, scene};

    fn run(renderer: Renderer, set: &Set, paints: &Paints, fb: &mut SliceFramebuffer<'_, Rgb565>) {
        let (set, paints) = (black_box(set), black_box(paints));
        match renderer {
            Renderer::SolidDraw => {
                for t in set.triangles() {
                    let _ = t.solid().draw(fb);
                }
            }
            Renderer::SolidDrawInto => {
                for t in set.triangles() {
                    t.solid().draw_into(fb);
                }
            }
            Renderer::GouraudDraw => {
                for t in set.triangles() {
                    let _ = t.gouraud().draw(fb);
                }
            }
            Renderer::GouraudDrawInto => {
                for t in set.triangles() {
                    t.gouraud().draw_into(fb);
                }
            }
            Renderer::GouraudDitheredDrawInto => {
                for t in set.triangles() {
                    t.gouraud().dithered().draw_into(fb);
                }
            }
            Renderer::OpacityDrawInto => {
                for t in set.triangles() {
                    t.solid().with_opacity(OPACITY).draw_into(fb);
                }
            }
            Renderer::AlphaDrawInto => {
                for t in set.triangles() {
                    t.gouraud().with_alpha(ALPHAS).draw_into(fb);
                }
            }
            Renderer::AntiAliasedDrawInto => {
                for t in set.triangles() {
                    t.solid().anti_aliased().draw_into(fb);
                }
            }
            Renderer::PolygonDraw => {
                for t in set.triangles() {
                    let _ = t.polygon().filled(t.colors[0]).draw(fb);
                }
            }
            Renderer::PolygonDrawInto => {
                for t in set.triangles() {
                    t.polygon().filled(t.colors[0]).draw_into(fb);
                }
            }
            Renderer::LinearDrawInto => {
                for t in set.triangles() {
                    t.painted(&paints.linear).draw_into(fb);
                }
            }
            Renderer::LinearDitheredDrawInto => {
                let paint = paints.linear.dithered();
                for t in set.triangles() {
                    t.painted(&paint).draw_into(fb);
                }
            }
            Renderer::RadialDrawInto => {
                for t in set.triangles() {
                    t.painted(&paints.radial).draw_into(fb);
                }
            }
            Renderer::RadialDitheredDrawInto => {
                let paint = paints.radial.dithered();
                for t in set.triangles() {
                    t.painted(&paint).draw_into(fb);
                }
            }
            Renderer::EgTriangle => {
                for t in set.triangles() {
                    let _ = t
                        .eg()
                        .into_styled(PrimitiveStyle::with_fill(t.colors[0]))
                        .draw(fb);
                }
            }
        }
    }

    /// Measures every renderer on triangle set `index`, prints a table row for each and returns
    /// the totals over all passes: (instructions, pixels, triangles). Not inlined, so the set
    /// lives on the stack only while it is measured.
    #[inline(never)]
    fn bench_set(
        index: usize,
        fb: &mut SliceFramebuffer<'_, Rgb565>,
        (cal_instructions, cal_ticks): (u64, u64),
    ) -> [(u32, u32, u32); RENDERERS.len()] {
        let size = fb.size();
        let set = &make_set(index, size.width as i32, size.height as i32);
        let paints = &Paints::new(size.width as i32, size.height as i32);
        let mut totals = [(0, 0, 0); RENDERERS.len()];
        for (total, &renderer) in totals.iter_mut().zip(&RENDERERS) {
            if renderer == Renderer::EgTriangle && set.name == "huge" {
                // It tests every pixel of the bounding box: 10⁸ instructions a triangle here.
                hprintln!("| {} | {} | – | – | – | – | – |", renderer.name(), set.name);
                continue;
            }
            let pixels = count_pixels(renderer, set, paints, (size.width, size.height));
            run(renderer, set, paints, fb); // warm-up, untimed
            let ticks = measure(set.reps, || run(renderer, set, paints, fb));
            let instructions = clock::instructions(ticks, (cal_instructions, cal_ticks));
            let passes = u64::from(set.reps);
            let n = set.triangles().len() as u64;
            hprintln!(
                "| {} | {} | {} | {} | {} | {} | {} |",
                renderer.name(),
                set.name,
                n,
                pixels,
                (instructions + passes / 2) / passes,
                Ratio(instructions, u64::from(pixels) * passes),
                Ratio(instructions, n * passes)
            );
            // 32 bits a figure (saturated; a set's passes stay far below): with fourteen
            // renderers and five sets, the micro:bit's stack has no room for 64.
            let narrow = |v: u64| u32::try_from(v).unwrap_or(u32::MAX);
            *total = (
                narrow(instructions),
                narrow(u64::from(pixels) * passes),
                narrow(n * passes),
            );
        }
        totals
    }

    // ---- stack depth -------------------------------------------------------------------------

    extern "C" {
        /// Lowest address the stack may reach (end of .bss/.uninit, the heap's start), from the
        /// runtime's link.x (cortex-m-rt's or riscv-rt's).
        static __sheap: u32;
        /// Initial stack pointer (top of RAM), from the runtime's link.x.
        static _stack_start: u32;
    }

    const PAINT: u32 = 0x5A5A_A5A5;
    /// Bytes below the current stack pointer that are painted and scanned per draw call.
    const WINDOW: usize = 6 * 1024;

    /// Lowest stack address to paint and scan: `window` bytes below `sp`, at most down to the
    /// end of the stack.
    fn stack_floor(sp: usize, window: usize) -> usize {
        let end = core::ptr::addr_of!(__sheap) as usize;
        end.max(sp.saturating_sub(window))
    }

    /// Bytes just below the stack pointer left unpainted: the compiler may read the stack
    /// pointer before this function's own prologue pushes (shrink-wrapping).
    const MARGIN: usize = 64;

    /// Paints up to `window` bytes of free stack below the caller's stack pointer.
    #[inline(never)]
    fn paint_below_sp(window: usize) {
        let sp = board::stack_pointer();
        let top = sp - MARGIN;
        let mut p = stack_floor(sp, window);
        while p + 4 <= top {
            // SAFETY: free stack between the stack's lower bound and the current stack pointer.
            unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
            p += 4;
        }
    }

    /// The lowest address at or above `floor` and below `sp` that no longer holds the paint.
    fn lowest_touched(floor: usize, sp: usize) -> usize {
        let mut p = floor;
        // SAFETY: reads of the painted region.
        while p < sp && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
            p += 4;
        }
        p
    }

    /// Bytes of stack used by `f(fb, t)` below the caller's stack pointer (`None` if it used the
    /// whole scanned window).
    #[inline(never)]
    fn stack_depth(
        f: DrawCall,
        fb: &mut SliceFramebuffer<'_, Rgb565>,
        shape: &scene::Shape,
    ) -> Option<usize> {
        paint_below_sp(WINDOW);
        let sp = board::stack_pointer();
        black_box(f)(fb, shape);
        let floor = stack_floor(sp, WINDOW);
        let p = lowest_touched(floor, sp);
        (p > floor).then_some(sp - p)
    }

    fn gouraud_of(shape: &scene::Shape) -> embedded_raster::GouraudTriangle<Rgb565> {
        match *shape {
            scene::Shape::Gouraud(t) => t,
            scene::Shape::Solid(t) => embedded_raster::GouraudTriangle::new(
                t.points
                    .map(|(x, y)| embedded_raster::Vertex::new(x, y, t.color)),
            ),
        }
    }

    fn solid_of(shape: &scene::Shape) -> embedded_raster::SolidTriangle<Rgb565> {
        match *shape {
            scene::Shape::Gouraud(t) => embedded_raster::SolidTriangle::new(
                t.vertices.map(|v| v.position()),
                t.vertices[0].color,
            ),
            scene::Shape::Solid(t) => t,
        }
    }

    /// A draw call whose stack depth is measured.
    type DrawCall = fn(&mut SliceFramebuffer<'_, Rgb565>, &scene::Shape);

    const STACK_CASES: [(&str, DrawCall); 4] = [
        ("SolidTriangle::draw", |fb, s| {
            let _ = solid_of(s).draw(fb);
        }),
        ("SolidTriangle::draw_into", |fb, s| {
            solid_of(s).draw_into(fb)
        }),
        ("GouraudTriangle::draw", |fb, s| {
            let _ = gouraud_of(s).draw(fb);
        }),
        ("GouraudTriangle::draw_into", |fb, s| {
            gouraud_of(s).draw_into(fb)
        }),
    ];

    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::new(0, 0, 0); board::PIXELS];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the static's only reference.
        let pixels = unsafe { &mut *core::ptr::addr_of_mut!(PIXELS) };
        let (width, height) = board::SIZE;
        let mut fb = SliceFramebuffer::new(pixels, width, height).expect("framebuffer size");
        // Paint all free stack now; at the end, the deepest point the benchmark reached shows,
        // and touching the end of the stack (running into .bss) fails the run.
        paint_below_sp(usize::MAX);
        let main_sp = board::stack_pointer();
        clock::start();

        let (cal_instructions, cal_ticks) = calibrate();

        hprintln!("### {}\n", board::name());
        hprintln!(
            "Framebuffer {}×{} Rgb565 (`SliceFramebuffer`); {} {} instructions/tick \
             (calibrated); QEMU `-icount shift=0`.\n",
            width,
            height,
            clock::SOURCE,
            Ratio(cal_instructions, cal_ticks)
        );
        hprintln!(
            "| renderer | set | triangles | pixels | instructions per pass | instr/pixel | instr/triangle |"
        );
        hprintln!("|---|---|---:|---:|---:|---:|---:|");
        // Totals over all passes per set and renderer: (instructions, pixels, triangles).
        let mut totals = [[(0u32, 0u32, 0u32); RENDERERS.len()]; SETS];
        for (index, row) in totals.iter_mut().enumerate() {
            *row = bench_set(index, &mut fb, (cal_instructions, cal_ticks));
        }
        let [large, small, tiny, huge, medium] = &totals;
        hprintln!(
            "\n| renderer | instr/pixel, large | instr/pixel, small (16 px²) | setup: instr/triangle, \
             tiny (0–1 px) | setup: small minus large per-pixel | instr/triangle, huge (general \
             set-up) | instr/pixel, medium (1,000 px²) |"
        );
        hprintln!("|---|---:|---:|---:|---:|---:|---:|");
        for (r, &renderer) in RENDERERS.iter().enumerate() {
            let wide = |(a, b, c): (u32, u32, u32)| (u64::from(a), u64::from(b), u64::from(c));
            let (lt, lp, _) = wide(large[r]);
            let (st, sp, sn) = wide(small[r]);
            // Small-set instructions not explained by the large-set per-pixel rate.
            let explained = (sp * lt).checked_div(lp).unwrap_or(0);
            let (ht, _, hn) = wide(huge[r]);
            hprintln!(
                "| {} | {} | {} | {} | {} | {} | {} |",
                renderer.name(),
                Ratio(lt, lp),
                Ratio(st, sp),
                Ratio(wide(tiny[r]).0, wide(tiny[r]).2),
                Ratio(st.saturating_sub(explained), sn),
                Ratio(ht, hn),
                Ratio(wide(medium[r]).0, wide(medium[r]).1)
            );
        }

        // Stack depth of one draw call, worst case over every shape of the test scene (including
        // vertices at the ends of the Coord range). SysTick is off so its frames don't count.
        clock::stop();
        hprintln!(
            "\n| draw call | max stack, bytes (over the {} scene triangles) |",
            {
                let mut n = 0;
                scene::for_each_shape(width, height, |_| n += 1);
                n
            }
        );
        hprintln!("|---|---:|");
        for (name, f) in STACK_CASES {
            let mut worst = Some(0);
            scene::for_each_shape(width, height, |shape| {
                worst = match (worst, stack_depth(f, &mut fb, &shape)) {
                    (Some(a), Some(b)) => Some(a.max(b)),
                    _ => None,
                };
            });
            match worst {
                Some(bytes) => hprintln!("| {} | {} |", name, bytes),
                None => hprintln!("| {} | > {} |", name, WINDOW),
            }
        }
        let end = core::ptr::addr_of!(__sheap) as usize;
        let stack_top = core::ptr::addr_of!(_stack_start) as usize;
        let deepest = lowest_touched(end, main_sp);
        hprintln!(
            "\nDeepest stack use of this benchmark firmware: {} of {} bytes.\n",
            stack_top - deepest,
            stack_top - end
        );
        // The word at the end of the stack was painted; if it changed, the stack overflowed.
        board::exit(deepest > end)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    // The host has no instruction counter: list the cases and their exact pixel counts.
    for (width, height) in scene::SIZES {
        println!("{width}×{height}:");
        for index in 0..SETS {
            let set = make_set(index, width as i32, height as i32);
            let paints = Paints::new(width as i32, height as i32);
            for renderer in RENDERERS {
                let pixels = count_pixels(renderer, &set, &paints, (width, height));
                println!(
                    "  {:<28} {:<6} {:>3} triangles {:>6} pixels ({:.2} px/triangle), {} passes in firmware",
                    renderer.name(),
                    set.name,
                    set.triangles().len(),
                    pixels,
                    f64::from(pixels) / set.triangles().len() as f64,
                    set.reps
                );
            }
        }
    }
}
