//! Renders the texture pictures into `docs/`:
//!
//! * `textured_spot.png` — Keenan Crane's spot with its own texture (256 × 256, 4-bit palette,
//!   bilinear), Gouraud-lit and perspective-correct, next to the untextured Gouraud spot in the
//!   same pose: the 3D benchmark's 320×240 frame (camera, light and pose of
//!   `examples/common/scene3d.rs`);
//! * `texture_filters.png` — nearest against bilinear filtering: spot's eyes in its frame at 2×,
//!   drawn once with each filter and shown at 4× zoom (pixel replication);
//! * `sprite.png` — a 2D sprite: a procedural 64 × 64 Rgb565 logo on a textured quad (two
//!   `TexturedTriangle`s sharing a diagonal), rotated and scaled over a background, drawn with
//!   `draw_into` into a `SliceFramebuffer` and, in the last panel, with `Drawable::draw`
//!   straight into an embedded-graphics-simulator display.
//!
//! Run with `cargo run --release --features std --example textured`.

use embedded_graphics::{
    mono_font::{ascii::FONT_6X10, MonoTextStyleBuilder},
    pixelcolor::Rgb565,
    prelude::*,
    primitives::{Line, PrimitiveStyle, Rectangle},
    text::Text,
};
use embedded_graphics_simulator::{OutputSettingsBuilder, SimulatorDisplay};
use embedded_raster::texture::{Filter, Rgb565Texels, TexelSource, Texture, Wrap};
use embedded_raster::three_d::{
    Angle, DepthTarget, Light, Mat4, Material, Pipeline, Scalar, Shading, Specular,
    TexturedMaterial, Vec3,
};
use embedded_raster::{
    GouraudTriangle, SliceFramebuffer, TexturedTriangle, TexturedVertex, Vertex,
};

#[allow(clippy::all)]
#[rustfmt::skip]
#[path = "common/meshes/spot_textured.rs"]
mod spot_textured;

#[allow(clippy::all)]
#[rustfmt::skip]
#[path = "common/textures/spot_texture.rs"]
mod spot_texture;

use spot_texture::{SPOT_TEXTURE, SPOT_TEXTURE_HEIGHT, SPOT_TEXTURE_WIDTH};
use spot_textured::SPOT_TEXTURED;

/// The benchmark frame's size (`scene3d::SIZE`).
const FRAME: (u32, u32) = (320, 240);

/// The benchmark frame's background (`scene3d::BACKGROUND`).
const BACKGROUND: Rgb565 = Rgb565::new(3, 6, 4);

/// The untextured spot's colour (`scene3d::MATERIAL`).
const SPOT_COLOR: Rgb565 = Rgb565::new(30, 48, 16);

/// Label text colour.
const LABEL: Rgb565 = Rgb565::new(27, 55, 27);

/// The benchmark camera, light and pose of spot (`scene3d::pipeline(Model::Spot)`) for a
/// viewport of `scale` times the 320×240 frame: a 60° perspective camera 2.5 units from the
/// origin, the light from the upper left and in front, ambient 0.15; spot tilted 15° towards
/// the camera and turned by 145°.
fn spot_pipeline(scale: u32) -> Pipeline {
    let (w, h) = (FRAME.0 * scale, FRAME.1 * scale);
    let projection = Mat4::perspective(
        Angle::from_degrees(60),
        Scalar::from_num(w) / Scalar::from_num(h),
        Scalar::from_bits(1 << 15),
        Scalar::from_num(8),
    )
    .unwrap();
    let view = Mat4::translation(Vec3::from_bits(0, 0, -(5 << 16) / 2));
    let light = Light::new(
        Vec3::from_bits(-26214, 39322, 45875),
        Scalar::from_bits(9830),
    );
    let pose =
        Mat4::rotation_x(Angle::from_degrees(15)) * Mat4::rotation_y(Angle::from_degrees(145));
    let viewport = Rectangle::new(Point::zero(), Size::new(w, h));
    Pipeline::new(pose, projection * view, viewport, light)
}

/// Spot's frame at `scale` times 320×240, textured with `filter` or, for `None`, in the plain
/// Gouraud material: the colour buffer, row-major.
fn render_spot(scale: u32, filter: Option<Filter>) -> Vec<Rgb565> {
    render_spot_lit(scale, filter, None)
}

