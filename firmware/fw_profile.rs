//! Profiling firmware: draws one triangle set many times with one renderer, for QEMU's
//! execution log (`-d in_asm,exec,nochain`), which `.ci/qprof.py` turns into instructions per
//! function. The renderer and set are chosen at build time with the `PROFILE` environment
//! variable, `<solid|gouraud|aa|polygon|opacity|linear|radial>[-dithered]-<large|small|tiny>`
//! (default `gouraud-tiny`; `aa`: solid anti-aliased; `linear`, `radial`: `fw_bench`'s
//! three-stop gradients; `-dithered`: the Gouraud or gradient fill ordered-dithered):
//!
//! ```text
//! PROFILE=solid-small cargo build --release --target thumbv6m-none-eabi --example fw_profile
//! ```
#![cfg_attr(target_os = "none", no_std, no_main)]

use embedded_graphics::pixelcolor::Rgb565;
use embedded_graphics::prelude::*;
use embedded_raster::{Coord, GouraudTriangle, Polygon, SliceFramebuffer, SolidTriangle, Vertex};

#[allow(dead_code)]
#[path = "../examples/common/scene.rs"]
mod scene;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

const PROFILE: &str = match option_env!("PROFILE") {
    Some(p) => p,
    None => "gouraud-tiny",
};

/// Triangles (corner pixel centres) of the chosen set on a `w × h` screen.
fn triangles(w: i32, h: i32) -> ([[(i32, i32); 3]; 4], u32) {
    let has = |s: &str| {
        PROFILE
            .as_bytes()
            .windows(s.len())
            .any(|x| x == s.as_bytes())
    };
    if has("large") {
        let t = scene::large_triangles(w, h);
        (t, 4)
    } else if has("small") {
        (
            [
                [(10, 10), (16, 11), (11, 15)],
                [(25, 10), (26, 16), (20, 13)],
                [(30, 25), (33, 20), (36, 24)],
                [(41, 21), (46, 25), (40, 26)],
            ],
            200,
        )
    } else {
        (
            [
                [(10, 10), (11, 10), (10, 11)],
                [(21, 10), (21, 11), (20, 11)],
                [(30, 20), (31, 21), (30, 21)],
                [(40, 20), (41, 20), (41, 21)],
            ],
            400,
        )
    }
}

fn draw(fb: &mut SliceFramebuffer<'_, Rgb565>) {
    let (w, h) = (fb.size().width as i32, fb.size().height as i32);
    let (set, reps) = triangles(w, h);
    let centre = |i: i32| Coord::from_bits(i * 256 + 128);
    let gouraud = PROFILE.starts_with("gouraud");
    let dithered = PROFILE.contains("dithered");
    let colors = [Rgb565::RED, Rgb565::GREEN, Rgb565::BLUE];
    for _ in 0..reps {
        for t in &set {
            if gouraud {
                let v = [0, 1, 2].map(|k| Vertex::new(centre(t[k].0), centre(t[k].1), colors[k]));
                if dithered {
                    GouraudTriangle::new(v).dithered().draw_into(fb);
                } else {
                    GouraudTriangle::new(v).draw_into(fb);
                }
            } else if PROFILE.starts_with("polygon") {
                let corners = t.map(|(x, y)| (centre(x), centre(y)));
                if let Ok(polygon) = Polygon::<3>::from_points(&corners) {
                    polygon.filled(Rgb565::RED).draw_into(fb);
                }
            } else if PROFILE.starts_with("linear") || PROFILE.starts_with("radial") {
                use embedded_raster::paint::{LinearGradient, RadialGradient, Stop, STOP_ONE};
                use embedded_raster::PaintedTriangle;
                let stops = [
                    Stop::new(0, Rgb565::new(31, 8, 2)),
                    Stop::new(STOP_ONE * 2 / 5, Rgb565::new(3, 60, 9)),
                    Stop::new(STOP_ONE, Rgb565::new(1, 12, 30)),
                ];
                let at = |x: i32, y: i32| (Coord::from_bits(x * 256), Coord::from_bits(y * 256));
                let points = t.map(|(x, y)| (centre(x), centre(y)));
                if PROFILE.starts_with("radial") {
                    let centre = at(w * 2 / 5, h / 2);
                    let mut g = RadialGradient::new(centre, Coord::from_bits(w * 256), stops);
                    if dithered {
                        g = g.dithered();
                    }
                    PaintedTriangle::new(points, g).draw_into(fb);
                } else {
                    let mut g = LinearGradient::new(at(0, 0), at(w, h), stops);
                    if dithered {
                        g = g.dithered();
                    }
                    PaintedTriangle::new(points, g).draw_into(fb);
                }
            } else if PROFILE.starts_with("opacity") {
                SolidTriangle::new(t.map(|(x, y)| (centre(x), centre(y))), Rgb565::RED)
                    .with_opacity(128)
                    .draw_into(fb);
            } else if PROFILE.starts_with("aa") {
                SolidTriangle::new(t.map(|(x, y)| (centre(x), centre(y))), Rgb565::RED)
                    .anti_aliased()
                    .draw_into(fb);
            } else {
                SolidTriangle::new(t.map(|(x, y)| (centre(x), centre(y))), Rgb565::RED)
                    .draw_into(fb);
            }
        }
    }
}

#[cfg(target_os = "none")]
mod firmware {
    use super::*;
    use crate::board::entry;

    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::BLACK; board::PIXELS];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the static's only reference.
        let pixels = unsafe { &mut *core::ptr::addr_of_mut!(PIXELS) };
        let (w, h) = board::SIZE;
        if let Ok(mut fb) = SliceFramebuffer::new(pixels, w, h) {
            draw(&mut fb);
        }
        board::exit(true)
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        board::exit(false)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    let mut pixels = [Rgb565::BLACK; 128 * 96];
    if let Ok(mut fb) = SliceFramebuffer::new(&mut pixels, 128, 96) {
        draw(&mut fb);
    }
    println!("{PROFILE}");
}
