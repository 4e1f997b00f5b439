//! Renders the README pictures into `docs/`:
//!
//! * `gouraud.png` — Gouraud triangles on a 320×240 Rgb565 screen, some crossing its edges;
//! * `fan.png` — a fan of thin triangles around a sub-pixel centre, and next to it how often each
//!   pixel was drawn (white once, red more than once, black never inside the fan);
//! * `heatmap.png` — per-pixel colour error against the f64 reference, in LSB of Rgb888, with
//!   its legend below the map;
//! * `antialias.png` — the same shapes aliased, anti-aliased triangle by triangle, and as one
//!   coverage mask, at 4×;
//! * `translucent.png` — a Gouraud scene under translucent triangles: one opacity, an alpha per
//!   vertex, and an anti-aliased one;
//! * `polygons.png` — filled polygons: a self-intersecting star under the non-zero and the
//!   even-odd rule, and a shape with holes (two contours inside an outline), at 3×;
//! * `lines.png` — lines: a plot of a thin and a 2.5 px wide polyline (round joins and caps) at
//!   sub-pixel points, and a fan of thin lines from one sub-pixel point, at 3×.
//!
//! Run with `cargo run --release --example gallery`.

use embedded_graphics::image::Image;
use embedded_graphics::{
    mono_font::{ascii::FONT_5X8, MonoTextStyle},
    pixelcolor::{Rgb565, Rgb888},
    prelude::*,
    primitives::Rectangle,
    text::{Alignment, Text},
};
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use embedded_raster::{
    Cap, Coord, CoverageMask, FillRule, GouraudTriangle, Join, Line, Polygon, Polyline,
    SliceFramebuffer, SolidTriangle, Stroke, Vertex,
};

// The f64 reference, compiled in directly so that the example needs no cargo feature
// (it is `embedded_raster::reference` with the `reference` feature).
#[allow(dead_code, unused_imports)]
#[path = "../src/reference/mod.rs"]
mod reference;

fn coord(v: f64) -> Coord {
    Coord::from_num(v)
}

fn vertex<C>(x: f64, y: f64, color: C) -> Vertex<C> {
    Vertex::new(coord(x), coord(y), color)
}

fn save<C>(display: &SimulatorDisplay<C>, scale: u32, name: &str)
where
    C: PixelColor + Into<Rgb888>,
{
    let settings = OutputSettingsBuilder::new().scale(scale).build();
    let path = format!("docs/{name}");
    display
        .to_rgb_output_image(&settings)
        .save_png(&path)
        .expect("write PNG");
    println!("wrote {path}");
}

fn gouraud() {
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(320, 240));
    let triangles = [
        [
            vertex(20.0, 12.5, Rgb565::RED),
            vertex(300.25, 60.0, Rgb565::GREEN),
            vertex(110.75, 228.0, Rgb565::BLUE),
        ],
        [
            vertex(250.0, 120.0, Rgb565::YELLOW),
            vertex(380.0, 250.0, Rgb565::MAGENTA),
            vertex(200.5, 300.0, Rgb565::CYAN),
        ],
        [
            vertex(-60.0, 150.0, Rgb565::WHITE),
            vertex(70.0, 200.0, Rgb565::new(8, 16, 8)),
            vertex(-10.0, 260.0, Rgb565::RED),
        ],
    ];
    for t in triangles {
        GouraudTriangle::new(t).draw(&mut display).unwrap();
    }
    save(&display, 2, "gouraud.png");
}

/// A fan of `n` triangles around a sub-pixel centre, alternating winding.
fn fan(n: usize, cx: f64, cy: f64, r: f64) -> Vec<[(f64, f64); 3]> {
    let at = |k: usize| {
        let a = k as f64 * core::f64::consts::TAU / n as f64 + 0.1;
        (cx + r * a.cos(), cy + r * a.sin())
    };
    (0..n)
        .map(|k| {
            if k % 2 == 0 {
                [(cx, cy), at(k), at(k + 1)]
            } else {
                [(cx, cy), at(k + 1), at(k)]
            }
        })
        .collect()
}

