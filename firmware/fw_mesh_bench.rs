//! Firmware benchmark of the 3D pipeline: the frame of `examples/common/scene3d.rs` (320×240
//! Rgb565, 16-bit z-buffer, back faces culled, Gouraud, colour and depth cleared) for each bench
//! mesh, in instructions counted by SysTick (or `minstret`) under QEMU's `-icount` (`firmware/common/clock.rs`).
//!
//! ```text
//! cargo run --release --target thumbv7em-none-eabihf --example fw_mesh_bench   # mps2-an386, M4F
//! cargo run --release --target thumbv7m-none-eabi    --example fw_mesh_bench   # mps2-an385, M3
//! cargo run --release --example fw_mesh_bench                                  # host: checksums
//! ```
//!
//! The buffers take 300 KB of RAM, so this runs on the MPS2 boards (4 MiB). `.ci/firmware.sh`
//! also runs the Cortex-M0 build (thumbv6m) on the mps2-an385 model: ARMv7-M executes the
//! ARMv6-M instruction stream unchanged, so the count is the Cortex-M0 code's.
//!
//! Each board prints one `frame …` line per mesh (the pipeline's counts, covered pixels and a
//! checksum of colours and depths), which must equal the host's, then a table: the frame with
//! each vertex transformed once into a scratch slice (`Pipeline::draw_mesh_with`) and without
//! (`draw_mesh`, once per face using the vertex). Both must give the same frame, or the run fails.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[allow(dead_code)]
#[path = "../examples/common/scene3d.rs"]
mod scene3d;

