//! The firmware scene (`examples/common/scene.rs`) on the host, checked against an independent
//! reference, for every framebuffer size the firmware uses.
//!
//! The reference here is written from the coverage contract alone: exact `i128` edge functions at
//! pixel centres with the top-left rule, barycentric colours in `f64`, painter's order. The crate's
//! image must have exactly the reference's coverage (solid colours exact, Gouraud colours within
//! 1 LSB per channel). `.ci/firmware.sh` then checks that every board's firmware prints the same
//! checksum as the host build of `fw_scene` (`cargo run --release --example fw_scene`); this test
//! prints those values too (`cargo test --release --test firmware_checksum -- --nocapture`).

#[allow(dead_code)]
#[path = "../examples/common/scene.rs"]
mod scene;

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_raster::{GouraudColor, SliceFramebuffer};
use scene::Shape;

/// What the reference puts at one pixel.
#[derive(Clone, Copy, Debug)]
enum Expected {
    Background,
    Solid(Rgb565),
    /// Exact channel values (r 0..31, g 0..63, b 0..31).
    Gouraud([f64; 3]),
    /// Exact channel values of a translucent blend, and the error the pixel under it may add.
    Blended([f64; 3], f64),
}

/// Exact coverage and barycentric weights of a pixel centre under the top-left rule.
fn reference_weights(p: [(i32, i32); 3], i: i64, j: i64) -> Option<[f64; 3]> {
    let p = p.map(|(x, y)| (i128::from(x), i128::from(y)));
    let (px, py) = (i128::from(i) * 256 + 128, i128::from(j) * 256 + 128);
    let mut weights = [0.0; 3];
    for k in 0..3 {
        // Edge a→b opposite vertex c = p[k].
        let (a, b, c) = (p[(k + 1) % 3], p[(k + 2) % 3], p[k]);
        let side = |x: i128, y: i128| (x - a.0) * (b.1 - a.1) - (b.0 - a.0) * (y - a.1);
        let dc = side(c.0, c.1);
        if dc == 0 {
            return None; // collinear: no interior
        }
        let dp = side(px, py);
        if dp == 0 {
            // On the edge: covered only for a top edge (horizontal, third vertex below) or a
            // left edge (interior to the right: c lies at larger x than the edge at c's height,
            // i.e. dc has the sign of b.y − a.y).
            let top = a.1 == b.1 && c.1 > a.1;
            let left = a.1 != b.1 && (dc > 0) == (b.1 - a.1 > 0);
            if !(top || left) {
                return None;
            }
        } else if (dp > 0) != (dc > 0) {
            return None;
        }
        weights[k] = dp as f64 / dc as f64;
    }
    Some(weights)
}

fn reference_image(width: u32, height: u32) -> Vec<Expected> {
    let mut image = vec![Expected::Background; (width * height) as usize];
    scene::for_each_shape(width, height, |shape| {
        let positions = shape.raw_positions();
        for j in 0..height {
            for i in 0..width {
                let Some(w) = reference_weights(positions, i64::from(i), i64::from(j)) else {
                    continue;
                };
                image[(j * width + i) as usize] = match shape {
                    Shape::Solid(t) => Expected::Solid(t.color),
                    Shape::Gouraud(t) => {
                        let ch = |f: fn(&Rgb565) -> u8| {
                            (0..3)
                                .map(|k| w[k] * f64::from(f(&t.vertices[k].color)))
                                .sum::<f64>()
                        };
                        Expected::Gouraud([ch(Rgb565::r), ch(Rgb565::g), ch(Rgb565::b)])
                    }
                };
            }
        }
    });
    // The translucent triangle blended over it: `P + d·(1 − α)` of the barycentric premultiplied
    // colour `P` and alpha `α`.
    let top = scene::translucent(width, height);
    let positions = top.shape().vertices.map(|v| (v.x.to_bits(), v.y.to_bits()));
    for j in 0..height {
        for i in 0..width {
            let Some(w) = reference_weights(positions, i64::from(i), i64::from(j)) else {
                continue;
            };
            let idx = (j * width + i) as usize;
            let a = top.alpha().map(|a| f64::from(a) / 255.0);
            let alpha = (0..3).map(|k| w[k] * a[k]).sum::<f64>();
            let (under, slack) = match image[idx] {
                Expected::Background => (channels(scene::BACKGROUND), 0.0),
                Expected::Solid(c) => (channels(c), 0.0),
                // The pixel under it is within 1 LSB of the exact colour.
                Expected::Gouraud(exact) => (exact, 1.0 - alpha),
                Expected::Blended(..) => unreachable!("one translucent triangle"),
            };
            let blended = [0, 1, 2].map(|ch| {
                let p = (0..3)
                    .map(|k| w[k] * a[k] * channels(top.shape().vertices[k].color)[ch])
                    .sum::<f64>();
                p + under[ch] * (1.0 - alpha)
            });
            image[idx] = Expected::Blended(blended, slack);
        }
    }
    image
}

fn channels(c: Rgb565) -> [f64; 3] {
    [c.r(), c.g(), c.b()].map(f64::from)
}

fn render(width: u32, height: u32) -> Vec<Rgb565> {
    let mut pixels = vec![Rgb565::BLACK; (width * height) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, width, height).unwrap();
    scene::render_opaque(&mut fb);
    pixels
}

