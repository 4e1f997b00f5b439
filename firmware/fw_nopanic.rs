//! Firmware that only links if the drawing code has no panic paths left after optimisation.
//!
//! Its `#[panic_handler]` calls a function that does not exist, so any reachable call to
//! `core::panicking::*` (an `unwrap`, a bounds check, a division by zero, ...) makes the release
//! link fail with `undefined symbol: embedded_raster_drawing_code_can_panic`. (To find the panic
//! site, disassemble `fw_scene` and look for calls to `core::panicking`.) Everything drawn goes
//! through `core::hint::black_box` (triangles, colours, framebuffer dimensions, clip rectangles),
//! so the optimiser cannot prove anything from constants: what links is panic-free for all inputs
//! the types allow. Debug builds keep their panics, so there the handler just exits with failure.
//!
//! It draws the shared scene (checksum printed like `fw_scene`, so the run is checked too), the
//! same triangles in other colour formats through both `draw` and `draw_into`, their spans
//! under arbitrary clip rectangles, the framebuffer's `DrawTarget` fills on arbitrary
//! rectangles, and a flash mesh through the 3D pipeline (`draw_mesh` and `draw_mesh_with`, every
//! shading and culling, with and without a specular highlight, opaque matrices, viewport and
//! lights, with the first light alone and with point and directional lights; its wireframe, but
//! on ARMv6-M, whose micro:bit flash has no room for it). Textured drawing
//! has a firmware of its own, `fw_nopanic_textures`.
//!
//! ```text
//! cargo run --release --target thumbv6m-none-eabi --example fw_nopanic
//! ```
#![cfg_attr(target_os = "none", no_std, no_main)]

#[allow(dead_code)]
#[path = "../examples/common/scene.rs"]
mod scene;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[path = "common/nopanic.rs"]
mod nopanic;

#[cfg(target_os = "none")]
#[path = "common/plain_print.rs"]
mod plain_print;