/// [`render_spot`] with a Blinn-Phong highlight on the texture, if `specular` is given.
fn render_spot_lit(scale: u32, filter: Option<Filter>, specular: Option<Specular>) -> Vec<Rgb565> {
    let (w, h) = (FRAME.0 * scale, FRAME.1 * scale);
    let mut pixels = vec![BACKGROUND; (w * h) as usize];
    let mut depth = vec![0u16; (w * h) as usize];
    let mut target = DepthTarget::new(&mut pixels, &mut depth, w, h).expect("buffers fit");
    target.clear(BACKGROUND);
    let pipeline = spot_pipeline(scale);
    let stats = match filter {
        Some(filter) => {
            let texture = Texture::new(SPOT_TEXTURE, SPOT_TEXTURE_WIDTH, SPOT_TEXTURE_HEIGHT)
                .expect("256 × 256 texels")
                .with_filter(filter);
            let mut material = TexturedMaterial::new(&texture, Shading::Gouraud);
            if let Some(specular) = specular {
                material = material.with_specular(specular);
            }
            pipeline.draw_textured_mesh(&SPOT_TEXTURED, &material, &mut target)
        }
        None => {
            let material = Material::new(SPOT_COLOR, Shading::Gouraud);
            pipeline.draw_mesh(&SPOT_TEXTURED, &material, &mut target)
        }
    };
    assert!(stats.drawn > 1000, "{stats:?}");
    pixels
}

/// Copies the `size` pixels of `pixels` (rows of `width`) from `from` into `display` at `to`,
/// each repeated `zoom` × `zoom` times.
fn blit(
    display: &mut SimulatorDisplay<Rgb565>,
    pixels: &[Rgb565],
    width: u32,
    from: Point,
    size: Size,
    to: Point,
    zoom: u32,
) {
    let area = Rectangle::new(to, size * zoom);
    let colors = (0..size.height * zoom).flat_map(|y| {
        (0..size.width * zoom).map(move |x| {
            let (x, y) = (from.x as u32 + x / zoom, from.y as u32 + y / zoom);
            pixels[(y * width + x) as usize]
        })
    });
    display.fill_contiguous(&area, colors).expect("infallible");
}

fn label(display: &mut SimulatorDisplay<Rgb565>, text: &str, at: Point) {
    // On a dark box: readable over the light parts of a picture too.
    let style = MonoTextStyleBuilder::new()
        .font(&FONT_6X10)
        .text_color(LABEL)
        .background_color(BACKGROUND)
        .build();
    Text::new(text, at, style)
        .draw(display)
        .expect("infallible");
}

fn save(display: &SimulatorDisplay<Rgb565>, name: &str) {
    let settings = OutputSettingsBuilder::new().scale(1).build();
    let path = format!("docs/{name}");
    display
        .to_rgb_output_image(&settings)
        .save_png(&path)
        .expect("write PNG");
    println!("wrote {path}");
}

/// `textured_spot.png`: the textured spot (bilinear), the same with a highlight, and the plain
/// one, side by side.
fn textured_spot() {
    let (w, h) = FRAME;
    let mut display = SimulatorDisplay::new(Size::new(3 * w, h));
    let highlight = Specular::new(Scalar::from_num(0.5), 24);
    let panels = [
        (Some(Filter::Bilinear), None, "textured, Gouraud"),
        (
            Some(Filter::Bilinear),
            Some(highlight),
            "textured, specular",
        ),
        (None, None, "untextured, Gouraud"),
    ];
    for (k, (filter, specular, name)) in panels.into_iter().enumerate() {
        let pixels = render_spot_lit(1, filter, specular);
        let at = Point::new(k as i32 * w as i32, 0);
        blit(
            &mut display,
            &pixels,
            w,
            Point::zero(),
            Size::new(w, h),
            at,
            1,
        );
        label(&mut display, name, at + Point::new(6, 12));
    }
    save(&display, "textured_spot.png");
}

/// `texture_filters.png`: spot's eyes in the frame drawn at twice the benchmark's size
/// (about two pixels a texel), nearest and bilinear, each crop shown at 4×.
fn texture_filters() {
    const SCALE: u32 = 2;
    const ZOOM: u32 = 4;
    let crop = Rectangle::new(Point::new(160, 110), Size::new(80, 60));
    let panel = crop.size * ZOOM;
    let mut display = SimulatorDisplay::new(Size::new(2 * panel.width, panel.height));
    let panels = [
        (Filter::Nearest, "Filter::Nearest, 4x"),
        (Filter::Bilinear, "Filter::Bilinear, 4x"),
    ];
    for (k, (filter, name)) in panels.into_iter().enumerate() {
        let pixels = render_spot(SCALE, Some(filter));
        let at = Point::new(k as i32 * panel.width as i32, 0);
        let width = FRAME.0 * SCALE;
        blit(
            &mut display,
            &pixels,
            width,
            crop.top_left,
            crop.size,
            at,
            ZOOM,
        );
        label(&mut display, name, at + Point::new(6, 12));
    }
    save(&display, "texture_filters.png");
}