fn fan_picture() {
    let (w, h) = (160u32, 120u32);
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(2 * w + 8, h));
    let triangles = fan(60, 80.3, 61.7, 56.0);
    let palette = [
        Rgb888::CSS_ORANGE,
        Rgb888::CSS_TEAL,
        Rgb888::CSS_PURPLE,
        Rgb888::CSS_GOLD,
    ];
    let mut counts = vec![0u8; (w * h) as usize];
    for (k, t) in triangles.iter().enumerate() {
        let c = palette[k % palette.len()];
        let dark = Rgb888::new(c.r() / 4, c.g() / 4, c.b() / 4);
        let v = [
            vertex(t[0].0, t[0].1, Rgb888::WHITE),
            vertex(t[1].0, t[1].1, c),
            vertex(t[2].0, t[2].1, dark),
        ];
        let mut left = display.clipped(&Rectangle::new(Point::zero(), Size::new(w, h)));
        GouraudTriangle::new(v).draw(&mut left).unwrap();
        embedded_raster::raster::for_each_span(
            t.map(|(x, y)| (coord(x), coord(y))),
            Rectangle::new(Point::zero(), Size::new(w, h)),
            |y, x0, x1| {
                for x in x0..x1 {
                    counts[(y as u32 * w + x as u32) as usize] += 1;
                }
            },
        );
    }
    let (mut gaps, mut overlaps) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let inside = triangles.iter().any(|t| {
                reference::covers(
                    t.map(|(x, y)| (coord(x).to_bits(), coord(y).to_bits())),
                    x as i32,
                    y as i32,
                )
            });
            let color = match counts[(y * w + x) as usize] {
                0 if inside => {
                    gaps += 1;
                    Rgb888::BLACK
                }
                0 => Rgb888::new(40, 40, 48),
                1 => Rgb888::WHITE,
                _ => {
                    overlaps += 1;
                    Rgb888::RED
                }
            };
            Pixel(Point::new((w + 8 + x) as i32, y as i32), color)
                .draw(&mut display)
                .unwrap();
        }
    }
    println!(
        "fan: {} triangles, {gaps} gaps, {overlaps} pixels drawn twice",
        triangles.len()
    );
    save(&display, 3, "fan.png");
}

