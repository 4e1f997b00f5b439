//! Anti-aliased triangles against the exact area of each pixel square inside them.
//!
//! White over black in `Gray8` makes each pixel's value the alpha its coverage was blended with
//! (checked below for every alpha), so every pixel of random triangles — sub-pixel to far
//! beyond the target, slivers, vertices anywhere in the `Coord` range — is compared with
//! `255 ×` the `f64` polygon clip of `reference::pixel_area`: within 1/255 everywhere and ½/255 on
//! average over the pixels cut by an edge (the issue asks for 2/255 and 1/255); pixels the triangle does not reach stay untouched
//! and pixels wholly inside are the plain fill. Then every path (`draw_into`, `draw_reading`,
//! `over` a background, bands of every height) gives the same pixels.

use embedded_graphics::pixelcolor::{Gray8, Rgb565, Rgb888};
use embedded_graphics::prelude::*;
use embedded_raster::band::{BandDrawable, BandLayout, ColorBand};
use embedded_raster::reference;
use embedded_raster::{Coord, GouraudColor, SliceFramebuffer, SolidTriangle};

use crate::readable_target;
use readable_target::ReadableTarget;

use crate::rng;
use rng::Rng;

use crate::raw_points;
use raw_points::mixed_triangle;

const W: u32 = 53;
const H: u32 = 41;

fn triangle(rng: &mut Rng) -> [(i32, i32); 3] {
    mixed_triangle(rng, W, H)
}

fn coords(v: [(i32, i32); 3]) -> [(Coord, Coord); 3] {
    v.map(|(x, y)| (Coord::from_bits(x), Coord::from_bits(y)))
}

/// White at alpha `a` over black in Gray8 is `a`: the drawn value is the alpha.
#[test]
fn white_over_black_is_the_alpha() {
    for a in 0..=255u8 {
        assert_eq!(Gray8::WHITE.blend(Gray8::BLACK, a), Gray8::new(a));
    }
}

#[test]
fn coverage_is_within_two_levels_of_the_exact_area() {
    let mut rng = Rng(7);
    let (mut worst, mut sum, mut edge_pixels) = (0.0f64, 0.0f64, 0u64);
    for n in 0..3000 {
        let v = triangle(&mut rng);
        let mut pixels = vec![Gray8::BLACK; (W * H) as usize];
        let mut fb = SliceFramebuffer::new(&mut pixels, W, H).unwrap();
        SolidTriangle::new(coords(v), Gray8::WHITE)
            .anti_aliased()
            .draw_into(&mut fb);
        for y in 0..H as i32 {
            for x in 0..W as i32 {
                let area = reference::pixel_area(v, x, y);
                let got = f64::from(fb.get(x, y).unwrap().luma());
                if area == 0.0 || area == 1.0 {
                    assert_eq!(got, area * 255.0, "triangle {n} {v:?}, pixel ({x}, {y})");
                    continue;
                }
                let error = (got - area * 255.0).abs();
                // The issue asks for 2/255; the coverage is within 2⁻⁹ of the area, and its
                // alpha rounded: within 1/255.
                assert!(
                    error <= 1.0,
                    "triangle {n} {v:?}, pixel ({x}, {y}): {got} for an area of {area}"
                );
                worst = worst.max(error);
                sum += error;
                edge_pixels += 1;
            }
        }
    }
    let mean = sum / edge_pixels as f64;
    println!("{edge_pixels} pixels cut by an edge: error max {worst:.3}, mean {mean:.3} (of 255)");
    // At an opacity: the alpha is coverage × opacity, rounded.
    for _ in 0..500 {
        let v = triangle(&mut rng);
        let opacity = rng.below(256) as u8;
        let mut pixels = vec![Gray8::BLACK; (W * H) as usize];
        let mut fb = SliceFramebuffer::new(&mut pixels, W, H).unwrap();
        let aa = SolidTriangle::new(coords(v), Gray8::WHITE).anti_aliased();
        aa.with_opacity(opacity).draw_into(&mut fb);
        for y in 0..H as i32 {
            for x in 0..W as i32 {
                let want = reference::pixel_area(v, x, y) * f64::from(opacity);
                let got = f64::from(fb.get(x, y).unwrap().luma());
                assert!(
                    (got - want).abs() <= 1.0,
                    "{v:?} at {opacity}: ({x}, {y}) {got} for {want}"
                );
            }
        }
    }
    assert!(mean <= 0.5, "mean error {mean}");
    assert!(edge_pixels > 100_000);
}