/// The translucent shapes over the opaque image `under`: each pixel the reference covers is the
/// shape's colour blended over it (`GouraudColor::blend`, the definition), the others as they
/// were; shapes in drawing order.
fn reference_translucent(width: u32, height: u32, under: &[Rgb565]) -> Vec<Rgb565> {
    let mut image = under.to_vec();
    for (t, alpha) in scene::translucent_shapes(width, height) {
        let positions = t.points.map(|(x, y)| (x.to_bits(), y.to_bits()));
        for j in 0..height {
            for i in 0..width {
                if reference_weights(positions, i64::from(i), i64::from(j)).is_some() {
                    let px = &mut image[(j * width + i) as usize];
                    *px = t.color.blend(*px, alpha);
                }
            }
        }
    }
    image
}

#[test]
fn scene_matches_independent_reference_at_every_firmware_size() {
    for (width, height) in scene::SIZES {
        let got = render(width, height);
        let want = reference_image(width, height);
        let mut shaded = 0;
        for (idx, (g, w)) in got.iter().zip(&want).enumerate() {
            let (x, y) = (idx as u32 % width, idx as u32 / width);
            let ok = match *w {
                Expected::Background => *g == scene::BACKGROUND,
                Expected::Solid(c) => *g == c,
                Expected::Gouraud(exact) => {
                    shaded += 1;
                    let got = [g.r(), g.g(), g.b()].map(f64::from);
                    (0..3).all(|k| (got[k] - exact[k]).abs() <= 1.0 + 1e-9)
                }
                Expected::Blended(exact, slack) => {
                    shaded += 1;
                    let got = [g.r(), g.g(), g.b()].map(f64::from);
                    (0..3).all(|k| (got[k] - exact[k]).abs() <= 1.0 + slack + 1e-9)
                }
            };
            assert!(
                ok,
                "{width}x{height}: pixel ({x}, {y}) is {g:?}, reference {w:?}"
            );
        }
        // The scene must actually exercise the rasterizer at this size.
        assert!(
            shaded > (width * height) as usize * 3 / 4,
            "{shaded} shaded pixels"
        );
        // Then the translucent shapes, exactly their blends over the opaque image.
        let want = reference_translucent(width, height, &got);
        let blended = got.iter().zip(&want).filter(|(g, w)| g != w).count();
        assert!(
            blended > (width * height) as usize / 4,
            "{blended} blended pixels"
        );
        let mut got = got;
        let mut fb = SliceFramebuffer::new(&mut got, width, height).unwrap();
        scene::render_translucent(&mut fb);
        for (idx, (g, w)) in got.iter().zip(&want).enumerate() {
            let (x, y) = (idx as u32 % width, idx as u32 / width);
            assert_eq!(g, w, "{width}x{height}: translucent pixel ({x}, {y})");
        }
        let mut whole = vec![Rgb565::BLACK; (width * height) as usize];
        scene::render(&mut SliceFramebuffer::new(&mut whole, width, height).unwrap());
        assert_eq!(
            whole, got,
            "render is render_opaque then render_translucent"
        );
        println!(
            "{}",
            scene::ChecksumLine {
                width,
                height,
                checksum: scene::checksum(&got)
            }
        );
    }
}

#[test]
fn checksum_is_fnv1a_of_the_little_endian_raw_pixels() {
    // Published FNV-1a test vectors: "" → 0x811c9dc5, "a" → 0xe40c292c, "foobar" → 0xbf9cf968.
    // Rgb565 raw 0x6f66 is the bytes "fo", 0x626f "ob", 0x7261 "ar".
    assert_eq!(scene::checksum(&[]), 0x811c_9dc5);
    let px = |raw: u16| Rgb565::from(embedded_graphics::pixelcolor::raw::RawU16::new(raw));
    assert_eq!(
        scene::checksum(&[px(0x6f66), px(0x626f), px(0x7261)]),
        0xbf9c_f968
    );
}

#[test]
fn shapes_cross_every_border_and_include_degenerate_ones() {
    // The scene is meant to clip: make sure a change to it keeps doing so.
    let (width, height) = scene::MPS2_SIZE;
    let (w, h) = (width as i64 * 256, height as i64 * 256);
    let mut crossing = [false; 4];
    let mut degenerate = 0;
    let mut count = 0;
    scene::for_each_shape(width, height, |shape| {
        count += 1;
        let p = shape
            .raw_positions()
            .map(|(x, y)| (i64::from(x), i64::from(y)));
        let inside_y = p.iter().any(|v| (0..h).contains(&v.1));
        let inside_x = p.iter().any(|v| (0..w).contains(&v.0));
        crossing[0] |= inside_y && p.iter().any(|v| v.0 < 0);
        crossing[1] |= inside_y && p.iter().any(|v| v.0 >= w);
        crossing[2] |= inside_x && p.iter().any(|v| v.1 < 0);
        crossing[3] |= inside_x && p.iter().any(|v| v.1 >= h);
        let area2 = (p[1].0 - p[0].0) as i128 * (p[2].1 - p[0].1) as i128
            - (p[2].0 - p[0].0) as i128 * (p[1].1 - p[0].1) as i128;
        degenerate += usize::from(area2 == 0);
    });
    assert_eq!(crossing, [true; 4]);
    assert!(degenerate >= 1);
    assert!(count >= 200, "{count} shapes");
}