#[path = "../examples/common/textured3d.rs"]
mod textured3d;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[path = "common/report_panic.rs"]
mod report_panic;

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/clock.rs"]
mod clock;

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;

    use crate::board::entry;
    use crate::board::hprintln;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_raster::band::BinEntry;
    use embedded_raster::three_d::{DepthTarget, ProjectedVertex, TexCoord, Vec3};
    use embedded_raster::three_d::{LightSource, Lights, Material, Scalar, Shading, Specular};

    use crate::clock::Ratio;
    use crate::scene3d::{self, FrameLine, Model, TurntableLine, MAX_VERTICES, PIXELS, SIZE};
    use crate::scene3d::{SCATTER_FACES, SCATTER_VERTICES};
    use crate::scene3d::{TORUS_FACES, TORUS_VERTICES, TURNTABLE_POSES};
    use crate::textured3d::{self, Textured, TexturedLine, BAND_PIXELS, TEXELS};
    use crate::textured3d::{FLOOR_FACES, FLOOR_VERTICES};
    use crate::{board, clock};

    /// The instruction set this build runs (the Cortex-M0 code runs on the Cortex-M3 board).
    fn code() -> &'static str {
        if cfg!(armv6m) {
            "thumbv6m-none-eabi (Cortex-M0 code)"
        } else if cfg!(all(armv8m, arm_dsp)) {
            "thumbv8m.main-none-eabihf, feature dsp (Cortex-M33 code with the DSP extension)"
        } else if cfg!(armv8m) {
            "thumbv8m.main-none-eabihf (Cortex-M33 code)"
        } else if cfg!(arm_dsp) {
            "thumbv7em-none-eabihf (Cortex-M4F code)"
        } else if cfg!(armv7m) {
            "thumbv7m-none-eabi (Cortex-M3 code)"
        } else {
            board::name()
        }
    }

    static mut COLORS: [Rgb565; PIXELS] = [Rgb565::new(0, 0, 0); PIXELS];
    static mut DEPTH: [u16; PIXELS] = [0; PIXELS];
    static mut TORUS_V: [Vec3; TORUS_VERTICES] = [Vec3::ZERO; TORUS_VERTICES];
    static mut TORUS_N: [Vec3; TORUS_VERTICES] = [Vec3::ZERO; TORUS_VERTICES];
    static mut TORUS_I: [[u16; 3]; TORUS_FACES] = [[0; 3]; TORUS_FACES];
    static mut SCRATCH: [ProjectedVertex; MAX_VERTICES] = [ProjectedVertex::EMPTY; MAX_VERTICES];
    static mut TEXTURE: [u16; TEXELS] = [0; TEXELS];
    static mut SCATTER_V: [Vec3; SCATTER_VERTICES] = [Vec3::ZERO; SCATTER_VERTICES];
    static mut SCATTER_N: [Vec3; SCATTER_VERTICES] = [Vec3::ZERO; SCATTER_VERTICES];
    static mut SCATTER_I: [[u16; 3]; SCATTER_FACES] = [[0; 3]; SCATTER_FACES];
    static mut FLOOR_V: [Vec3; FLOOR_VERTICES] = [Vec3::ZERO; FLOOR_VERTICES];
    static mut FLOOR_N: [Vec3; FLOOR_VERTICES] = [Vec3::ZERO; FLOOR_VERTICES];
    static mut FLOOR_T: [TexCoord; FLOOR_VERTICES] = [TexCoord::from_bits(0, 0); FLOOR_VERTICES];
    static mut FLOOR_I: [[u16; 3]; FLOOR_FACES] = [[0; 3]; FLOOR_FACES];
    static mut BAND_COLORS: [Rgb565; BAND_PIXELS] = [Rgb565::new(0, 0, 0); BAND_PIXELS];
    static mut BAND_DEPTH: [u16; BAND_PIXELS] = [0; BAND_PIXELS];
    /// The textured bands' bin: bands at one row (the most a layout of the frame has) plus
    /// spot's faces (5,856).
    static mut BIN_STORAGE: [BinEntry; 240 + 5856] = [BinEntry::EMPTY; 240 + 5856];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the statics' only references.
        let (colors, depth, torus_v, torus_n, torus_i, scratch, texture) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(COLORS),
                &mut *core::ptr::addr_of_mut!(DEPTH),
                &mut *core::ptr::addr_of_mut!(TORUS_V),
                &mut *core::ptr::addr_of_mut!(TORUS_N),
                &mut *core::ptr::addr_of_mut!(TORUS_I),
                &mut *core::ptr::addr_of_mut!(SCRATCH),
                &mut *core::ptr::addr_of_mut!(TEXTURE),
            )
        };

        clock::start();
        let calibration = clock::calibrate();
        let torus = scene3d::torus(torus_v, torus_n, torus_i);
        let (width, height) = SIZE;
        let mut target = DepthTarget::new(colors, depth, width, height).expect("buffers fit");

        if let Some(kind) = option_env!("MESH_PROFILE").and_then(|p| p.strip_prefix("textured")) {
            // Profiling build: a textured frame alone (`textured`: nearest; `textured-quadratic`:
            // per pixel with the highlight; `textured-unlit`; `textured-bilinear`), a few times.
            let frame = match kind {
                "-quadratic" => Textured::QuadraticSpecular,
                "-bilinear" => Textured::Bilinear,
                "-unlit" => Textured::Unlit,
                _ => Textured::Nearest,
            };
            textured3d::expand(texture);
            for _ in 0..4 {
                let scratch = Some(&mut scratch[..]);
                black_box(textured3d::render(frame, texture, &mut target, scratch));
            }
            board::exit(true)
        }
        if let Some(profile) = option_env!("MESH_PROFILE") {
            // Profiling build (.ci/profile.sh): only this frame, a few times.
            let model = if profile.starts_with("torus") {
                Model::Torus
            } else if profile.starts_with("spot") {
                Model::Spot
            } else {
                Model::Knot
            };
            let mesh = model.mesh(&torus);
            if profile.ends_with("wireframe") {
                for _ in 0..4 {
                    let scratch = Some(&mut scratch[..]);
                    black_box(scene3d::render_wireframe(
                        model,
                        black_box(mesh),
                        &mut target,
                        scratch,
                    ));
                }
                board::exit(true)
            }
            for _ in 0..4 {
                let scratch = (!profile.ends_with("faces")).then_some(&mut scratch[..]);
                black_box(scene3d::render(
                    model,
                    black_box(mesh),
                    &mut target,
                    scratch,
                ));
            }
            board::exit(true)
        }
        let mut lines = [None, None, None];
        let mut rows = [(0u64, 0u64, 0u32); 3];
        let mut same = true;
        for (k, model) in Model::ALL.into_iter().enumerate() {
            let mesh = model.mesh(&torus);
            // Untimed frames for the counts and the checksums, then the timed ones.
            let stats = scene3d::render(model, mesh, &mut target, Some(&mut scratch[..]));
            let line = FrameLine::of(model, false, stats, &target);
            scene3d::render(model, mesh, &mut target, None);
            same &=
                line.checksum == scene3d::checksum(target.framebuffer().pixels(), target.depth());
            let with = clock::measure(1, || {
                let scratch = Some(&mut scratch[..]);
                black_box(scene3d::render(
                    model,
                    black_box(mesh),
                    &mut target,
                    scratch,
                ));
            });
            let without = clock::measure(1, || {
                black_box(scene3d::render(model, black_box(mesh), &mut target, None));
            });
            rows[k] = (
                clock::instructions(with, calibration),
                clock::instructions(without, calibration),
                mesh.indices.len() as u32,
            );
            lines[k] = Some(line);
        }
        // The knot's hidden-line wireframe: its faces into the z-buffer, then their edges.
        let knot = Model::Knot.mesh(&torus);
        let wire_stats =
            scene3d::render_wireframe(Model::Knot, knot, &mut target, Some(&mut scratch[..]));
        let wire_line = FrameLine::of(Model::Knot, true, wire_stats, &target);
        scene3d::render_wireframe(Model::Knot, knot, &mut target, None);
        same &=
            wire_line.checksum == scene3d::checksum(target.framebuffer().pixels(), target.depth());
        let wire = clock::instructions(
            clock::measure(1, || {
                let scratch = Some(&mut scratch[..]);
                black_box(scene3d::render_wireframe(
                    Model::Knot,
                    black_box(knot),
                    &mut target,
                    scratch,
                ));
            }),
            calibration,
        );
        let mut poses = [0u64; TURNTABLE_POSES as usize];
        let mut pose = 0;
        let spot = Model::Spot.mesh(&torus);
        let turntable = scene3d::turntable_checksum(spot, &mut target, &mut scratch[..], |frame| {
            poses[pose] = clock::instructions(clock::measure(1, || frame()), calibration);
            pose += 1;
        });
        // Spot with more lights (`MESH_LIGHTS=1` builds only: more materials drawn by the
        // firmware change how the frames above inline): the frame's light and two point lights
        // (flat and Gouraud, without and with a highlight), against the first light alone.
        let lights = Lights::new()
            .with(LightSource::point(
                Vec3::from_bits(78643, 52429, 78643),
                Scalar::from_bits(52429),
                Scalar::from_bits(3 << 16),
            ))
            .with(LightSource::point(
                Vec3::from_bits(-85197, -26214, 58982),
                Scalar::from_bits(39322),
                Scalar::from_bits(5 << 15),
            ));
        let one = scene3d::pipeline(Model::Spot);
        let more = one.with_lights(lights);
        let mut lit = [[0u64; 4]; 2];
        let bench_lights = option_env!("MESH_LIGHTS").is_some();
        for (k, shading) in [Shading::Flat, Shading::Gouraud].into_iter().enumerate() {
            if !bench_lights {
                break;
            }
            let plain = Material::new(scene3d::MATERIAL.color, shading);
            let shiny = plain.with_specular(Specular::new(Scalar::from_bits(1 << 15), 24));
            let frames = [(&one, plain), (&one, shiny), (&more, plain), (&more, shiny)];
            for (j, (pipeline, material)) in frames.into_iter().enumerate() {
                let ticks = clock::measure(1, || {
                    target.clear(scene3d::BACKGROUND);
                    let scratch = &mut scratch[..];
                    let _ =
                        black_box(pipeline.draw_mesh_with(spot, &material, &mut target, scratch));
                });
                lit[k][j] = clock::instructions(ticks, calibration);
            }
        }
        // The textured frames: counts and checksums untimed, then timed with the scratch.
        textured3d::expand(texture);
        let mut textured: [Option<(TexturedLine, u64)>; Textured::ALL.len()] = Default::default();
        for (k, frame) in Textured::ALL.into_iter().enumerate() {
            let stats = textured3d::render(frame, texture, &mut target, Some(&mut scratch[..]));
            let covered = scene3d::covered(target.depth());
            let checksum = scene3d::checksum(target.framebuffer().pixels(), target.depth());
            textured3d::render(frame, texture, &mut target, None);
            same &= checksum == scene3d::checksum(target.framebuffer().pixels(), target.depth());
            let ticks = clock::measure(1, || {
                let scratch = Some(&mut scratch[..]);
                black_box(textured3d::render(
                    black_box(frame),
                    texture,
                    &mut target,
                    scratch,
                ));
            });
            let line = TexturedLine {
                frame,
                stats,
                covered,
                checksum,
            };
            textured[k] = Some((line, clock::instructions(ticks, calibration)));
        }
        // The nearest frame in bands of 16 and 7 rows, each band drawing the mesh or a bin's faces
        // of it (its frame re-clipped a band at a time): the hashes of the frame drawn whole.
        // SAFETY: as for the statics above: these are their only references.
        let (band_colors, band_depth) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(BAND_COLORS),
                &mut *core::ptr::addr_of_mut!(BAND_DEPTH),
            )
        };
        textured3d::render(
            Textured::Nearest,
            texture,
            &mut target,
            Some(&mut scratch[..]),
        );
        let whole = textured3d::hashes(target.framebuffer().pixels(), target.depth());
        // SAFETY: as for the statics above: its only reference.
        let bin = unsafe { &mut *core::ptr::addr_of_mut!(BIN_STORAGE) };
        let bands = [16, 7].into_iter().all(|rows| {
            [false, true].into_iter().all(|binned| {
                let bin = binned.then_some(&mut bin[..]);
                let hashes =
                    textured3d::render_bands(texture, rows, band_colors, band_depth, scratch, bin);
                hashes == whole
            })
        });
        for line in lines.iter().flatten() {
            hprintln!("{}", line);
        }
        hprintln!("{}", wire_line);
        hprintln!("{}", TurntableLine(turntable));
        // SAFETY: as for the statics above: these are their only references.
        let (scatter_v, scatter_n, scatter_i) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(SCATTER_V),
                &mut *core::ptr::addr_of_mut!(SCATTER_N),
                &mut *core::ptr::addr_of_mut!(SCATTER_I),
            )
        };
        let scatter = scene3d::scatter(scatter_v, scatter_n, scatter_i);
        hprintln!(
            "{}",
            scene3d::render_scatter(&scatter, &mut target, scratch)
        );
        // SAFETY: as for the statics above: these are their only references (the scatter
        // mesh's borrows end above).
        let (depths_v, depths_n, depths_i) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(SCATTER_V),
                &mut *core::ptr::addr_of_mut!(SCATTER_N),
                &mut *core::ptr::addr_of_mut!(SCATTER_I),
            )
        };
        let depths = scene3d::depths(depths_v, depths_n, depths_i);
        hprintln!("{}", scene3d::render_depths(&depths, &mut target, scratch));
        for (line, _) in textured.iter().flatten() {
            hprintln!("{}", line);
        }
        // SAFETY: as for the statics above: these are their only references.
        let floor = unsafe {
            textured3d::floor(
                &mut *core::ptr::addr_of_mut!(FLOOR_V),
                &mut *core::ptr::addr_of_mut!(FLOOR_N),
                &mut *core::ptr::addr_of_mut!(FLOOR_T),
                &mut *core::ptr::addr_of_mut!(FLOOR_I),
            )
        };
        let stats = textured3d::render_floor(&floor, &mut target, scratch);
        hprintln!("{}", TexturedLine::of(Textured::Floor, stats, &target));
        // SAFETY: as for the statics above: these are their only references (the floor's
        // borrows end above).
        let (scatter_v, scatter_n, scatter_i, uvs) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(SCATTER_V),
                &mut *core::ptr::addr_of_mut!(SCATTER_N),
                &mut *core::ptr::addr_of_mut!(SCATTER_I),
                &mut *core::ptr::addr_of_mut!(FLOOR_T),
            )
        };
        let scatter = scene3d::scatter(scatter_v, scatter_n, scatter_i);
        let stats = textured3d::render_scatter_textured(&scatter, uvs, &mut target, scratch);
        hprintln!("{}", TexturedLine::of(Textured::Scatter, stats, &target));
        hprintln!("\n### 3D frame, {}\n", code());
        hprintln!(
            "| mesh | faces | drawn | covered px | instructions a frame | per face | per drawn face | per covered px | without scratch |"
        );
        hprintln!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
        for (line, (instructions, without, faces)) in lines.iter().flatten().zip(rows) {
            hprintln!(
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                line.model.name(),
                faces,
                line.stats.drawn,
                line.covered,
                instructions,
                Ratio(instructions, u64::from(faces)),
                Ratio(instructions, u64::from(line.stats.drawn)),
                Ratio(instructions, u64::from(line.covered)),
                without
            );
        }
        let faces = knot.indices.len() as u64;
        hprintln!(
            "| knot-wireframe | {} | {} | {} | {} | {} | {} | {} | – |",
            faces,
            wire_line.stats.drawn,
            wire_line.covered,
            wire,
            Ratio(wire, faces),
            Ratio(wire, u64::from(wire_line.stats.drawn)),
            Ratio(wire, u64::from(wire_line.covered)),
        );
        hprintln!(
            "\n| spot textured (256×256 texture, Gouraud or per pixel (quadratic), perspective-correct) | drawn | covered px | instructions a frame |"
        );
        hprintln!("|---|---:|---:|---:|");
        for (line, instructions) in textured.iter().flatten() {
            hprintln!(
                "| {} | {} | {} | {} |",
                line.frame.name(),
                line.stats.drawn,
                line.covered,
                instructions
            );
        }
        let (min, max) = (poses.iter().min(), poses.iter().max());
        let mean = poses.iter().sum::<u64>() / poses.len() as u64;
        hprintln!(
            "\n| spot turntable ({} poses, yaw every 30°) | fewest | mean | most |",
            TURNTABLE_POSES
        );
        hprintln!("|---|---:|---:|---:|");
        hprintln!(
            "| instructions a frame | {} | {} | {} |",
            min.copied().unwrap_or(0),
            mean,
            max.copied().unwrap_or(0)
        );
        if bench_lights {
            hprintln!(
                "\n| spot, shading (instructions a frame) | first light | with a highlight | with 2 point lights | both |"
            );
            hprintln!("|---|---:|---:|---:|---:|");
            for (name, row) in ["flat", "Gouraud"].into_iter().zip(lit) {
                hprintln!(
                    "| {} | {} | {} | {} | {} |",
                    name,
                    row[0],
                    row[1],
                    row[2],
                    row[3]
                );
            }
        }
        hprintln!();
        if !same {
            hprintln!("error: the frames with and without the vertex scratch differ");
        }
        if !bands {
            hprintln!("error: the textured frame in bands differs from the frame drawn whole");
        }
        board::exit(same && bands)
    }
}

