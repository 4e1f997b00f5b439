//! The host texture converter (`texture::convert`, feature `png`): PNG decoding of every colour
//! type and depth, the box filter, palette reduction, the flash emitter (its text parsed back
//! and read through the crate's texel sources) and the generated spot texture.
//!
//! `examples/common/textures/spot_texture.rs` must be what the converter makes of
//! `spot_texture.png` (compared ignoring whitespace and trailing commas, like the flash meshes).
//! Set `REGENERATE_TEXTURES=1` to rewrite it after changing the converter.

use embedded_graphics::pixelcolor::{Rgb565, Rgb888};
use embedded_raster::texture::convert::{
    read_png, ConvertError, Palette, TexelFormat, TextureData,
};
use embedded_raster::texture::{
    Gray8Texels, Indexed4, Indexed8, Rgb565Texels, Rgb888Texels, TexelSource, Texture,
};
use png::{BitDepth, ColorType};

#[path = "../../examples/common/textures/spot_texture.rs"]
mod spot_texture;

/// A PNG of `data` (rows packed as PNG packs them), with an optional palette and `tRNS`.
fn encode(
    (width, height): (u32, u32),
    color: ColorType,
    depth: BitDepth,
    data: &[u8],
    palette: Option<&[u8]>,
    trns: Option<&[u8]>,
) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    if let Some(p) = palette {
        encoder.set_palette(p.to_vec());
    }
    if let Some(t) = trns {
        encoder.set_trns(t.to_vec());
    }
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(data).unwrap();
    writer.finish().unwrap();
    out
}

fn image(width: u32, height: u32, pixels: Vec<[u8; 3]>) -> TextureData {
    assert_eq!(pixels.len(), (width * height) as usize);
    TextureData {
        width,
        height,
        pixels,
    }
}

fn decoded(png: &[u8]) -> Vec<[u8; 3]> {
    let data = TextureData::from_png(png).unwrap();
    assert_eq!(data.pixels.len(), (data.width * data.height) as usize);
    data.pixels
}

fn grey(levels: &[u8]) -> Vec<[u8; 3]> {
    levels.iter().map(|&l| [l; 3]).collect()
}

#[test]
fn decodes_grey_at_every_depth() {
    use BitDepth::*;
    let g = ColorType::Grayscale;
    // 3 × 2; rows start on a byte.
    let one = encode((3, 2), g, One, &[0b1010_0000, 0b0110_0000], None, None);
    assert_eq!(decoded(&one), grey(&[255, 0, 255, 0, 255, 255]));
    let two = encode((3, 2), g, Two, &[0b0001_1000, 0b1110_0100], None, None);
    assert_eq!(decoded(&two), grey(&[0, 85, 170, 255, 170, 85]));
    let four = encode((3, 2), g, Four, &[0x07, 0xf0, 0x1e, 0x80], None, None);
    assert_eq!(decoded(&four), grey(&[0, 119, 255, 17, 238, 136]));
    let eight = encode((3, 2), g, Eight, &[0, 1, 127, 128, 254, 255], None, None);
    assert_eq!(decoded(&eight), grey(&[0, 1, 127, 128, 254, 255]));
    // 16 bits: the nearest 8-bit level of v / 257.
    #[rustfmt::skip]
    let sixteen = [
        0x00, 0x00, 0x00, 0x80, 0x00, 0x81, // 0, 128/257 → 0, 129/257 → 1
        0x80, 0x80, 0x12, 0x34, 0xff, 0xff, // 128, 4660/257 = 18.1, 255
    ];
    let sixteen = encode((3, 2), g, Sixteen, &sixteen, None, None);
    assert_eq!(decoded(&sixteen), grey(&[0, 0, 1, 128, 18, 255]));
    // A tRNS grey level is alpha, dropped.
    let trns = encode((3, 1), g, Eight, &[10, 20, 30], None, Some(&[0, 20]));
    assert_eq!(decoded(&trns), grey(&[10, 20, 30]));
}