fn paths_agree<C: GouraudColor + std::fmt::Debug>(seed: u64, count: usize) {
    let mut rng = Rng(seed);
    let color = |rng: &mut Rng| {
        C::from_channels(core::array::from_fn(|k| {
            rng.below(u64::from(C::MAX[k]) + 1) as u8
        }))
    };
    for _ in 0..count {
        let v = coords(triangle(&mut rng));
        let opacity = if rng.chance(2) {
            255
        } else {
            rng.below(256) as u8
        };
        let aa = SolidTriangle::new(v, color(&mut rng))
            .anti_aliased()
            .with_opacity(opacity);
        let under: Vec<C> = (0..W * H).map(|_| color(&mut rng)).collect();
        let mut want = under.clone();
        aa.draw_into(&mut SliceFramebuffer::new(&mut want, W, H).unwrap());

        let mut target = ReadableTarget::new(W, H, under.clone());
        aa.draw_reading(&mut target).unwrap();
        assert_eq!(target.pixels, want, "draw_reading");

        for rows in [1, 2, 5, 16, H] {
            let layout = BandLayout::new(Size::new(W, H), rows).unwrap();
            let mut buffer = vec![under[0]; layout.buffer_len()];
            for index in 0..layout.count() {
                let band_rect = layout.band(index).unwrap();
                let start = (band_rect.top_left.y as u32 * W) as usize;
                let len = (band_rect.size.height * W) as usize;
                buffer[..len].copy_from_slice(&under[start..start + len]);
                let mut band = ColorBand::new(&mut buffer, &layout, index).unwrap();
                band.draw(&aa);
                assert_eq!(
                    band.pixels(),
                    &want[start..start + len],
                    "{rows}-row band {index}"
                );
                // A bin keeps the triangle for every band it may reach.
                if let Some((first, last)) = aa.rows() {
                    let (top, bottom) = (
                        band_rect.top_left.y,
                        band_rect.top_left.y + band_rect.size.height as i32 - 1,
                    );
                    if last < top || first > bottom {
                        assert_eq!(
                            band.pixels(),
                            &under[start..start + len],
                            "rows() misses band {index}"
                        );
                    }
                }
            }
        }

        let uniform = color(&mut rng);
        let mut want = vec![uniform; (W * H) as usize];
        aa.draw_into(&mut SliceFramebuffer::new(&mut want, W, H).unwrap());
        let mut target = ReadableTarget::new(W, H, vec![uniform; (W * H) as usize]);
        aa.over(uniform).draw(&mut target).unwrap();
        assert_eq!(target.pixels, want, "over a background colour");
    }
}

#[test]
fn every_path_gives_the_same_pixels() {
    paths_agree::<Rgb565>(41, 400);
    paths_agree::<Rgb888>(42, 200);
}

/// A fan of 60 triangles around a sub-pixel centre (raw sub-pixels), radii 19 and 18 px.
fn fan60() -> Vec<[(i32, i32); 3]> {
    let (cx, cy) = (26 * 256 + 77, 20 * 256 + 161);
    let rim: Vec<(i32, i32)> = (0..60)
        .map(|k| {
            let a = f64::from(k) * std::f64::consts::TAU / 60.0;
            (
                cx + (4900.0 * a.cos()) as i32,
                cy + (4700.0 * a.sin()) as i32,
            )
        })
        .collect();
    (0..60)
        .map(|k| [(cx, cy), rim[k], rim[(k + 1) % 60]])
        .collect()
}

/// With every edge shared, the anti-aliased fill is the aliased one, pixel for pixel.
#[test]
fn all_edges_shared_is_the_aliased_fill() {
    let mut rng = Rng(51);
    for _ in 0..2000 {
        let v = coords(triangle(&mut rng));
        let mut aliased = vec![Gray8::BLACK; (W * H) as usize];
        SolidTriangle::new(v, Gray8::WHITE)
            .draw_into(&mut SliceFramebuffer::new(&mut aliased, W, H).unwrap());
        let mut shared = vec![Gray8::BLACK; (W * H) as usize];
        let aa = SolidTriangle::new(v, Gray8::WHITE)
            .anti_aliased()
            .with_shared_edges([true; 3]);
        aa.draw_into(&mut SliceFramebuffer::new(&mut shared, W, H).unwrap());
        assert_eq!(shared, aliased, "{v:?}");
    }
}

