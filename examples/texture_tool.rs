//! Turns a PNG into a flash texture: Rust source declaring `static` texel arrays and the texel
//! source reading them, for `embedded_raster::texture::Texture::new`.
//!
//! ```text
//! cargo run --release --features png --example texture_tool -- \
//!     <in.png> <out.rs> <NAME> <rgb565|rgb888|gray8|indexed8|indexed4> [WIDTHxHEIGHT]
//! ```
//!
//! * `in.png`: any PNG (grey, grey + alpha, RGB, RGBA or indexed, 1 to 16 bits); alpha is
//!   dropped, each pixel keeping its stored colour.
//! * `out.rs`: the file to write (replaced). Include it in firmware as a module
//!   (`#[path = "out.rs"] mod texture;`); it names the crate `embedded_raster` and, for the
//!   palette formats, `embedded_graphics::pixelcolor::Rgb565`.
//! * `NAME`: the statics' prefix, a Rust identifier (`LOGO` gives `LOGO`, `LOGO_WIDTH`,
//!   `LOGO_HEIGHT` and `LOGO_TEXELS`, or `LOGO_INDICES` and `LOGO_PALETTE`).
//! * The format: raw Rgb565 words (2 bytes a texel), Rgb888 bytes (3), Gray8 luma (1), or an
//!   Rgb565 palette of up to 256 colours with a byte a texel (`indexed8`) or of up to 16 with
//!   half a byte (`indexed4`); the palette is exact for images with that few colours, else a
//!   median cut.
//! * `WIDTHxHEIGHT` (optional): resize first — area-average when shrinking, nearest when
//!   growing.
//!
//! It reports the sizes, the distinct colours, the quantisation error of the palette formats and
//! the flash the texture takes. The spot texture of the examples was made with
//!
//! ```text
//! cargo run --release --features png --example texture_tool -- \
//!     examples/common/textures/spot_texture.png examples/common/textures/spot_texture.rs \
//!     SPOT_TEXTURE indexed4 256x256
//! ```
//!
//! (`tests/all/texture_convert.rs` checks the file is what this gives).

use std::path::Path;
use std::process::ExitCode;

use embedded_graphics::pixelcolor::{Rgb565, Rgb888, RgbColor};
use embedded_raster::texture::convert::{read_png, Palette, TexelFormat};
use embedded_raster::texture::MAX_SIZE;

const USAGE: &str = "usage: texture_tool <in.png> <out.rs> <NAME> \
                     <rgb565|rgb888|gray8|indexed8|indexed4> [WIDTHxHEIGHT]";

/// `WIDTHxHEIGHT`, each 1 to `MAX_SIZE`.
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let bad = || format!("`{s}` is not a size WIDTHxHEIGHT, each 1 to {MAX_SIZE}");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let side = |v: &str| {
        v.parse::<u32>()
            .ok()
            .filter(|v| (1..=MAX_SIZE).contains(v))
            .ok_or_else(bad)
    };
    Ok((side(w)?, side(h)?))
}

/// Whether `name` is a Rust identifier (ASCII).
fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && name != "_"
}

fn run(args: &[String]) -> Result<(), String> {
    let (input, output, name, format, size) = match args {
        [i, o, n, f] => (i, o, n, f, None),
        [i, o, n, f, s] => (i, o, n, f, Some(s)),
        _ => return Err(USAGE.to_owned()),
    };
    if !is_identifier(name) {
        return Err(format!("`{name}` is not a Rust identifier\n{USAGE}"));
    }
    let format: TexelFormat = format.parse().map_err(|e| format!("{e}\n{USAGE}"))?;
    let size = size.map(|s| parse_size(s)).transpose()?;

    let image = read_png(input).map_err(|e| format!("{input}: {e}"))?;
    let (w0, h0) = (image.width, image.height);
    let file_name = Path::new(input)
        .file_name()
        .map_or(input.clone(), |f| f.to_string_lossy().into_owned());
    let mut origin = format!("From `{file_name}` ({w0} × {h0})");
    let image = match size {
        Some((w, h)) if (w, h) != (w0, h0) => {
            let how = if w <= w0 && h <= h0 {
                "box-filtered"
            } else {
                "resized"
            };
            origin += &format!(", {how} to {w} × {h}");
            image.resized(w, h)
        }
        _ => image,
    };
    origin += ".";
    if image.width > MAX_SIZE || image.height > MAX_SIZE {
        return Err(format!(
            "{input} is {w0} × {h0}: a texture is at most {MAX_SIZE} on a side (resize it)"
        ));
    }
    eprintln!("{input}: {w0} × {h0}");
    if (image.width, image.height) != (w0, h0) {
        eprintln!("resized to {} × {}", image.width, image.height);
    }
    eprintln!("{} distinct colours", image.histogram().len());

    let mut flash = format.texel_bytes(image.len());
    if let Some(k) = format.palette_size() {
        let palette = image.palette(k);
        let e = palette.error(&image);
        eprintln!(
            "{}-colour palette: RMS error {:.2}, largest {:.1} (8-bit levels)",
            palette.colors.len(),
            e.rms,
            e.max
        );
        // The palette as firmware reads it: each colour through Rgb565.
        let rgb565 = Palette {
            colors: palette
                .rgb565()
                .into_iter()
                .map(|c: Rgb565| {
                    let c = Rgb888::from(c);
                    [c.r(), c.g(), c.b()]
                })
                .collect(),
            indices: palette.indices.clone(),
        };
        let e = rgb565.error(&image);
        eprintln!("in Rgb565: RMS error {:.2}, largest {:.1}", e.rms, e.max);
        flash += 2 * palette.colors.len();
    }
    let source = image.to_rust_source_from(name, format, "embedded_raster", &origin);
    std::fs::write(output, &source).map_err(|e| format!("{output}: {e}"))?;
    eprintln!("{output}: {format}, {flash} bytes of flash");
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("texture_tool: {e}");
            ExitCode::FAILURE
        }
    }
}
