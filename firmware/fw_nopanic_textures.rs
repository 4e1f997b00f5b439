//! Firmware that must link without a panic handler, as `fw_nopanic`, for the textured drawing
//! (`firmware/common/texture_scene.rs`): 2D `TexturedTriangle`s through `draw` and `draw_into`
//! with every wrap mode and filter; a textured mesh through `draw_textured_mesh_with` with every
//! shading, vertex colours and highlights, perspective-correct faces among its own, and
//! `three_d::draw_textured`; the 2D shapes too (polygons, thin and stroked lines: `fw_nopanic`
//! is at the micro:bit's flash limit); on the MPS2 boards also `draw_textured_mesh`, which the micro:bit's
//! flash has no room for at opt-level 3. Its `textures` checksum lines must be the host build's
//! (`cargo run --release --example fw_nopanic_textures` prints them; `.ci/firmware.sh` compares
//! them on every board, at opt-level 3, "s" and "z"). A firmware of its own: with the rest of
//! `fw_nopanic` it would not fit the micro:bit's 256 KiB of flash.
//!
//! ```text
//! cargo run --release --target thumbv6m-none-eabi --example fw_nopanic_textures
//! ```
#![cfg_attr(target_os = "none", no_std, no_main)]

#[path = "common/texture_scene.rs"]
mod texture_scene;

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
    use crate::board::entry;
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_raster::three_d::ProjectedVertex;

    use crate::plain_print::{decimal, hex, print};
    use crate::{board, texture_scene};

    /// The 3D frames' pixels.
    const PIXELS_3D: usize = (texture_scene::SIZE_3D.0 * texture_scene::SIZE_3D.1) as usize;
    /// The 2D frame's pixels.
    const PIXELS_2D: usize = (texture_scene::SIZE_2D.0 * texture_scene::SIZE_2D.1) as usize;

    /// Prints a `textures` line: `what`, the frame's size and its checksum (the host's format).
    fn textures_line(what: &[u8], (width, height): (u32, u32), checksum: u32) {
        print(b"textures ");
        print(what);
        print(b" ");
        decimal(u64::from(width));
        print(b"x");
        decimal(u64::from(height));
        print(b" fnv1a=0x");
        hex(checksum);
        print(b"\n");
    }

    /// The 2D frame, its pixels on this function's stack (out of line: the 3D draws, which need
    /// more stack, run after it returns; the micro:bit has 16 KiB of RAM).
    #[inline(never)]
    fn two_d() {
        let mut pixels = [Rgb565::new(0, 0, 0); PIXELS_2D];
        let checksum = texture_scene::render_2d(&mut pixels);
        textures_line(b"2d", texture_scene::SIZE_2D, checksum);
    }

    /// The 2D shapes (polygons, lines, strokes), out of line like [`two_d`].
    #[inline(never)]
    fn shapes() {
        const PIXELS: usize =
            (texture_scene::SIZE_SHAPES.0 * texture_scene::SIZE_SHAPES.1) as usize;
        let mut pixels = [Rgb565::new(0, 0, 0); PIXELS];
        let checksum = texture_scene::render_shapes(&mut pixels);
        textures_line(b"shapes", texture_scene::SIZE_SHAPES, checksum);
    }

    static mut COLORS_3D: [Rgb565; PIXELS_3D] = [Rgb565::new(0, 0, 0); PIXELS_3D];
    static mut DEPTH_3D: [u16; PIXELS_3D] = [0; PIXELS_3D];
    static mut SCRATCH: [ProjectedVertex; 42] = [ProjectedVertex::EMPTY; 42];

    #[entry]
    fn main() -> ! {
        // SAFETY: `main` runs once and never returns: the statics' only references.
        let (colors_3d, depth_3d, scratch) = unsafe {
            (
                &mut *core::ptr::addr_of_mut!(COLORS_3D),
                &mut *core::ptr::addr_of_mut!(DEPTH_3D),
                &mut *core::ptr::addr_of_mut!(SCRATCH),
            )
        };
        crate::stack::paint_run();

        two_d();
        shapes();
        let checksum = texture_scene::render_3d(colors_3d, depth_3d, scratch);
        textures_line(b"3d", texture_scene::SIZE_3D, checksum);
        // Not on the micro:bit, whose flash it would overflow at opt-level 3.
        #[cfg(not(armv6m))]
        {
            let checksum = texture_scene::render_3d_mesh(colors_3d, depth_3d);
            textures_line(b"3d-mesh", texture_scene::SIZE_3D, checksum);
        }
        crate::stack::report();
        board::exit(true)
    }
}

/// The host prints the `textures` lines the firmware must print (`.ci/firmware.sh` compares
/// them; the scene's line is `fw_scene`'s).
#[cfg(not(target_os = "none"))]
fn main() {
    use embedded_graphics::pixelcolor::Rgb565;
    use embedded_graphics::prelude::*;
    use embedded_raster::three_d::ProjectedVertex;

    let (w, h) = texture_scene::SIZE_2D;
    let mut pixels = vec![Rgb565::BLACK; (w * h) as usize];
    let checksum = texture_scene::render_2d(&mut pixels);
    println!("textures 2d {w}x{h} fnv1a=0x{checksum:08x}");
    let (w, h) = texture_scene::SIZE_SHAPES;
    let mut pixels = vec![Rgb565::BLACK; (w * h) as usize];
    let checksum = texture_scene::render_shapes(&mut pixels);
    println!("textures shapes {w}x{h} fnv1a=0x{checksum:08x}");
    let (w, h) = texture_scene::SIZE_3D;
    let (mut colors, mut depths) = (
        vec![Rgb565::BLACK; (w * h) as usize],
        vec![0; (w * h) as usize],
    );
    let mut scratch = [ProjectedVertex::EMPTY; 42];
    let checksum = texture_scene::render_3d(&mut colors, &mut depths, &mut scratch);
    println!("textures 3d {w}x{h} fnv1a=0x{checksum:08x}");
    let checksum = texture_scene::render_3d_mesh(&mut colors, &mut depths);
    println!("textures 3d-mesh {w}x{h} fnv1a=0x{checksum:08x}");
}