/// Draws `triangles` (raw vertices) white over black, anti-aliased with their shared edges
/// marked, and compares every pixel with the exact area of the union (the sum of the triangles'
/// areas: they do not overlap). Pixels wholly inside the union must be whole (no seam), pixels
/// outside it untouched; returns the largest error elsewhere (of 255) and the largest seam dip
/// of the same triangles drawn without marking their shared edges.
fn mesh_seams(triangles: &[[(i32, i32); 3]]) -> (f64, f64) {
    let key = |p: (i32, i32)| p;
    let shared = |t: &[(i32, i32); 3], i: usize| {
        let (a, b) = (key(t[i]), key(t[(i + 1) % 3]));
        triangles.iter().filter(|u| *u != t).any(|u| {
            (0..3).any(|j| (u[j] == a && u[(j + 1) % 3] == b) || (u[j] == b && u[(j + 1) % 3] == a))
        })
    };
    let mut seamless = vec![Gray8::BLACK; (W * H) as usize];
    let mut naive = vec![Gray8::BLACK; (W * H) as usize];
    for t in triangles {
        let aa = SolidTriangle::new(coords(*t), Gray8::WHITE).anti_aliased();
        aa.with_shared_edges([0, 1, 2].map(|i| shared(t, i)))
            .draw_into(&mut SliceFramebuffer::new(&mut seamless, W, H).unwrap());
        aa.draw_into(&mut SliceFramebuffer::new(&mut naive, W, H).unwrap());
    }
    let (mut worst, mut dip) = (0.0f64, 0.0f64);
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let area: f64 = triangles
                .iter()
                .map(|t| reference::pixel_area(*t, x, y))
                .sum();
            let i = (y as u32 * W + x as u32) as usize;
            let got = f64::from(seamless[i].luma());
            if area >= 1.0 - 1e-9 {
                assert_eq!(got, 255.0, "pixel ({x}, {y}) wholly inside the union");
                dip = dip.max(255.0 - f64::from(naive[i].luma()));
            } else if area <= 1e-9 {
                assert_eq!(got, 0.0, "pixel ({x}, {y}) outside the union");
            } else {
                worst = worst.max((got - 255.0 * area).abs());
            }
        }
    }
    (worst, dip)
}

/// A fan of 60 thin triangles around a sub-pixel centre, and jittered grids of triangles: no seam
/// anywhere inside; where the outline turns inside a pixel, its error is reported.
#[test]
fn meshes_with_shared_edges_have_no_seams() {
    let fan = fan60();
    let (worst, dip) = mesh_seams(&fan);
    println!("fan: outline error up to {worst:.2}/255; without shared edges, seams dip {dip}/255");
    // The rim turns by 6° a vertex: the owner of a pixel there misses little of the turn.
    assert!(worst <= 8.0 && dip > 32.0, "{worst} {dip}");

    let mut rng = Rng(61);
    for n in 0..20 {
        let (cols, rows) = (2 + rng.below(6) as usize, 2 + rng.below(5) as usize);
        let grid: Vec<Vec<(i32, i32)>> = (0..=rows)
            .map(|j| {
                (0..=cols)
                    .map(|i| {
                        let x = 300 + (i as i64 * 12_000 / cols as i64) + rng.range(-300, 300);
                        let y = 300 + (j as i64 * 9_500 / rows as i64) + rng.range(-300, 300);
                        (x as i32, y as i32)
                    })
                    .collect()
            })
            .collect();
        let mut mesh = Vec::new();
        for j in 0..rows {
            for i in 0..cols {
                let (a, b, c, d) = (
                    grid[j][i],
                    grid[j][i + 1],
                    grid[j + 1][i + 1],
                    grid[j + 1][i],
                );
                if rng.chance(2) {
                    mesh.push([a, b, c]);
                    mesh.push([a, c, d]);
                } else {
                    mesh.push([a, b, d]);
                    mesh.push([b, c, d]);
                }
            }
        }
        let (worst, dip) = mesh_seams(&mesh);
        println!(
            "mesh {n}: outline error up to {worst:.2}/255, seams without sharing dip {dip}/255"
        );
        // Where the outline turns inside a pixel, the triangle that owns the pixel by its
        // centre blends its own outline edge only: off by the area between the two edges there.
        assert!(worst < 128.0, "{worst}");
    }
}