#[test]
fn decodes_grey_alpha_rgb_and_rgba_dropping_alpha() {
    use BitDepth::*;
    let ga = encode(
        (2, 1),
        ColorType::GrayscaleAlpha,
        Eight,
        &[7, 0, 200, 255],
        None,
        None,
    );
    assert_eq!(decoded(&ga), grey(&[7, 200]));
    let ga16 = [0xff, 0x00, 0x00, 0x00, 0x40, 0x00, 0xff, 0xff];
    let ga16 = encode(
        (2, 1),
        ColorType::GrayscaleAlpha,
        Sixteen,
        &ga16,
        None,
        None,
    );
    // 0xff00 / 257 = 254.0 (the high byte would be 255); 0x4000 / 257 = 63.75.
    assert_eq!(decoded(&ga16), grey(&[254, 64]));

    let rgb = [255, 0, 0, 0, 255, 0, 0, 0, 255, 1, 2, 3];
    let rgb = encode((2, 2), ColorType::Rgb, Eight, &rgb, None, None);
    assert_eq!(
        decoded(&rgb),
        [[255, 0, 0], [0, 255, 0], [0, 0, 255], [1, 2, 3]]
    );
    let rgb16 = [
        0xff, 0xff, 0x01, 0x01, 0x7f, 0x80, 0x00, 0x7f, 0x80, 0x7f, 0xab, 0xcd,
    ];
    let rgb16 = encode((2, 1), ColorType::Rgb, Sixteen, &rgb16, None, None);
    // 0x7f80 / 257 = 127.0 (the high byte would be 127 too); 0x807f / 257 = 127.996;
    // 0xabcd / 257 = 171.2.
    assert_eq!(decoded(&rgb16), [[255, 1, 127], [0, 128, 171]]);
    let rgb_trns = encode(
        (1, 1),
        ColorType::Rgb,
        Eight,
        &[9, 8, 7],
        None,
        Some(&[0, 9, 0, 8, 0, 7]),
    );
    assert_eq!(decoded(&rgb_trns), [[9, 8, 7]]);

    // Fully transparent pixels keep their colour.
    let rgba = [10, 20, 30, 0, 40, 50, 60, 128, 70, 80, 90, 255];
    let rgba = encode((3, 1), ColorType::Rgba, Eight, &rgba, None, None);
    assert_eq!(decoded(&rgba), [[10, 20, 30], [40, 50, 60], [70, 80, 90]]);
    #[rustfmt::skip]
    let rgba16 = [
        0x12, 0x34, 0x56, 0x78, 0x9a, 0xbc, 0x00, 0x00,
        0xff, 0xfe, 0x00, 0x01, 0x80, 0x00, 0xff, 0xff,
    ];
    let rgba16 = encode((1, 2), ColorType::Rgba, Sixteen, &rgba16, None, None);
    // 0x1234 → 18.13, 0x5678 → 86.13, 0x9abc → 154.13; 0xfffe → 254.996, 1 → 0.004,
    // 0x8000 → 127.5019.
    assert_eq!(decoded(&rgba16), [[18, 86, 154], [255, 0, 128]]);
}

#[test]
fn decodes_indexed_at_every_depth() {
    use BitDepth::*;
    let palette = [
        0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, // 0 to 3
        1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, // 4 to 7
        13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, // 8 to 11
        25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, // 12 to 15
        200, 201, 202, // 16
    ];
    let i = ColorType::Indexed;
    let color = |k: usize| [palette[3 * k], palette[3 * k + 1], palette[3 * k + 2]];
    let colors = |ks: &[usize]| ks.iter().map(|&k| color(k)).collect::<Vec<_>>();
    let one = encode((3, 1), i, One, &[0b0100_0000], Some(&palette[..6]), None);
    assert_eq!(decoded(&one), colors(&[0, 1, 0]));
    let two = encode((3, 1), i, Two, &[0b1101_1000], Some(&palette[..12]), None);
    assert_eq!(decoded(&two), colors(&[3, 1, 2]));
    let four = encode(
        (3, 2),
        i,
        Four,
        &[0xf7, 0x90, 0x0a, 0x20],
        Some(&palette[..48]),
        None,
    );
    assert_eq!(decoded(&four), colors(&[15, 7, 9, 0, 10, 2]));
    let eight = encode((2, 1), i, Eight, &[16, 5], Some(&palette), None);
    assert_eq!(decoded(&eight), colors(&[16, 5]));
    // With tRNS the decoder yields RGBA: the alpha is dropped.
    let trns = encode(
        (2, 1),
        i,
        Eight,
        &[16, 5],
        Some(&palette),
        Some(&[0, 0, 0, 0, 0, 128]),
    );
    assert_eq!(decoded(&trns), colors(&[16, 5]));
    assert_eq!(read_png_size(&four), (3, 2));
}