fn heatmap() {
    let (w, h) = (160u32, 120u32);
    let mut pixels = vec![Rgb888::BLACK; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, w, h).unwrap();
    let mut error = vec![f64::NAN; (w * h) as usize];
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    let mut max_err: f64 = 0.0;
    for _ in 0..40 {
        let v: [Vertex<Rgb888>; 3] = core::array::from_fn(|_| {
            let x = (rnd() % (w as u64 * 256 + 4000)) as i32 - 2000;
            let y = (rnd() % (h as u64 * 256 + 4000)) as i32 - 2000;
            let c = rnd();
            Vertex::new(
                Coord::from_bits(x),
                Coord::from_bits(y),
                Rgb888::new(c as u8, (c >> 8) as u8, (c >> 16) as u8),
            )
        });
        GouraudTriangle::new(v).draw(&mut fb).unwrap();
        let raw = v.map(|v| (v.x.to_bits(), v.y.to_bits()));
        let channels = v.map(|v| [v.color.r(), v.color.g(), v.color.b()].map(f64::from));
        reference::for_each_covered(raw, 0, 0, w as i32, h as i32, |x, y| {
            let exact = reference::interpolate(raw, channels, x, y).unwrap();
            let got = fb.get(x, y).unwrap();
            let got = [got.r(), got.g(), got.b()].map(f64::from);
            let e = (0..3)
                .map(|k| (got[k] - exact[k]).abs())
                .fold(0.0, f64::max);
            error[(y as u32 * w + x as u32) as usize] = e;
            max_err = max_err.max(e);
        });
    }
    // The map, and below it its legend: the colour scale from 0 to 1 LSB and the colour of
    // pixels no triangle covers.
    let legend = 22;
    let mut display = SimulatorDisplay::<Rgb888>::new(Size::new(w, h + legend));
    for y in 0..h {
        for x in 0..w {
            let e = error[(y * w + x) as usize];
            Pixel(Point::new(x as i32, y as i32), error_color(e))
                .draw(&mut display)
                .unwrap();
        }
    }
    let text = MonoTextStyle::new(&FONT_5X8, Rgb888::WHITE);
    let (bar_x, bar_w, bar_y) = (8, 90, h as i32 + 3);
    for x in 0..=bar_w {
        let color = error_color(f64::from(x) / f64::from(bar_w));
        for y in 0..6 {
            Pixel(Point::new(bar_x + x, bar_y + y), color)
                .draw(&mut display)
                .unwrap();
        }
    }
    for (label, at) in [("0", 0), ("0.5", bar_w / 2), ("1 LSB", bar_w)] {
        Text::with_alignment(
            label,
            Point::new(bar_x + at, bar_y + 14),
            text,
            Alignment::Center,
        )
        .draw(&mut display)
        .unwrap();
    }
    let none = Rectangle::new(Point::new(bar_x + bar_w + 24, bar_y), Size::new(6, 6));
    none.into_styled(embedded_graphics::primitives::PrimitiveStyle::with_fill(
        error_color(f64::NAN),
    ))
    .draw(&mut display)
    .unwrap();
    Text::with_alignment(
        "none",
        Point::new(bar_x + bar_w + 33, bar_y + 6),
        text,
        Alignment::Left,
    )
    .draw(&mut display)
    .unwrap();
    println!("heatmap: max error {max_err:.4} LSB (Rgb888) over 40 random triangles");
    save(&display, 3, "heatmap.png");
}

/// The heat map's colour of an error of `e` LSB: blue at 0, green at ½, red at 1 and above;
/// dark grey for a pixel no triangle covers (`NaN`).
fn error_color(e: f64) -> Rgb888 {
    if e.is_nan() {
        return Rgb888::new(24, 24, 24);
    }
    let t = (e.clamp(0.0, 1.0) * 510.0) as u32;
    let (r, g, b) = if t < 255 {
        (0, t, 255 - t)
    } else {
        (t - 255, 510 - t, 0)
    };
    Rgb888::new(r as u8, g as u8, b as u8)
}

/// A star of `n` spikes around `(cx, cy)` as triangles from the centre: each spike two.
fn star(cx: f64, cy: f64, outer: f64, inner: f64, n: usize, turn: f64) -> Vec<[(f64, f64); 3]> {
    let at = |k: usize, r: f64| {
        let a = k as f64 * core::f64::consts::PI / n as f64 + turn;
        (cx + r * a.cos(), cy + r * a.sin())
    };
    (0..2 * n)
        .map(|k| {
            let r = |k: usize| if k % 2 == 0 { outer } else { inner };
            [(cx, cy), at(k, r(k)), at(k + 1, r(k + 1))]
        })
        .collect()
}

fn antialias_picture() {
    let (w, h) = (72u32, 56u32);
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(3 * w + 8, h));
    let background = Rgb565::new(3, 8, 6);
    let thin = [(4.3, 50.2), (66.7, 6.4), (68.9, 10.1)];
    let tilted = [(6.2, 4.7), (30.5, 9.3), (12.8, 33.6)];
    let shapes = star(46.3, 34.4, 20.5, 8.2, 5, 0.3);
    for panel in 0..3 {
        let mut pixels = vec![background; (w * h) as usize];
        let mut fb = SliceFramebuffer::new(&mut pixels, w, h).unwrap();
        let mut cells = vec![0u16; (w * h) as usize];
        let mut mask = CoverageMask::new(&mut cells, fb.bounding_box()).unwrap();
        for (points, color) in [(thin, Rgb565::CSS_GOLD), (tilted, Rgb565::CSS_TOMATO)] {
            let t = SolidTriangle::new(points, color);
            match panel {
                0 => t.draw_into(&mut fb),
                _ => t.anti_aliased().draw_into(&mut fb),
            }
        }
        for points in &shapes {
            let t = SolidTriangle::new(*points, Rgb565::CSS_LIGHT_SKY_BLUE);
            match panel {
                0 => t.draw_into(&mut fb),
                1 => t.anti_aliased().draw_into(&mut fb),
                _ => mask.add_triangle(&t),
            }
        }
        mask.fill_into(Rgb565::CSS_LIGHT_SKY_BLUE, &mut fb);
        let at = Point::new(panel * (w as i32 + 4), 0);
        Image::new(&fb, at).draw(&mut display).unwrap();
    }
    save(&display, 4, "antialias.png");
}

