//! PNG files of framebuffers and z-buffers (feature `png`), read back with the `png` crate's
//! decoder and compared pixel by pixel with the colours converted independently.

use embedded_graphics::pixelcolor::{Gray8, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raster::three_d::{draw_flat, DepthTarget, ScreenVertex};
use embedded_raster::{fixed_point::ToCoord, SliceFramebuffer};

fn decode(path: &std::path::Path) -> (png::OutputInfo, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut data = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut data).unwrap();
    data.truncate(info.buffer_size());
    (info, data)
}

#[test]
fn framebuffers_and_depth_save_as_png() {
    let dir = std::env::temp_dir().join(format!("embedded-raster-png-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (w, h) = (7u32, 5u32);
    let mut pixels: Vec<Rgb565> = (0..w * h)
        .map(|i| Rgb565::new((i % 32) as u8, (i * 7 % 64) as u8, (31 - i % 32) as u8))
        .collect();
    let want: Vec<u8> = pixels
        .iter()
        .flat_map(|&c| {
            // 5/6-bit channels scaled to 8 bits, rounded (embedded-graphics' conversion).
            let s = |v: u8, max: u32| ((u32::from(v) * 255 + max / 2) / max) as u8;
            [s(c.r(), 31), s(c.g(), 63), s(c.b(), 31)]
        })
        .collect();
    let path = dir.join("colour.png");
    SliceFramebuffer::new(&mut pixels, w, h)
        .unwrap()
        .save_png(&path)
        .unwrap();
    let (info, data) = decode(&path);
    assert_eq!((info.width, info.height), (w, h));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(data, want);

    // Depth: 16-bit grey, 65535 − depth; empty pixels 0.
    let mut colour = vec![Rgb888::BLACK; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut target = DepthTarget::new(&mut colour, &mut depth, w, h).unwrap();
    let v = |x: f32, y: f32| ScreenVertex::new(x.to_coord(), y.to_coord(), 1000);
    let clip = target.bounding_box();
    draw_flat(
        &mut target,
        &clip,
        &[v(0.0, 0.0), v(7.0, 0.0), v(0.0, 5.0)],
        Rgb888::RED,
    );
    let depths = target.depth().to_vec();
    let path = dir.join("depth.png");
    target.save_depth_png(&path).unwrap();
    let (info, data) = decode(&path);
    assert_eq!(info.bit_depth, png::BitDepth::Sixteen);
    assert_eq!(info.color_type, png::ColorType::Grayscale);
    let got: Vec<u16> = data
        .chunks(2)
        .map(|b| u16::from_be_bytes([b[0], b[1]]))
        .collect();
    let want: Vec<u16> = depths.iter().map(|&d| 65535 - d).collect();
    assert_eq!(got, want);
    assert!(got.contains(&0) && got.contains(&(65535 - 1000)));

    // The same z-buffer blitted as Gray8: the high byte.
    let mut grey = vec![Gray8::WHITE; (w * h) as usize];
    let mut screen = SliceFramebuffer::new(&mut grey, w, h).unwrap();
    embedded_graphics::image::Image::new(&target.depth_image(), Point::zero())
        .draw(&mut screen)
        .unwrap();
    let luma: Vec<u16> = grey.iter().map(|g| u16::from(g.luma())).collect();
    assert_eq!(luma, want.iter().map(|v| v >> 8).collect::<Vec<_>>());
    std::fs::remove_dir_all(&dir).unwrap();
}