fn read_png_size(png: &[u8]) -> (u32, u32) {
    let data = TextureData::from_png(png).unwrap();
    (data.width, data.height)
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let good = encode(
        (2, 2),
        ColorType::Rgb,
        BitDepth::Eight,
        &[7; 12],
        None,
        None,
    );
    for bytes in [&[][..], b"not a png", &good[..8], &good[..good.len() - 20]] {
        let e = TextureData::from_png(bytes).unwrap_err();
        assert!(matches!(e, ConvertError::Decode(_)), "{e:?}");
        assert!(!e.to_string().is_empty());
    }
    let mut corrupt = good.clone();
    let n = corrupt.len();
    corrupt[n - 20] ^= 0xff; // the IDAT's checksum or data
    assert!(TextureData::from_png(&corrupt).is_err());

    // A 60000 × 60000 RGBA header (26.8 GiB decoded), no data: refused before allocating.
    let mut huge = Vec::new();
    let mut encoder = png::Encoder::new(&mut huge, 60000, 60000);
    encoder.set_color(ColorType::Rgba);
    encoder.set_depth(BitDepth::Sixteen);
    let mut writer = encoder.write_header().unwrap();
    writer.write_chunk(png::chunk::IDAT, &[0x78, 0x9c]).unwrap();
    drop(writer);
    let e = TextureData::from_png(&huge).unwrap_err();
    assert!(e.to_string().contains("60000 × 60000"), "{e}");

    let e = read_png("/nonexistent/texture.png").unwrap_err();
    assert!(matches!(e, ConvertError::Io(_)));
    assert!(std::error::Error::source(&e).is_some());

    let e = "rgb555".parse::<TexelFormat>().unwrap_err();
    assert!(matches!(e, ConvertError::UnknownFormat(ref s) if s == "rgb555"));
    for f in TexelFormat::ALL {
        assert_eq!(f.name().parse::<TexelFormat>().unwrap(), f);
        assert_eq!(
            f.to_string().to_uppercase().parse::<TexelFormat>().unwrap(),
            f
        );
    }
}

#[test]
fn mismatched_pixel_counts_read_as_black() {
    // The fields are public: a short `pixels` is padded with black, never indexed out of range.
    let short = TextureData {
        width: 3,
        height: 1,
        pixels: vec![[255, 255, 255]],
    };
    assert_eq!(short.rgb565(), [0xffff, 0, 0]);
    assert_eq!(short.resized(1, 1).pixels, [[85, 85, 85]]);
    assert_eq!(short.palette(4).indices.len(), 3);
    let text = short.to_rust_source("S", TexelFormat::Gray8, "crate");
    assert_eq!(array(&text, "S_TEXELS"), [255, 0, 0]);
}

