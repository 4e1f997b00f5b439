//! The crate's globs next to embedded-graphics' prelude (issue #32, item 5): `Angle` is
//! embedded-graphics' alone in scope (this crate's is `three_d::Angle`), so neither glob makes
//! the name ambiguous. This file compiles only while that holds: a second `Angle` at the crate's
//! root or in its prelude makes every use of `Angle` below an error (rustc reports some glob
//! ambiguities as a future-incompatibility warning for now: denied here).
#![deny(warnings)]

/// `use embedded_raster::*` with embedded-graphics' prelude.
mod root_glob {
    use embedded_graphics::{pixelcolor::Rgb565, prelude::*, primitives::Rectangle};
    use embedded_raster::three_d::meshes::icosphere::ICOSPHERE;
    use embedded_raster::*;

    #[test]
    fn angles_and_a_mesh() {
        // embedded-graphics' `Angle` and `.deg()`, as the matrices take them.
        let quarter: Angle = 90.0.deg();
        let exact = three_d::Angle::from_degrees(90);
        assert_eq!(Mat4::rotation_y(quarter), Mat4::rotation_y(exact));
        assert_eq!(
            Mat4::rotation_x(Angle::from_degrees(30.0)),
            Mat4::rotation_x(three_d::Angle::from_degrees(30))
        );
        assert_eq!(quarter.to_angle(), three_d::Angle::QUARTER);

        let (mut pixels, mut depth) = ([Rgb565::BLACK; 32 * 32], [0u16; 32 * 32]);
        let mut target = DepthTarget::new(&mut pixels, &mut depth, 32, 32).unwrap();
        let camera = Mat4::perspective(60.0.deg(), 1, 0.5, 20).unwrap()
            * Mat4::translation(Vec3::new(0, 0, -3));
        let viewport = Rectangle::new(Point::zero(), Size::new(32, 32));
        let pipeline = Pipeline::new(
            Mat4::rotation_y(30.0.deg()),
            camera,
            viewport,
            Light::default(),
        );
        let material = Material::new(Rgb565::WHITE, Shading::Gouraud);
        let stats = pipeline.draw_mesh(&ICOSPHERE, &material, &mut target);
        assert!(stats.drawn > 0);
        assert_ne!(target.framebuffer().get(16, 16), Some(Rgb565::BLACK));
    }
}

/// `use embedded_raster::prelude::*` with embedded-graphics' prelude.
mod prelude_glob {
    use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
    use embedded_raster::prelude::*;
    use embedded_raster::three_d;

    #[test]
    fn angles_and_degrees() {
        assert_eq!(
            Mat4::rotation_z(Angle::from_degrees(45.0)),
            Mat4::rotation_z(three_d::Angle::from_degrees(45))
        );
        // The prelude's `Degrees` and `ToAngle` side by side: integers are degrees, exactly.
        assert_eq!(Degrees::to_angle(90), three_d::Angle::QUARTER);
        assert_eq!(180.0.deg().to_angle(), three_d::Angle::HALF);

        let mut pixels = [Rgb565::BLACK; 8 * 8];
        let mut fb = SliceFramebuffer::new(&mut pixels, 8, 8).unwrap();
        SolidTriangle::new([(0.0, 0.0), (8.0, 0.0), (0.0, 8.0)], Rgb565::RED).draw_into(&mut fb);
        assert_eq!(fb.get(1, 1), Some(Rgb565::RED));
    }
}