/// Side of the sprite's texture, in texels.
const LOGO: u32 = 64;

/// A 64 × 64 Rgb565 logo built in code: a bordered badge with a blue-to-teal gradient, a white
/// arrow pointing up and an orange dot in its upper-right corner (so rotations and mirror
/// images tell apart), as raw 5-6-5 words. The arrow and the dot are antialiased: each texel
/// takes them by the signed distance of its centre to their outlines.
fn logo_texels() -> Vec<u16> {
    let half = LOGO as f32 / 2.0;
    // Signed distances (units, negative inside) from the badge's centre, y down: the arrow's
    // head (apex (0, −11), base y = −1, 18 wide), its shaft (6 wide, into the head so the two
    // overlap), the dot.
    let head = |x: f32, y: f32| {
        let side = (10.0 * x.abs() - 9.0 * (y + 11.0)) / (10.0f32.powi(2) + 9.0f32.powi(2)).sqrt();
        side.max(y + 1.0)
    };
    let shaft = |x: f32, y: f32| (x.abs() - 3.0).max(y - 11.0).max(-3.0 - y);
    let dot = |x: f32, y: f32| ((x - 10.0).powi(2) + (y + 10.0).powi(2)).sqrt() - 3.0;
    // Texels a unit of the shapes' 32-unit design, and the coverage of a texel centre at a
    // distance in units: a ramp a texel wide.
    let unit = LOGO as f32 / 32.0;
    let cover = |distance: f32| (0.5 - distance * unit).clamp(0.0, 1.0);
    let mix = |a: [f32; 3], b: [f32; 3], t: f32| [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t);
    let mut texels = Vec::with_capacity((LOGO * LOGO) as usize);
    for y in 0..LOGO {
        for x in 0..LOGO {
            let rim = LOGO / 16;
            let border = x < rim || y < rim || x >= LOGO - rim || y >= LOGO - rim;
            let rgb = if border {
                [4.0, 8.0, 12.0]
            } else {
                // Blue at the top left to teal at the bottom right, in 5-6-5 levels.
                let t = (x + y) as f32 / (2.0 * LOGO as f32);
                let ground = [4.0 + 2.0 * t, 14.0 + 36.0 * t, 28.0 - 6.0 * t];
                let (cx, cy) = (
                    (x as f32 + 0.5 - half) / unit,
                    (y as f32 + 0.5 - half) / unit,
                );
                let arrow = cover(head(cx, cy).min(shaft(cx, cy)));
                let with_dot = mix(ground, [31.0, 36.0, 0.0], cover(dot(cx, cy)));
                mix(with_dot, [31.0, 63.0, 31.0], arrow)
            };
            let [r, g, b] = rgb.map(|c| c.round() as u8);
            texels.push(Rgb565::new(r, g, b).into_storage());
        }
    }
    texels
}