#[test]
fn box_filter_averages_the_covered_area() {
    // 4 × 2 → 2 × 1: each new pixel the mean of a 2 × 2 block.
    #[rustfmt::skip]
    let img = image(4, 2, vec![
        [0, 10, 255], [4, 20, 255], [100, 0, 0], [101, 0, 0],
        [8, 30, 255], [12, 41, 254], [102, 0, 1], [102, 255, 0],
    ]);
    // (0+4+8+12)/4 = 6, (10+20+30+41)/4 = 25.25, (255·3+254)/4 = 254.75; (100+101+102+102)/4 =
    // 101.25, 255/4 = 63.75, 1/4.
    assert_eq!(img.resized(2, 1).pixels, [[6, 25, 255], [101, 64, 0]]);
    // 3 → 2: new pixel 0 covers old 0 and half of old 1, new pixel 1 the other half and old 2.
    let row = image(3, 1, vec![[0, 0, 0], [90, 1, 255], [255, 2, 0]]);
    // (2·0 + 90)/3 = 30, (2·0 + 1)/3 = 0.33, 255/3 = 85; (90 + 2·255)/3 = 200, (1 + 4)/3 = 1.67,
    // 255/3 = 85.
    assert_eq!(row.resized(2, 1).pixels, [[30, 0, 85], [200, 2, 85]]);
    // Halves round up.
    let pair = image(2, 1, vec![[0, 0, 0], [1, 3, 255]]);
    assert_eq!(pair.resized(1, 1).pixels, [[1, 2, 128]]);
    // Growing takes the nearest: centres at (i + ½)·2/5 = 0.2, 0.6, 1.0, 1.4, 1.8.
    let (a, b) = ([1, 2, 3], [4, 5, 6]);
    let grown = image(2, 1, vec![a, b]).resized(5, 2);
    assert_eq!(grown.pixels, [a, a, b, b, b, a, a, b, b, b]);
    // The same size keeps the pixels; 0 gives nothing; nothing gives black.
    assert_eq!(img.resized(4, 2), img);
    assert!(img.resized(0, 3).pixels.is_empty());
    assert_eq!(TextureData::default().resized(2, 1).pixels, [[0; 3]; 2]);
}

/// A 64 × 64 test picture: smooth gradients with a few hard edges.
fn gradient() -> TextureData {
    let mut pixels = Vec::new();
    for y in 0..64u32 {
        for x in 0..64u32 {
            let edge = if (x / 16 + y / 16) % 2 == 0 { 0 } else { 60 };
            pixels.push([(x * 4) as u8, (y * 3 + edge) as u8, ((x + y) * 2) as u8]);
        }
    }
    image(64, 64, pixels)
}

#[test]
fn box_filter_by_four_matches_block_means() {
    let img = gradient();
    let small = img.resized(16, 16);
    for (i, got) in small.pixels.iter().enumerate() {
        let (bx, by) = (i as u32 % 16 * 4, i as u32 / 16 * 4);
        let mut sum = [0u32; 3];
        for y in by..by + 4 {
            for x in bx..bx + 4 {
                let pixel = img.pixels[(y * 64 + x) as usize];
                for (s, c) in sum.iter_mut().zip(pixel) {
                    *s += u32::from(c);
                }
            }
        }
        let want = sum.map(|s| (f64::from(s) / 16.0).round() as u8);
        assert_eq!(*got, want, "pixel {i}");
    }
}

#[test]
fn palette_is_exact_for_few_colours() {
    let colors = [[9, 9, 9], [0, 0, 200], [255, 0, 0], [0, 0, 201], [1, 0, 0]];
    let pixels: Vec<[u8; 3]> = (0..35).map(|i| colors[i * 7 % 5]).collect();
    let img = image(7, 5, pixels);
    for max in [5, 16, 256] {
        let p = img.palette(max);
        let mut sorted = colors.to_vec();
        sorted.sort();
        assert_eq!(p.colors, sorted);
        assert_eq!(p.indices.len(), 35);
        for (i, &k) in p.indices.iter().enumerate() {
            assert_eq!(p.colors[usize::from(k)], img.pixels[i]);
        }
        assert_eq!(p.error(&img).max, 0.0);
    }
    // Asking for fewer than 2 asks for 2.
    let two = image(3, 1, vec![[0; 3], [255; 3], [0; 3]]);
    assert_eq!(two.palette(0).colors, [[0; 3], [255; 3]]);
    assert_eq!(two.palette(1).indices, [0, 1, 0]);
}