#[cfg(target_os = "none")]
#[path = "common/stack.rs"]
mod stack;

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;

    use crate::board::entry;
    use embedded_graphics::pixelcolor::raw::RawU16;
    use embedded_graphics::pixelcolor::{BinaryColor, Gray8, Rgb565, Rgb888};
    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::Rectangle;
    use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
    use embedded_raster::three_d::{
        Angle, Cull, DepthTarget, Light, LightSource, Lights, Mat4, Material, Pipeline,
        ProjectedVertex, Scalar, Shading, Specular, Vec3,
    };
    use embedded_raster::{
        raster::for_each_span, GouraudColor, GouraudTriangle, SliceFramebuffer, SolidTriangle,
        Vertex,
    };

    use crate::plain_print::{decimal, hex, print};
    use crate::{board, scene};

    /// Size of the framebuffers for the other colour formats.
    const SMALL: (u32, u32) = (24, 16);
    const SMALL_PIXELS: usize = (SMALL.0 * SMALL.1) as usize;

    /// Draws a scene shape recoloured to `C` both ways into `fb`, with opaque inputs.
    fn draw_as<C: GouraudColor>(
        shape: scene::Shape,
        fb: &mut SliceFramebuffer<'_, C>,
        map: fn(Rgb565) -> C,
    ) {
        match shape {
            scene::Shape::Gouraud(t) => {
                let t = black_box(GouraudTriangle::new(
                    t.vertices.map(|v| Vertex::new(v.x, v.y, map(v.color))),
                ));
                let _ = t.draw(fb);
                t.draw_into(fb);
            }
            scene::Shape::Solid(t) => {
                let t = black_box(SolidTriangle::new(t.points, map(t.color)));
                let _ = t.draw(fb);
                t.draw_into(fb);
            }
        }
    }

    /// The scene's shapes in other colour formats through both entry points, and their spans
    /// under a clip rectangle, into `sw × sh` framebuffers on the stack (out of line: the
    /// stack they take is free again for the 3D draws, which the micro:bit's 16 KiB of RAM
    /// needs).
    #[inline(never)]
    fn other_formats(sw: u32, sh: u32) {
        let mut rgb888_pixels = [Rgb888::new(0, 0, 0); SMALL_PIXELS];
        let mut gray8_pixels = [Gray8::new(0); SMALL_PIXELS];
        let mut binary_pixels = [BinaryColor::Off; SMALL_PIXELS];
        let mut rgb888 = SliceFramebuffer::new(&mut rgb888_pixels, sw, sh).ok();
        let mut gray8 = SliceFramebuffer::new(&mut gray8_pixels, sw, sh).ok();
        let mut binary = SliceFramebuffer::new(&mut binary_pixels, sw, sh).ok();
        let mut spans = 0u32;
        scene::for_each_shape(sw, sh, |shape| {
            let shape = black_box(shape);
            if let Some(fb) = rgb888.as_mut() {
                draw_as(shape, fb, Rgb888::from);
            }
            if let Some(fb) = gray8.as_mut() {
                draw_as(shape, fb, |c| Gray8::new(c.g() << 2));
            }
            if let Some(fb) = binary.as_mut() {
                draw_as(shape, fb, |c| BinaryColor::from(c.r() > 15));
            }
            // Spans under an arbitrary clip rectangle.
            let clip = black_box(Rectangle::new(Point::new(-3, 2), Size::new(40, 9)));
            for_each_span(
                black_box(shape.raw_positions()).map(|(x, y)| {
                    (
                        embedded_raster::Coord::from_bits(x),
                        embedded_raster::Coord::from_bits(y),
                    )
                }),
                clip,
                |_, x0, x1| {
                    spans = spans.wrapping_add(x1.wrapping_sub(x0) as u32);
                },
            );
        });
        black_box(spans);
        black_box((
            rgb888.as_ref().map(|f| f.pixels()),
            gray8.as_ref().map(|f| f.pixels()),
        ));
        black_box(binary.as_ref().map(|f| f.pixels()));
    }

    static mut PIXELS: [Rgb565; board::PIXELS] = [Rgb565::new(0, 0, 0); board::PIXELS];
    static mut DEPTH_3D: [u16; SMALL_PIXELS] = [0; SMALL_PIXELS];
    static mut SCRATCH: [ProjectedVertex; 42] = [ProjectedVertex::EMPTY; 42];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the statics' only references.
        let (pixels, depth_3d, scratch) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(PIXELS),
                &mut *core::ptr::addr_of_mut!(DEPTH_3D),
                &mut *core::ptr::addr_of_mut!(SCRATCH),
            )
        };
        crate::stack::paint_run();

        // The scene, exactly as fw_scene draws it but into a framebuffer of opaque size.
        let (width, height) = black_box(board::SIZE);
        let Ok(mut fb) = SliceFramebuffer::new(pixels, width, height) else {
            board::exit(false)
        };
        scene::render(&mut fb);
        // The same line as fw_scene's `scene::ChecksumLine`.
        print(b"scene ");
        decimal(u64::from(width));
        print(b"x");
        decimal(u64::from(height));
        print(b" fnv1a=0x");
        hex(scene::checksum(fb.pixels()));
        print(b"\n");

        // Other colour formats, both entry points, opaque framebuffer sizes.
        let (sw, sh) = black_box(SMALL);
        other_formats(sw, sh);

        // The framebuffer's DrawTarget methods on opaque rectangles and pixels (any corner in
        // i32, any size, past i32::MAX too).
        let areas = black_box([
            Rectangle::new(Point::new(-5, 3), Size::new(3_000_000_000, 1 << 31)),
            Rectangle::new(Point::new(i32::MAX - 1, 0), Size::new(2, 1)),
            Rectangle::new(Point::new(2, 1), Size::new(7, 5)),
        ]);
        for area in &areas {
            let _ = fb.fill_solid(area, black_box(Rgb565::WHITE));
            // A slice iterator skips off-screen colours in constant time.
            let colors: [Rgb565; 64] = black_box(core::array::from_fn(|i| {
                Rgb565::from(RawU16::new(i as u16))
            }));
            let _ = fb.fill_contiguous(area, colors.iter().copied());
        }
        let _ = fb.draw_iter(black_box([Pixel(Point::new(-1, 7), Rgb565::RED); 2]));
        black_box(fb.pixels());

        // The 3D pipeline: a flash mesh, opaque matrices, viewport and light, every shading and
        // culling, with and without the vertex scratch.
        // Its colours in the scene's framebuffer, done with (RAM for the stack on the micro:bit).
        let colors_3d = fb.pixels_mut().get_mut(..SMALL_PIXELS).unwrap_or_default();
        // Opaque parameters: the `None` of a projection that shows nothing stays a branch.
        let projection = Mat4::perspective(
            black_box(Angle::from_degrees(60)),
            black_box(Scalar::from_bits(98_304)),
            black_box(Scalar::from_bits(1 << 15)),
            black_box(Scalar::from_bits(20 << 16)),
        );
        if let (Ok(mut target), Some(projection)) = (
            DepthTarget::new(colors_3d, depth_3d, sw, sh),
            black_box(projection),
        ) {
            let model = black_box(Mat4::rotation_y(Angle::from_degrees(30)));
            let view = black_box(Mat4::translation(Vec3::from_bits(0, 0, -3 << 16)));
            let viewport = black_box(Rectangle::new(Point::new(-2, 1), Size::new(30, 12)));
            let light = Light::new(
                black_box(Vec3::from_bits(1 << 15, 1 << 16, 1 << 16)),
                black_box(Scalar::from_bits(1 << 13)),
            );
            let mut pipeline = Pipeline::new(model, projection * view, viewport, light);
            for (k, shading) in [
                Shading::Unlit,
                Shading::Flat,
                Shading::Gouraud,
                Shading::Quadratic,
            ]
            .into_iter()
            .enumerate()
            {
                pipeline.cull = black_box([Cull::Back, Cull::None, Cull::Front, Cull::Back][k]);
                let material = Material::new(black_box(Rgb565::WHITE), black_box(shading));
                let mesh = black_box(&ICOSPHERE);
                black_box(pipeline.draw_mesh(mesh, &material, &mut target));
                let _ = black_box(pipeline.draw_mesh_with(mesh, &material, &mut target, scratch));
                // With a highlight.
                let specular = Specular::new(black_box(Scalar::from_bits(1 << 15)), black_box(24));
                let shiny = material.with_specular(specular);
                black_box(pipeline.draw_mesh(mesh, &shiny, &mut target));
                let _ = black_box(pipeline.draw_mesh_with(mesh, &shiny, &mut target, scratch));
                // With more lights: point and directional, opaque.
                let lights = black_box(
                    Lights::new()
                        .with(LightSource::point(
                            black_box(Vec3::from_bits(1 << 16, 1 << 15, 1 << 16)),
                            black_box(Scalar::ONE),
                            black_box(Scalar::from_bits(3 << 16)),
                        ))
                        .with(LightSource::directional(
                            black_box(Vec3::from_bits(0, -1 << 16, 0)),
                            black_box(Scalar::from_bits(1 << 15)),
                        )),
                );
                let lit = pipeline.with_lights(lights);
                black_box(lit.draw_mesh(mesh, &material, &mut target));
                let _ = black_box(lit.draw_mesh_with(mesh, &shiny, &mut target, scratch));
                // Its wireframe, over the faces (not on ARMv6-M: the micro:bit's flash has no
                // room for its two face loops and the thin line's exact rule, about 43 KB there).
                #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "32"))))]
                {
                    let edges = black_box(Rgb565::GREEN);
                    black_box(pipeline.draw_wireframe(mesh, edges, &mut target));
                    let _ =
                        black_box(pipeline.draw_wireframe_with(mesh, edges, &mut target, scratch));
                }
            }
            black_box(target.depth());
        }

        crate::stack::report();
        board::exit(true)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!("fw_nopanic is firmware: build it with --target thumbv6m-none-eabi (see .cargo/config.toml)");
}