/// The two triangles of a textured quad showing the whole of a `width × height` texture,
/// centred at `centre`, scaled by `scale` (pixels a texel) and turned by `degrees`
/// (clockwise on the screen, whose y is down). They share the diagonal from the texture's
/// top-left corner to its bottom-right, so the quad's pixels are each drawn once.
fn sprite_quad<'t, S: TexelSource>(
    texture: &'t Texture<S>,
    centre: (f32, f32),
    degrees: f32,
    scale: f32,
) -> [TexturedTriangle<'t, S, Rgb565>; 2]
where
    Rgb565: From<S::Color>,
{
    let (w, h) = (texture.width() as f32, texture.height() as f32);
    let (sin, cos) = degrees.to_radians().sin_cos();
    let corner = |u: f32, v: f32| {
        let (dx, dy) = (scale * (u - w / 2.0), scale * (v - h / 2.0));
        let x = centre.0 + dx * cos - dy * sin;
        let y = centre.1 + dx * sin + dy * cos;
        TexturedVertex::new(x, y, u, v)
    };
    let [a, b, c, d] = [
        corner(0.0, 0.0),
        corner(w, 0.0),
        corner(w, h),
        corner(0.0, h),
    ];
    [
        TexturedTriangle::new([a, b, c], texture),
        TexturedTriangle::new([a, c, d], texture),
    ]
}

/// Side of a sprite panel.
const PANEL: u32 = 160;

/// The panel's background, into any target: a vertical gradient (two Gouraud triangles) with a
/// grid over it.
fn background<D: DrawTarget<Color = Rgb565>>(
    target: &mut D,
    origin: Point,
) -> Result<(), D::Error> {
    let (x0, y0) = (origin.x as f32, origin.y as f32);
    let side = PANEL as f32;
    let (top, bottom) = (Rgb565::new(2, 6, 8), Rgb565::new(8, 12, 4));
    let v = |x: f32, y: f32, c| Vertex::new(x0 + x, y0 + y, c);
    GouraudTriangle::new([v(0.0, 0.0, top), v(side, 0.0, top), v(side, side, bottom)])
        .draw(target)?;
    GouraudTriangle::new([
        v(0.0, 0.0, top),
        v(side, side, bottom),
        v(0.0, side, bottom),
    ])
    .draw(target)?;
    let grid = PrimitiveStyle::with_stroke(Rgb565::new(6, 14, 8), 1);
    for k in (10..PANEL as i32).step_by(20) {
        Line::new(
            origin + Point::new(k, 0),
            origin + Point::new(k, PANEL as i32 - 1),
        )
        .into_styled(grid)
        .draw(target)?;
        Line::new(
            origin + Point::new(0, k),
            origin + Point::new(PANEL as i32 - 1, k),
        )
        .into_styled(grid)
        .draw(target)?;
    }
    Ok(())
}

/// `sprite.png`: the logo at four angles and scales drawn with `draw_into` into a
/// `SliceFramebuffer`, and a fifth drawn with `Drawable::draw` into the simulator's display.
fn sprite() {
    let texels = logo_texels();
    // Bilinear between texels; clamped, so the quad's edges do not blend in the opposite edge.
    let texture = Texture::new(Rgb565Texels(&texels), LOGO, LOGO)
        .expect("64 × 64 texels")
        .with_wrap(Wrap::Clamp, Wrap::Clamp)
        .with_filter(Filter::Bilinear);
    let frames = [(0.0, 1.0), (30.0, 1.25), (135.0, 1.5), (250.0, 0.75)];
    let centre = PANEL as f32 / 2.0;

    // The strip: one framebuffer, `draw_into`.
    let (w, h) = (PANEL * frames.len() as u32, PANEL);
    let mut pixels = vec![BACKGROUND; (w * h) as usize];
    let mut strip = SliceFramebuffer::new(&mut pixels, w, h).expect("buffer fits");
    for (k, &(degrees, scale)) in frames.iter().enumerate() {
        let origin = Point::new(k as i32 * PANEL as i32, 0);
        background(&mut strip, origin).expect("infallible");
        let at = (origin.x as f32 + centre, centre);
        for triangle in sprite_quad(&texture, at, degrees, scale) {
            triangle.draw_into(&mut strip);
        }
    }

    let mut display = SimulatorDisplay::new(Size::new(w + PANEL, h));
    blit(
        &mut display,
        &pixels,
        w,
        Point::zero(),
        Size::new(w, h),
        Point::zero(),
        1,
    );
    for (k, &(degrees, scale)) in frames.iter().enumerate() {
        let at = Point::new(k as i32 * PANEL as i32 + 6, 12);
        label(&mut display, &format!("{degrees} deg, {scale}x"), at);
        label(
            &mut display,
            "draw_into",
            at + Point::new(0, PANEL as i32 - 18),
        );
    }

    // The fifth panel: any DrawTarget, through `Drawable::draw`.
    let origin = Point::new(w as i32, 0);
    let (degrees, scale) = (-20.0, 1.75);
    background(&mut display, origin).expect("infallible");
    let at = (origin.x as f32 + centre, centre);
    for triangle in sprite_quad(&texture, at, degrees, scale) {
        triangle.draw(&mut display).expect("infallible");
    }
    // The same sprite with `draw_into`: the same pixels.
    let mut check = vec![BACKGROUND; (PANEL * PANEL) as usize];
    let mut framebuffer = SliceFramebuffer::new(&mut check, PANEL, PANEL).expect("buffer fits");
    background(&mut framebuffer, Point::zero()).expect("infallible");
    for triangle in sprite_quad(&texture, (centre, centre), degrees, scale) {
        triangle.draw_into(&mut framebuffer);
    }
    for (i, &color) in check.iter().enumerate() {
        let p = origin + Point::new(i as i32 % PANEL as i32, i as i32 / PANEL as i32);
        assert_eq!(display.get_pixel(p), color, "at {p}");
    }
    let at = origin + Point::new(6, 12);
    label(&mut display, &format!("{degrees} deg, {scale}x"), at);
    label(
        &mut display,
        "Drawable::draw",
        at + Point::new(0, PANEL as i32 - 18),
    );
    save(&display, "sprite.png");
}

fn main() {
    std::fs::create_dir_all("docs").expect("create docs/");
    textured_spot();
    texture_filters();
    sprite();
}