#[test]
fn median_cut_is_bounded_nearest_and_deterministic() {
    let img = gradient();
    assert!(img.histogram().len() > 1000);
    let p = img.palette(16);
    assert_eq!(p.colors.len(), 16);
    assert!(p.colors.windows(2).all(|w| w[0] < w[1]));
    // Every pixel has the nearest palette colour.
    let d2 = |a: [u8; 3], b: [u8; 3]| -> i32 {
        (0..3)
            .map(|c| (i32::from(a[c]) - i32::from(b[c])).pow(2))
            .sum()
    };
    let (mut sum, mut max) = (0.0, 0i32);
    for (&c, &k) in img.pixels.iter().zip(&p.indices) {
        let mine = d2(c, p.colors[usize::from(k)]);
        assert!(p.colors.iter().all(|&q| d2(c, q) >= mine));
        sum += f64::from(mine);
        max = max.max(mine);
    }
    let rms = (sum / (3.0 * 4096.0)).sqrt();
    let e = p.error(&img);
    assert!((e.rms - rms).abs() < 1e-9 && e.max == f64::from(max).sqrt());
    // 16 colours for a cube of ~250 × 250 × 250 levels: about 16 levels a channel.
    assert!(rms < 16.0, "RMS error {rms}");
    assert!(e.max < 64.0, "largest error {}", e.max);
    // 256 colours do better.
    assert!(img.palette(256).error(&img).rms < rms / 3.0);

    // The same image gives the same palette, whatever the order of its pixels.
    assert_eq!(img.palette(16), p);
    let mut transposed = img.clone();
    for y in 0..64 {
        for x in 0..64 {
            transposed.pixels[x * 64 + y] = img.pixels[y * 64 + x];
        }
    }
    assert_eq!(transposed.palette(16).colors, p.colors);
}

/// The numbers of the array `name` in generated `source` (decimal or `0x` hex).
fn array(source: &str, name: &str) -> Vec<u32> {
    let decl = format!("pub static {name}: [");
    let start = source.find(&decl).unwrap_or_else(|| panic!("no {name}"));
    let body = &source[start + decl.len()..];
    let body = &body[body.find("= [").unwrap() + 3..];
    let body = &body[..body.find("];").unwrap()];
    numbers(body)
}

fn numbers(text: &str) -> Vec<u32> {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|t| t.starts_with(|c: char| c.is_ascii_digit()))
        .map(|t| match t.strip_prefix("0x") {
            Some(hex) => u32::from_str_radix(hex, 16).unwrap(),
            None => t.parse().unwrap(),
        })
        .collect()
}

/// The palette of generated `source` as `Rgb565`s (`Rgb565::new(r, g, b)` triples).
fn palette(source: &str, name: &str) -> Vec<Rgb565> {
    array(source, name)
        .chunks(3)
        .map(|c| Rgb565::new(c[0] as u8, c[1] as u8, c[2] as u8))
        .collect()
}

fn constant(source: &str, name: &str) -> u32 {
    let decl = format!("pub const {name}: u32 = ");
    let start = source.find(&decl).unwrap() + decl.len();
    numbers(&source[start..source[start..].find(';').unwrap() + start])[0]
}

/// Red, green, blue / white, grey, a dark colour just past the rounding edges.
fn tiny() -> TextureData {
    #[rustfmt::skip]
    let img = image(3, 2, vec![
        [255, 0, 0], [0, 255, 0], [0, 0, 255],
        [255, 255, 255], [128, 128, 128], [5, 3, 4],
    ]);
    img
}

#[test]
fn emitted_direct_formats_hold_the_raw_values() {
    let img = tiny();
    let s = img.to_rust_source("TINY", TexelFormat::Rgb565, "embedded_raster");
    assert!(s.starts_with(
        "//! Generated by `embedded_raster::texture::convert::TextureData::to_rust_source`; \
         do not edit.\n"
    ));
    assert!(s.contains("use embedded_raster::texture::Rgb565Texels;"));
    assert!(s.contains("pub static TINY: Rgb565Texels<'static> = Rgb565Texels(&TINY_TEXELS);"));
    assert_eq!(
        (constant(&s, "TINY_WIDTH"), constant(&s, "TINY_HEIGHT")),
        (3, 2)
    );
    // 128: 31·128/255 = 15.56 → 16, 63·128/255 = 32.4 → 32; 5 → 0.61 → 1, 3 → 0.74 → 1,
    // 4 → 0.49 → 0.
    let words = array(&s, "TINY_TEXELS");
    assert_eq!(words, [0xf800, 0x07e0, 0x001f, 0xffff, 0x8410, 0x0820]);
    let raw: Vec<u16> = words.iter().map(|&w| w as u16).collect();
    assert_eq!(Rgb565Texels(&raw).texel(4), Rgb565::new(16, 32, 16));
    assert_eq!(image(1, 1, vec![[4, 2, 5]]).rgb565(), [0x0001]);

    let s = img.to_rust_source("TINY", TexelFormat::Rgb888, "crate");
    assert!(s.contains("use crate::texture::Rgb888Texels;"));
    let bytes: Vec<u8> = array(&s, "TINY_TEXELS").iter().map(|&b| b as u8).collect();
    assert_eq!(bytes.len(), 18);
    let texels = Rgb888Texels(&bytes);
    for (i, &[r, g, b]) in img.pixels.iter().enumerate() {
        assert_eq!(texels.texel(i), Rgb888::new(r, g, b));
    }

    // round(0.299 R + 0.587 G + 0.114 B): 76.2, 149.7, 29.1, 255, 128, 3.7.
    let s = img.to_rust_source("TINY", TexelFormat::Gray8, "crate");
    assert_eq!(array(&s, "TINY_TEXELS"), [76, 150, 29, 255, 128, 4]);
    let bytes: Vec<u8> = array(&s, "TINY_TEXELS").iter().map(|&b| b as u8).collect();
    assert_eq!(Gray8Texels(&bytes).texels(), 6);
}

