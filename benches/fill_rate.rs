//! Host fill-rate benchmarks on a 320×240 `Rgb565` screen.
//!
//! Three triangle-size mixes (≈16 px², ≈1,000 px², screen-filling), each drawn with:
//! our `SolidTriangle` and `GouraudTriangle` (fast `draw_into` path and the generic `Drawable`
//! path, on our `SliceFramebuffer` and on embedded-graphics' `Framebuffer`), embedded-graphics'
//! filled `Triangle` (on both targets) and a textbook per-pixel `f32` barycentric rasterizer.
//!
//! Throughput is `Elements` = pixels one pass over the set writes, counted once outside the timed
//! loop with each method's *own* coverage: `raster::for_each_span` for ours, a counting draw
//! target for embedded-graphics' `Triangle` (integer vertices, its own fill convention) and the
//! naive rasterizer's own inside test. Criterion's "elem/s" is therefore pixels per second.
//!
//! ```text
//! cargo bench --bench fill_rate -- --warm-up-time 1 --measurement-time 3
//! ```
//!
//! Criterion measures one method at a time; for ratios measured side by side in one process (what
//! the README quotes) run `cargo run --release --example bench_report`.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

#[path = "fill_rate/workload.rs"]
mod workload;

use workload::{draw_set, pixel_count, triangles, Method, SizeClass, Targets};

fn fill_rate(c: &mut Criterion) {
    let mut targets = Targets::new();
    for class in SizeClass::ALL {
        let tris = triangles(class);
        let mut group = c.benchmark_group(format!("fill_rate/{}", class.id()));
        for method in Method::ALL {
            group.throughput(Throughput::Elements(pixel_count(method, &tris)));
            group.bench_function(method.id(), |b| {
                b.iter(|| {
                    draw_set(method, black_box(&tris), &mut targets);
                    black_box(&mut targets);
                })
            });
        }
        group.finish();
    }
}

criterion_group!(benches, fill_rate);
criterion_main!(benches);
