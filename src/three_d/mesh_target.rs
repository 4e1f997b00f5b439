//! What the pipeline's mesh draws take as their target: a [`DepthTarget`] (the whole frame) or a
//! band of a frame (the band module's `DepthBand`), so that one call reads the same for both:
//! `pipeline.draw_mesh(mesh, material, target)`.

use embedded_graphics::primitives::Rectangle;

use super::{DepthTarget, TargetClip};
use crate::raster::band::{AllRows, RowWindow};

/// A target of [`Pipeline::draw_mesh`](super::Pipeline::draw_mesh) and its kin: a
/// [`DepthTarget`] of the whole frame, or a band of it (`band::DepthBand`), which gets the
/// band's rows of the frame: the same pixels and depths there. Sealed: implemented by those two
/// only.
pub trait MeshTarget<C>: sealed::Target<C> {}

pub(crate) mod sealed {
    use super::*;

    /// The clip of a draw into the target, and its depth target.
    #[allow(private_bounds, private_interfaces)]
    pub trait Target<C> {
        /// The rows a draw fills.
        type Rows: RowWindow;

        /// The clip of a draw through `viewport` into the target.
        fn clip(&self, viewport: &Rectangle) -> TargetClip<Self::Rows>;

        /// Runs `draw` with the target's colours and depths.
        fn with_depth<R>(&mut self, draw: impl FnOnce(&mut DepthTarget<'_, C>) -> R) -> R;
    }
}

#[allow(private_bounds, private_interfaces)]
impl<C: embedded_graphics::prelude::PixelColor> sealed::Target<C> for DepthTarget<'_, C> {
    type Rows = AllRows;

    #[inline(always)]
    fn clip(&self, viewport: &Rectangle) -> TargetClip<AllRows> {
        TargetClip::new(viewport, self)
    }

    #[inline(always)]
    fn with_depth<R>(&mut self, draw: impl FnOnce(&mut DepthTarget<'_, C>) -> R) -> R {
        draw(self)
    }
}

impl<C: embedded_graphics::prelude::PixelColor> MeshTarget<C> for DepthTarget<'_, C> {}