#[test]
fn emitted_palettes_read_back_through_the_texel_sources() {
    let img = tiny();
    // The six colours sorted: blue, green, dark, grey, red, white.
    let want_palette = [
        Rgb565::new(0, 0, 31),
        Rgb565::new(0, 63, 0),
        Rgb565::new(1, 1, 0),
        Rgb565::new(16, 32, 16),
        Rgb565::new(31, 0, 0),
        Rgb565::new(31, 63, 31),
    ];
    let want_indices = [4, 1, 0, 5, 3, 2];

    let s = img.to_rust_source("TINY", TexelFormat::Indexed8, "embedded_raster");
    assert!(s.contains("use embedded_graphics::pixelcolor::Rgb565;"));
    assert!(s.contains("pub static TINY: Indexed8<'static, Rgb565> = Indexed8 {"));
    assert_eq!(palette(&s, "TINY_PALETTE"), want_palette);
    assert_eq!(array(&s, "TINY_INDICES"), want_indices);

    let s = img.to_rust_source("TINY", TexelFormat::Indexed4, "embedded_raster");
    assert_eq!(palette(&s, "TINY_PALETTE"), want_palette);
    // Two a byte, the first in the high nibble.
    assert_eq!(array(&s, "TINY_INDICES"), [0x41, 0x05, 0x32]);

    // Odd widths: packed across rows, only the very last byte padded. 5 × 3 = 15 texels.
    let colors = [[0, 0, 0], [10, 0, 0], [20, 0, 0], [30, 0, 0], [40, 0, 0]];
    let pixels: Vec<[u8; 3]> = (0..15).map(|i| colors[(i * 3 + i / 5) % 5]).collect();
    let odd = image(5, 3, pixels);
    for format in [TexelFormat::Indexed4, TexelFormat::Indexed8] {
        let s = odd.to_rust_source("ODD", format, "embedded_raster");
        let bytes: Vec<u8> = array(&s, "ODD_INDICES").iter().map(|&b| b as u8).collect();
        let pal = palette(&s, "ODD_PALETTE");
        assert_eq!(pal.len(), 5);
        // 31·c/255 for 0, 10, 20, 30, 40: 0, 1.2, 2.4, 3.6, 4.9.
        let levels = [0, 1, 2, 4, 5].map(|r| Rgb565::new(r, 0, 0));
        assert_eq!(pal, levels);
        let want = |i: usize| levels[(i * 3 + i / 5) % 5];
        if format == TexelFormat::Indexed4 {
            assert_eq!(bytes.len(), 8);
            // Texel i is index (i·3 + i/5) mod 5 (colours sorted as listed): 0, 3, 1, 4, 2 /
            // 1, 4, 2, 0, 3 / 2, 0, 3, 1, 4; the 16th nibble 0.
            assert_eq!(bytes, [0x03, 0x14, 0x21, 0x42, 0x03, 0x20, 0x31, 0x40]);
            let texels = Indexed4 {
                indices: &bytes,
                palette: &pal,
            };
            for i in 0..15 {
                assert_eq!(texels.texel(i), want(i), "texel {i}");
            }
            assert!(Texture::new(texels, 5, 3).is_ok());
        } else {
            let texels = Indexed8 {
                indices: &bytes,
                palette: &pal,
            };
            assert!((0..15).all(|i| texels.texel(i) == want(i)));
        }
    }
}

