//! The firmware scene (`examples/common/scene.rs`) on the host, checked against an independent
//! reference, for every framebuffer size the firmware uses.
//!
//! The reference here is written from the coverage contract alone: exact `i128` edge functions at
//! pixel centres with the top-left rule, barycentric colours in `f64`, painter's order. The crate's
//! image must have exactly the reference's coverage (solid colours exact, Gouraud colours within
//! 1 LSB per channel). `.ci/firmware.sh` then checks that every board's firmware prints the same
//! checksum as the host build of `fw_scene` (`cargo run --release --example fw_scene`); this test
//! prints those values too (`cargo test --release --test all firmware_checksum:: -- --nocapture`).

#[allow(dead_code)]
#[path = "../../examples/common/scene.rs"]
mod scene;

use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
use embedded_graphics::Drawable;
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
        // Then the anti-aliased shapes, one at a time, each over the image before it.
        check_antialiased(width, height, &mut got);
        // Then the dithered ones, likewise.
        check_dithered(width, height, &mut got);
        let mut whole = vec![Rgb565::BLACK; (width * height) as usize];
        scene::render(&mut SliceFramebuffer::new(&mut whole, width, height).unwrap());
        assert_eq!(
            whole, got,
            "render is render_opaque, render_translucent, render_antialiased then render_dithered"
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

/// The area of the square of pixel `(i, j)` inside the triangle `p` (raw sub-pixels): the
/// square clipped by the three edges in `f64`, the shoelace formula.
fn pixel_area(p: [(i32, i32); 3], i: u32, j: u32) -> f64 {
    let v = p.map(|(x, y)| (f64::from(x) / 256.0, f64::from(y) / 256.0));
    let orient = (v[1].0 - v[0].0) * (v[2].1 - v[0].1) - (v[1].1 - v[0].1) * (v[2].0 - v[0].0);
    let (x0, y0) = (f64::from(i), f64::from(j));
    let mut poly = vec![
        (x0, y0),
        (x0 + 1.0, y0),
        (x0 + 1.0, y0 + 1.0),
        (x0, y0 + 1.0),
    ];
    for k in 0..3 {
        let (a, b) = (v[k], v[(k + 1) % 3]);
        let side = |q: (f64, f64)| {
            orient.signum() * ((b.0 - a.0) * (q.1 - a.1) - (b.1 - a.1) * (q.0 - a.0))
        };
        let mut out = Vec::new();
        for n in 0..poly.len() {
            let (p0, p1) = (poly[n], poly[(n + 1) % poly.len()]);
            let (s0, s1) = (side(p0), side(p1));
            if s0 >= 0.0 {
                out.push(p0);
            }
            if (s0 >= 0.0) != (s1 >= 0.0) {
                let t = s0 / (s0 - s1);
                out.push((p0.0 + (p1.0 - p0.0) * t, p0.1 + (p1.1 - p0.1) * t));
            }
        }
        poly = out;
    }
    let n = poly.len();
    ((0..n)
        .map(|k| poly[k].0 * poly[(k + 1) % n].1 - poly[(k + 1) % n].0 * poly[k].1)
        .sum::<f64>()
        / 2.0)
        .abs()
}

/// Whether `got` is `color` over `under` at an alpha within one level of `255 · area · opacity/255`.
fn blended_near(got: Rgb565, color: Rgb565, under: Rgb565, area: f64, opacity: u8) -> bool {
    let exact = area * f64::from(opacity);
    let lo = (exact - 1.0).ceil().max(0.0) as u8;
    let hi = (exact + 1.0).floor().min(255.0) as u8;
    (lo..=hi).any(|a| color.blend(under, a) == got)
}

/// Draws the scene's anti-aliased shapes over `image` one at a time, checking each against the
/// pixel areas; leaves `image` as `render_antialiased` leaves it.
/// The dithered shapes drawn one at a time as `render_dithered` draws them: the pixels the
/// reference covers, and only those, are each channel's exact barycentric value plus the pixel's
/// 4×4 Bayer threshold `(2b + 1)/32` (written out here), truncated, within 1/64 LSB of the
/// lanes' stepping and 2⁻⁹ of the planes'.
fn check_dithered(width: u32, height: u32, image: &mut [Rgb565]) {
    const BAYER: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
    const SLACK: f64 = 1.0 / 64.0 + 1.0 / 512.0;
    let mut dithered = 0;
    for (k, t) in scene::dithered_shapes(width, height)
        .into_iter()
        .enumerate()
    {
        let under = image.to_vec();
        let mut fb = SliceFramebuffer::new(image, width, height).unwrap();
        if k % 2 == 0 {
            t.dithered().draw(&mut fb).unwrap();
        } else {
            t.dithered().draw_into(&mut fb);
        }
        let p = t.vertices.map(|v| (v.x.to_bits(), v.y.to_bits()));
        for (idx, (g, u)) in image.iter().zip(&under).enumerate() {
            let (i, j) = (idx as u32 % width, idx as u32 / width);
            let Some(w) = reference_weights(p, i64::from(i), i64::from(j)) else {
                assert_eq!(
                    g, u,
                    "{width}x{height}: pixel ({i}, {j}) outside dithered shape {k}"
                );
                continue;
            };
            dithered += 1;
            let threshold = f64::from(2 * BAYER[(j & 3) as usize][(i & 3) as usize] + 1) / 32.0;
            for (ch, &got) in channels(*g).iter().enumerate() {
                let exact = (0..3)
                    .map(|v| w[v] * channels(t.vertices[v].color)[ch])
                    .sum::<f64>();
                let (low, high) = (
                    (exact + threshold - SLACK).floor(),
                    (exact + threshold + SLACK).floor(),
                );
                assert!(
                    low <= got && got <= high,
                    "{width}x{height}: dithered shape {k} pixel ({i}, {j}) channel {ch}: {got} \
                     for {exact} + {threshold}"
                );
            }
        }
    }
    assert!(
        dithered > (width * height) as usize / 3,
        "{dithered} dithered pixels"
    );
}

fn check_antialiased(width: u32, height: u32, image: &mut [Rgb565]) {
    let mut touched = 0;
    for (t, opacity) in scene::antialiased_shapes(width, height) {
        let under = image.to_vec();
        t.anti_aliased()
            .with_opacity(opacity)
            .draw_into(&mut SliceFramebuffer::new(image, width, height).unwrap());
        let p = t.points.map(|(x, y)| (x.to_bits(), y.to_bits()));
        for (idx, (g, u)) in image.iter().zip(&under).enumerate() {
            let (i, j) = (idx as u32 % width, idx as u32 / width);
            let area = pixel_area(p, i, j);
            let ok = if area == 0.0 {
                g == u
            } else {
                blended_near(*g, t.color, *u, area, opacity)
            };
            touched += usize::from(area > 0.0);
            assert!(
                ok,
                "{width}x{height}: anti-aliased pixel ({i}, {j}) {g:?} over {u:?}, area {area}"
            );
        }
    }
    assert!(
        touched > (width * height) as usize / 8,
        "{touched} anti-aliased pixels"
    );
    // The mask: the two triangles' areas summed, one colour blended once.
    let under = image.to_vec();
    let f = scene::MASK_FAN;
    let parts = [[f[0], f[1], f[2]], [f[0], f[2], f[3]]];
    let mut fb = SliceFramebuffer::new(image, width, height).unwrap();
    scene::render_antialiased_mask(&mut fb);
    for (idx, (g, u)) in image.iter().zip(&under).enumerate() {
        let (i, j) = (idx as u32 % width, idx as u32 / width);
        let inside = (4..28).contains(&i) && (4..20).contains(&j);
        let area: f64 = if inside {
            parts.iter().map(|p| pixel_area(*p, i, j)).sum()
        } else {
            0.0
        };
        let ok = if area == 0.0 {
            g == u
        } else {
            blended_near(*g, scene::MASK_COLOR, *u, area.min(1.0), 255)
        };
        assert!(
            ok,
            "{width}x{height}: mask pixel ({i}, {j}) {g:?} over {u:?}, area {area}"
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
