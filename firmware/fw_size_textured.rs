//! Footprint firmware: `TexturedTriangle<Rgb565Texels, Rgb565>` through `draw` and `draw_into`,
//! a texture of any size, wrap mode and filter (see `firmware/common/size.rs`;
//! `.ci/firmware.sh` reports the sizes). Like the other footprint firmware it links only if the
//! drawing code has no panic path.
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

    use embedded_graphics::Drawable;
    use embedded_raster::texture::{Filter, Rgb565Texels, TexelCoord, Texture, Wrap};
    use embedded_raster::{TexturedTriangle, TexturedVertex};

    /// A 4 × 4 texture: the code's footprint, not the texels'.
    static TEXELS: [u16; 16] = [
        0xf800, 0x07e0, 0x001f, 0xffff, 0x0000, 0xf800, 0x07e0, 0x001f, 0xffff, 0x0000, 0xf800,
        0x07e0, 0x001f, 0xffff, 0x0000, 0xf800,
    ];
    size::run(|fb| {
        let (points, _) = size::inputs();
        let (w, h) = black_box((4, 4));
        let Ok(texture) = Texture::new(Rgb565Texels(black_box(&TEXELS)), w, h) else {
            return;
        };
        let texture = texture
            .with_wrap(black_box(Wrap::Repeat), black_box(Wrap::Clamp))
            .with_filter(black_box(Filter::Nearest));
        let vertex = |k: usize| {
            let (x, y) = points[k];
            let texel =
                |c: embedded_raster::Coord| TexelCoord::from_bits(black_box(c.to_bits() << 4));
            TexturedVertex {
                x,
                y,
                u: texel(x),
                v: texel(y),
            }
        };
        let triangle = TexturedTriangle::new([vertex(0), vertex(1), vertex(2)], &texture);
        let _ = black_box(triangle).draw(fb);
        black_box(triangle).draw_into(fb);
    })
}

#[cfg(not(target_os = "none"))]
fn main() {
    println!("fw_size_textured is firmware: build it with --target thumbv6m-none-eabi");
}