#[cfg(not(target_os = "none"))]
fn main() {
    use embedded_graphics::pixelcolor::{Rgb565, RgbColor};
    use embedded_raster::three_d::{DepthTarget, ProjectedVertex, Vec3};
    use scene3d::{FrameLine, Model, TurntableLine, MAX_VERTICES, PIXELS, SIZE};
    use scene3d::{TORUS_FACES, TORUS_VERTICES};

    let mut v = Box::new([Vec3::ZERO; TORUS_VERTICES]);
    let mut n = Box::new([Vec3::ZERO; TORUS_VERTICES]);
    let mut i = Box::new([[0u16; 3]; TORUS_FACES]);
    let torus = scene3d::torus(&mut v, &mut n, &mut i);
    let (mut colors, mut depth) = (vec![Rgb565::new(0, 0, 0); PIXELS], vec![0u16; PIXELS]);
    let mut target = DepthTarget::new(&mut colors, &mut depth, SIZE.0, SIZE.1).expect("buffers");
    let mut scratch = vec![ProjectedVertex::EMPTY; MAX_VERTICES];
    for model in Model::ALL {
        let mesh = model.mesh(&torus);
        scene3d::render(model, mesh, &mut target, None);
        let without = scene3d::checksum(target.framebuffer().pixels(), target.depth());
        let stats = scene3d::render(model, mesh, &mut target, Some(&mut scratch));
        let line = FrameLine::of(model, false, stats, &target);
        assert_eq!(
            line.checksum, without,
            "the frames with and without scratch differ"
        );
        println!("{line}");
        if let Some(dir) = std::env::args().nth(1) {
            let path = format!("{dir}/{}.ppm", model.name());
            let mut ppm = format!("P6 {} {} 255\n", SIZE.0, SIZE.1).into_bytes();
            for c in target.framebuffer().pixels() {
                ppm.extend([c.r() << 3, c.g() << 2, c.b() << 3]);
            }
            std::fs::write(&path, ppm).expect("write the picture");
        }
    }
    let knot = Model::Knot.mesh(&torus);
    scene3d::render_wireframe(Model::Knot, knot, &mut target, None);
    let without = scene3d::checksum(target.framebuffer().pixels(), target.depth());
    let stats = scene3d::render_wireframe(Model::Knot, knot, &mut target, Some(&mut scratch));
    let line = FrameLine::of(Model::Knot, true, stats, &target);
    assert_eq!(
        line.checksum, without,
        "the wireframes with and without scratch differ"
    );
    println!("{line}");
    let turntable = scene3d::turntable_checksum(&scene3d::SPOT, &mut target, &mut scratch, |f| f());
    println!("{}", TurntableLine(turntable));
    let mut sv = Box::new([Vec3::ZERO; scene3d::SCATTER_VERTICES]);
    let mut sn = Box::new([Vec3::ZERO; scene3d::SCATTER_VERTICES]);
    let mut si = Box::new([[0u16; 3]; scene3d::SCATTER_FACES]);
    let scatter = scene3d::scatter(&mut sv, &mut sn, &mut si);
    println!(
        "{}",
        scene3d::render_scatter(&scatter, &mut target, &mut scratch)
    );
    let depths = scene3d::depths(&mut sv[..], &mut sn[..], &mut si[..]);
    println!(
        "{}",
        scene3d::render_depths(&depths, &mut target, &mut scratch)
    );
    let mut texels = vec![0u16; textured3d::TEXELS];
    textured3d::expand(&mut texels);
    for frame in textured3d::Textured::ALL {
        textured3d::render(frame, &texels, &mut target, None);
        let without = scene3d::checksum(target.framebuffer().pixels(), target.depth());
        let stats = textured3d::render(frame, &texels, &mut target, Some(&mut scratch));
        let line = textured3d::TexturedLine {
            frame,
            stats,
            covered: scene3d::covered(target.depth()),
            checksum: scene3d::checksum(target.framebuffer().pixels(), target.depth()),
        };
        assert_eq!(
            line.checksum, without,
            "the textured frames with and without scratch differ"
        );
        println!("{line}");
    }
    use embedded_raster::band::BinEntry;
    use textured3d::{Textured, BAND_PIXELS, SPOT_TEXTURED};
    let mut fv = Box::new([Vec3::ZERO; textured3d::FLOOR_VERTICES]);
    let mut fnorm = Box::new([Vec3::ZERO; textured3d::FLOOR_VERTICES]);
    let mut ft =
        Box::new([embedded_raster::three_d::TexCoord::from_bits(0, 0); textured3d::FLOOR_VERTICES]);
    let mut fi = Box::new([[0u16; 3]; textured3d::FLOOR_FACES]);
    let floor = textured3d::floor(&mut fv, &mut fnorm, &mut ft, &mut fi);
    let stats = textured3d::render_floor(&floor, &mut target, &mut scratch);
    println!(
        "{}",
        textured3d::TexturedLine::of(Textured::Floor, stats, &target)
    );
    let scatter = scene3d::scatter(&mut sv, &mut sn, &mut si);
    let stats =
        textured3d::render_scatter_textured(&scatter, &mut ft[..], &mut target, &mut scratch);
    println!(
        "{}",
        textured3d::TexturedLine::of(Textured::Scatter, stats, &target)
    );
    textured3d::render(Textured::Nearest, &texels, &mut target, Some(&mut scratch));
    let whole = textured3d::hashes(target.framebuffer().pixels(), target.depth());
    let (mut band_colors, mut band_depth) =
        (vec![Rgb565::BLACK; BAND_PIXELS], vec![0; BAND_PIXELS]);
    let mut bin = vec![BinEntry::EMPTY; 240 + SPOT_TEXTURED.indices.len()];
    for rows in [16, 7] {
        for binned in [false, true] {
            let hashes = textured3d::render_bands(
                &texels,
                rows,
                &mut band_colors,
                &mut band_depth,
                &mut scratch,
                binned.then_some(&mut bin[..]),
            );
            assert_eq!(
                hashes, whole,
                "the textured frame in bands of {rows} rows (binned: {binned}) differs"
            );
        }
    }
}