fn translucent_picture() {
    let (w, h) = (160u32, 120u32);
    let mut pixels = vec![Rgb565::BLACK; (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, w, h).unwrap();
    let scene = [
        [
            vertex(6.0, 8.5, Rgb565::RED),
            vertex(150.25, 30.0, Rgb565::GREEN),
            vertex(55.75, 114.0, Rgb565::BLUE),
        ],
        [
            vertex(125.0, 60.0, Rgb565::YELLOW),
            vertex(190.0, 125.0, Rgb565::MAGENTA),
            vertex(100.5, 150.0, Rgb565::CYAN),
        ],
    ];
    for t in scene {
        GouraudTriangle::new(t).draw_into(&mut fb);
    }
    // A panel at half opacity, a white fade (an alpha per vertex), an anti-aliased tint.
    let panel = [(20.0, 70.0), (140.0, 70.0), (140.0, 108.0), (20.0, 108.0)];
    for [a, b, c] in [[0, 1, 2], [0, 2, 3]] {
        SolidTriangle::new([panel[a], panel[b], panel[c]], Rgb565::BLACK)
            .with_opacity(150)
            .draw_into(&mut fb);
    }
    GouraudTriangle::new([
        vertex(90.0, 4.0, Rgb565::WHITE),
        vertex(156.0, 4.0, Rgb565::WHITE),
        vertex(156.0, 60.0, Rgb565::CSS_ORANGE),
    ])
    .with_alpha([0, 230, 120])
    .draw_into(&mut fb);
    SolidTriangle::new([(8.3, 20.1), (70.6, 44.8), (30.2, 62.9)], Rgb565::CSS_AQUA)
        .anti_aliased()
        .draw_into(&mut fb);
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(w, h));
    Image::new(&fb, Point::zero()).draw(&mut display).unwrap();
    save(&display, 2, "translucent.png");
}

/// The points of a regular star polygon {n/k} around `(cx, cy)`: every `k`-th of `n` points on
/// a circle, so the contour crosses itself (winding numbers up to `k` inside).
fn star_polygon(cx: f64, cy: f64, r: f64, n: usize, k: usize, turn: f64) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let t = turn + (i * k % n) as f64 * std::f64::consts::TAU / n as f64;
            (cx + r * t.sin(), cy - r * t.cos())
        })
        .collect()
}