#[test]
fn emitted_source_is_laid_out_as_rustfmt_lays_it_out() {
    let Ok(out) = std::process::Command::new("rustfmt")
        .arg("--version")
        .output()
    else {
        eprintln!("no rustfmt: skipped");
        return;
    };
    assert!(out.status.success());
    let images = [
        image(1, 1, vec![[1, 2, 3]]),
        tiny(),
        gradient().resized(40, 3),
        gradient().resized(9, 9),
    ];
    for img in &images {
        for format in TexelFormat::ALL {
            let s = img.to_rust_source_from("T", format, "embedded_raster", "From a test.");
            let mut child = std::process::Command::new("rustfmt")
                .args(["--edition", "2021", "--emit", "stdout"])
                .stdin(std::process::Stdio::piped())
                .stdout(std::process::Stdio::piped())
                .spawn()
                .unwrap();
            use std::io::Write;
            child.stdin.take().unwrap().write_all(s.as_bytes()).unwrap();
            let out = child.wait_with_output().unwrap();
            assert!(out.status.success());
            let formatted = String::from_utf8(out.stdout).unwrap();
            assert_eq!(formatted, s, "{format} of {} × {}", img.width, img.height);
        }
    }
}

/// The text without whitespace and trailing commas (which rustfmt adds or drops with the
/// layout).
fn squeeze(s: &str) -> String {
    let s: String = s.chars().filter(|c| !c.is_whitespace()).collect();
    s.replace(",]", "]").replace(",)", ")").replace(",}", "}")
}

/// The spot texture as `examples/texture_tool.rs` makes it: Keenan Crane's public-domain
/// texture (`examples/common/textures/spot_README.txt`), 1024 × 1024, box-filtered to 256 × 256
/// and reduced to 16 colours.
fn spot() -> (TextureData, String) {
    let png = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/common/textures/spot_texture.png"
    );
    let full = read_png(png).unwrap();
    assert_eq!((full.width, full.height), (1024, 1024));
    let small = full.resized(256, 256);
    let origin = "From `spot_texture.png` (1024 × 1024), box-filtered to 256 × 256.";
    let source = small.to_rust_source_from(
        "SPOT_TEXTURE",
        TexelFormat::Indexed4,
        "embedded_raster",
        origin,
    );
    (small, source)
}

#[test]
fn spot_texture_matches_its_png() {
    let (small, source) = spot();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/common/textures/spot_texture.rs"
    );
    if std::env::var_os("REGENERATE_TEXTURES").is_some() {
        std::fs::write(path, &source).unwrap();
    }
    let stored = std::fs::read_to_string(path).unwrap();
    assert!(
        squeeze(&stored) == squeeze(&source),
        "{path} is stale: rerun with REGENERATE_TEXTURES=1"
    );

    // The compiled statics read as the palette image.
    use spot_texture::{SPOT_TEXTURE, SPOT_TEXTURE_HEIGHT, SPOT_TEXTURE_WIDTH};
    assert_eq!((SPOT_TEXTURE_WIDTH, SPOT_TEXTURE_HEIGHT), (256, 256));
    let texture = Texture::new(SPOT_TEXTURE, SPOT_TEXTURE_WIDTH, SPOT_TEXTURE_HEIGHT).unwrap();
    assert_eq!(SPOT_TEXTURE.indices.len(), 256 * 256 / 2);
    let p: Palette = small.palette(16);
    assert_eq!(SPOT_TEXTURE.palette, &p.rgb565()[..]);
    for (i, &k) in p.indices.iter().enumerate() {
        let (x, y) = (i as i32 % 256, i as i32 / 256);
        assert_eq!(texture.texel(x, y), SPOT_TEXTURE.palette[usize::from(k)]);
    }
    // Few colours (flat regions and their blended edges) and a small error.
    let e = p.error(&small);
    assert!(e.rms < 2.0, "RMS error {}", e.rms);
}
