//! Footprint firmware: a textured mesh through `Pipeline::draw_textured_mesh_with` — a cube with
//! texture coordinates and normals, a nearest Rgb565 texture, Gouraud-lit, perspective-correct,
//! into an Rgb565 framebuffer with its z-buffer (see `firmware/common/size.rs`, `run_depth`;
//! `.ci/firmware.sh` reports the sizes). The material is fixed as an application's would be;
//! the mesh, texture, camera and light are opaque (`black_box`), so nothing is specialised to
//! constants. Like the other footprint firmware it links only if the drawing code has no
//! panic path.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
#[allow(dead_code)]
#[path = "common/board.rs"]
mod board;

#[cfg(target_os = "none")]
#[path = "common/size.rs"]
mod size;

#[cfg(target_os = "none")]
fn main() -> ! {
    use core::hint::black_box;

    use embedded_graphics::prelude::*;
    use embedded_graphics::primitives::Rectangle;
    use embedded_raster::texture::{Rgb565Texels, Texture};
    use embedded_raster::three_d::{
        Angle, Light, Mat4, Mesh, Pipeline, ProjectedVertex, Scalar, Shading, TexCoord,
        TexturedMaterial, Vec3,
    };

    const ONE: i32 = 1 << 16;
    /// A cube's six faces, four vertices each (their own normal and texture coordinates).
    static POSITIONS: [Vec3; 24] = {
        let mut p = [Vec3::from_bits(0, 0, 0); 24];
        let mut face = 0;
        while face < 6 {
            let (axis, sign) = (face / 2, if face % 2 == 0 { ONE } else { -ONE });
            let corners = [(-ONE, -ONE), (ONE, -ONE), (ONE, ONE), (-ONE, ONE)];
            let mut k = 0;
            while k < 4 {
                let (a, b) = corners[k];
                let (a, b) = if sign > 0 { (a, b) } else { (b, a) };
                p[face * 4 + k] = match axis {
                    0 => Vec3::from_bits(sign, a, b),
                    1 => Vec3::from_bits(b, sign, a),
                    _ => Vec3::from_bits(a, b, sign),
                };
                k += 1;
            }
            face += 1;
        }
        p
    };
    static NORMALS: [Vec3; 24] = {
        let mut n = [Vec3::from_bits(0, 0, 0); 24];
        let mut k = 0;
        while k < 24 {
            let (axis, sign) = (k / 8, if k / 4 % 2 == 0 { ONE } else { -ONE });
            n[k] = match axis {
                0 => Vec3::from_bits(sign, 0, 0),
                1 => Vec3::from_bits(0, sign, 0),
                _ => Vec3::from_bits(0, 0, sign),
            };
            k += 1;
        }
        n
    };
    static UVS: [TexCoord; 24] = {
        let corners = [(0, 0), (ONE, 0), (ONE, ONE), (0, ONE)];
        let mut t = [TexCoord::from_bits(0, 0); 24];
        let mut k = 0;
        while k < 24 {
            t[k] = TexCoord::from_bits(corners[k % 4].0, corners[k % 4].1);
            k += 1;
        }
        t
    };
    static INDICES: [[u16; 3]; 12] = {
        let mut i = [[0u16; 3]; 12];
        let mut face = 0;
        while face < 6 {
            let b = face as u16 * 4;
            i[face * 2] = [b, b + 1, b + 2];
            i[face * 2 + 1] = [b, b + 2, b + 3];
            face += 1;
        }
        i
    };
    /// An 8 × 8 texture: the code's footprint, not the texels'.
    static TEXELS: [u16; 64] = {
        let mut t = [0u16; 64];
        let mut k = 0;
        while k < 64 {
            t[k] = if (k / 8 + k) % 2 == 0 { 0xf800 } else { 0xffff };
            k += 1;
        }
        t
    };

    size::run_depth(|target| {
        static mut SCRATCH: [ProjectedVertex; 24] = [ProjectedVertex::EMPTY; 24];
        // SAFETY: the only reference to SCRATCH, taken once.
        let scratch = unsafe { &mut *core::ptr::addr_of_mut!(SCRATCH) };
        let mesh = Mesh::new(
            black_box(&POSITIONS),
            black_box(&NORMALS),
            black_box(&INDICES),
        )
        .with_uvs(black_box(&UVS));
        let (w, h) = black_box((8, 8));
        let Some(texture) = Texture::new(Rgb565Texels(black_box(&TEXELS)), w, h).ok() else {
            return;
        };
        let material = TexturedMaterial::new(&texture, Shading::Gouraud);
        let (width, height) = black_box(board::SIZE);
        let Some(projection) = Mat4::perspective(
            black_box(Angle::from_degrees(60)),
            black_box(Scalar::from_bits(87_381)), // 4 / 3
            black_box(Scalar::from_bits(1 << 15)),
            black_box(Scalar::from_bits(20 << 16)),
        ) else {
            return;
        };
        let view = Mat4::translation(black_box(Vec3::from_bits(0, 0, -4 * ONE)));
        let model = Mat4::rotation_y(black_box(Angle::from_degrees(30)))
            * Mat4::rotation_x(black_box(Angle::from_degrees(20)));
        let viewport = Rectangle::new(Point::zero(), Size::new(width, height));
        let light = Light::new(
            black_box(Vec3::from_bits(-26214, 39322, 45875)),
            black_box(Scalar::from_bits(9830)),
        );
        let pipeline = Pipeline::new(model, projection * view, viewport, light);
        let _ = black_box(pipeline.draw_textured_mesh_with(&mesh, &material, target, scratch));
    })
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!("fw_size_textured3d is firmware: build it with --target thumbv6m-none-eabi");
}