fn polygons_picture() {
    let (w, h) = (88u32, 96u32);
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(3 * w + 8, h));
    let background = Rgb565::new(3, 8, 6);
    let label = MonoTextStyle::new(&FONT_5X8, Rgb565::WHITE);
    let star = star_polygon(44.3, 42.6, 38.2, 9, 4, 0.1);
    for panel in 0..3 {
        let mut pixels = vec![background; (w * h) as usize];
        let mut fb = SliceFramebuffer::new(&mut pixels, w, h).unwrap();
        let text = match panel {
            0 | 1 => {
                let polygon = Polygon::<9>::from_points(&star).unwrap();
                let (rule, text) = if panel == 0 {
                    (FillRule::NonZero, "non-zero")
                } else {
                    (FillRule::EvenOdd, "even-odd")
                };
                polygon
                    .filled(Rgb565::CSS_GOLD)
                    .with_rule(rule)
                    .draw_into(&mut fb);
                text
            }
            _ => {
                // An outline with two holes: the holes run the other way round, so both rules
                // cut them.
                let mut shape = Polygon::<24>::new();
                let outline = star_polygon(44.0, 43.0, 40.5, 12, 1, 0.13);
                let outline: Vec<(f64, f64)> = outline
                    .iter()
                    .enumerate()
                    .map(|(i, &(x, y))| {
                        let s = if i % 2 == 0 { 1.0 } else { 0.72 };
                        (44.0 + (x - 44.0) * s, 43.0 + (y - 43.0) * s)
                    })
                    .collect();
                shape.add_contour(&outline).unwrap();
                let mut hole = star_polygon(31.7, 36.2, 9.4, 6, 1, 0.0);
                hole.reverse();
                shape.add_contour(&hole).unwrap();
                let mut slot = vec![(48.3, 47.1), (61.8, 47.1), (61.8, 63.4), (48.3, 63.4)];
                slot.reverse();
                shape.add_contour(&slot).unwrap();
                shape.filled(Rgb565::CSS_LIGHT_SKY_BLUE).draw_into(&mut fb);
                "holes"
            }
        };
        let at = Point::new(panel * (w as i32 + 4), 0);
        Image::new(&fb, at).draw(&mut display).unwrap();
        Text::with_alignment(
            text,
            at + Point::new(w as i32 / 2, h as i32 - 3),
            label,
            Alignment::Center,
        )
        .draw(&mut display)
        .unwrap();
    }
    save(&display, 3, "polygons.png");
}

fn lines_picture() {
    let (w, h) = (120u32, 80u32);
    let mut pixels = vec![Rgb565::new(3, 8, 6); (w * h) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, w, h).unwrap();
    let grid = Rgb565::new(6, 14, 10);
    for k in 0..6 {
        let y = 8.5 + 12.0 * f64::from(k);
        Line::new((6.5, y), (76.5, y), grid).draw_into(&mut fb);
    }
    Line::new((6.5, 4.5), (6.5, 70.5), Rgb565::WHITE).draw_into(&mut fb);
    Line::new((6.5, 70.5), (77.5, 70.5), Rgb565::WHITE).draw_into(&mut fb);
    // Two series at sub-pixel points: a damped wave and a slow rise.
    let wave: Vec<(f64, f64)> = (0..=70)
        .map(|i| {
            let x = f64::from(i);
            (6.5 + x, 38.0 - 28.0 * (x / 5.3).sin() * (-x / 45.0).exp())
        })
        .collect();
    Polyline::new(&wave, Rgb565::CSS_GOLD).draw_into(&mut fb);
    let rise: Vec<(f64, f64)> = (0..=14)
        .map(|i| {
            let x = 5.0 * f64::from(i);
            (6.5 + x, 66.0 - 0.012 * x * x - 2.5 * (x / 2.0).sin())
        })
        .collect();
    let stroke = Stroke::new(2.5).with_cap(Cap::Round).with_join(Join::Round);
    Polyline::new(&rise, Rgb565::CSS_LIGHT_SKY_BLUE)
        .stroked(stroke)
        .draw_into(&mut fb);
    // A fan of 24 lines from one sub-pixel point, each leaving the point's pixel.
    let (cx, cy) = (99.3, 39.6);
    for k in 0..24 {
        let t = f64::from(k) * std::f64::consts::TAU / 24.0;
        Line::new(
            (cx, cy),
            (cx + 18.5 * t.cos(), cy + 30.0 * t.sin()),
            Rgb565::CSS_TOMATO,
        )
        .draw_into(&mut fb);
    }
    let mut display = SimulatorDisplay::<Rgb565>::new(Size::new(w, h));
    Image::new(&fb, Point::zero()).draw(&mut display).unwrap();
    save(&display, 3, "lines.png");
}

fn main() {
    std::fs::create_dir_all("docs").expect("create docs/");
    gouraud();
    fan_picture();
    heatmap();
    antialias_picture();
    translucent_picture();
    polygons_picture();
    lines_picture();
}