/// The union's exact area against a coverage mask's fill of the same triangles, opaque and at
/// other opacities: every pixel within 1/255 of `opacity ×` the area (the outline's turns
/// included), in the frame and in bands of every height.
fn mask_against_union(triangles: &[[(i32, i32); 3]]) -> f64 {
    [255, 200, 128, 31, 0]
        .into_iter()
        .map(|opacity| mask_against_union_at(triangles, opacity))
        .fold(0.0, f64::max)
}

fn mask_against_union_at(triangles: &[[(i32, i32); 3]], opacity: u8) -> f64 {
    use embedded_graphics::primitives::Rectangle;
    use embedded_raster::CoverageMask;
    let frame = Rectangle::new(Point::zero(), Size::new(W, H));
    let mut cells = vec![0u16; (W * H) as usize];
    let mut pixels = vec![Gray8::BLACK; (W * H) as usize];
    let mut fb = SliceFramebuffer::new(&mut pixels, W, H).unwrap();
    let mut mask = CoverageMask::new(&mut cells, frame).unwrap();
    for t in triangles {
        mask.add(coords(*t));
    }
    match opacity {
        255 => mask.fill_into(Gray8::WHITE, &mut fb),
        _ => mask.fill_translucent_into(Gray8::WHITE, opacity, &mut fb),
    }
    // Cleared: a second fill draws nothing.
    mask.fill_into(Gray8::new(7), &mut fb);
    let mut worst = 0.0f64;
    for y in 0..H as i32 {
        for x in 0..W as i32 {
            let area: f64 = triangles
                .iter()
                .map(|t| reference::pixel_area(*t, x, y))
                .sum();
            let got = f64::from(fb.get(x, y).unwrap().luma());
            let error = (got - f64::from(opacity) * area.min(1.0)).abs();
            assert!(
                error <= 1.0,
                "pixel ({x}, {y}): {got} for an area of {area} at opacity {opacity}"
            );
            worst = worst.max(error);
        }
    }
    for rows in [1, 3, 16] {
        let layout = BandLayout::new(Size::new(W, H), rows).unwrap();
        let mut buffer = vec![Gray8::BLACK; layout.buffer_len()];
        let mut band_cells = vec![0u16; layout.buffer_len()];
        for index in 0..layout.count() {
            let rect = layout.band(index).unwrap();
            let mut band = ColorBand::new(&mut buffer, &layout, index).unwrap();
            band.clear(Gray8::BLACK);
            let mut mask = CoverageMask::new(&mut band_cells, rect).unwrap();
            for t in triangles {
                mask.add(coords(*t));
            }
            match opacity {
                255 => band.fill_mask(&mut mask, Gray8::WHITE),
                _ => band.fill_mask_translucent(&mut mask, Gray8::WHITE, opacity),
            }
            let start = (rect.top_left.y as u32 * W) as usize;
            let len = (rect.size.height * W) as usize;
            assert_eq!(
                band.pixels(),
                &fb.pixels()[start..start + len],
                "{rows}-row band {index}"
            );
        }
    }
    worst
}

#[test]
fn a_coverage_mask_is_the_union_within_one_level() {
    let fan = fan60();
    println!("fan: {:.2}/255", mask_against_union(&fan));
    let mut rng = Rng(71);
    for _ in 0..20 {
        let (cols, rows) = (2 + rng.below(6) as i64, 2 + rng.below(5) as i64);
        let point = |i: i64, j: i64, rng: &mut Rng| {
            let x = 400 + i * 12_000 / cols + rng.range(-300, 300);
            let y = 400 + j * 9_500 / rows + rng.range(-300, 300);
            (x as i32, y as i32)
        };
        let grid: Vec<Vec<(i32, i32)>> = (0..=rows)
            .map(|j| (0..=cols).map(|i| point(i, j, &mut rng)).collect())
            .collect();
        let mut mesh = Vec::new();
        for j in 0..rows as usize {
            for i in 0..cols as usize {
                let (a, b, c, d) = (
                    grid[j][i],
                    grid[j][i + 1],
                    grid[j + 1][i + 1],
                    grid[j + 1][i],
                );
                mesh.push([a, b, c]);
                mesh.push([a, c, d]);
            }
        }
        println!("grid: {:.2}/255", mask_against_union(&mesh));
    }
    // Random triangles one at a time (overlaps saturate, so one each).
    for _ in 0..300 {
        mask_against_union(&[triangle(&mut rng)]);
    }
}
