//! Pictures of a scene through any index: Phong-shaded renders with hard and soft shadows, and
//! per-pixel cost heat maps (primitive tests or node visits of each camera ray).
//!
//! Every picture traces through the object-safe [`TraceIndex`](crate::index::TraceIndex), so all indices render through
//! the same code, and the shading math is deterministic (area-light samples are seeded by pixel
//! and light, not by thread): the same hits give byte-identical images, whichever index.
//!
//! ```no_run
//! # use accelbench::{index, render, scene, geometry::TriangleKernelKind};
//! let scene = scene::load_scene("stadium:n=20000").unwrap();
//! let spec = "brute".parse().unwrap();
//! let idx = index::build_index(&spec, &scene.geometry(), TriangleKernelKind::Watertight).unwrap();
//! let opts = render::RenderOptions::new(256, 256);
//! render::render_shaded(&scene, idx.as_ref(), &opts).unwrap().write_png("shaded.png".as_ref()).unwrap();
//! let heat = render::render_heatmap(&scene, idx.as_ref(), &opts, render::HeatmapKind::Tests).unwrap();
//! heat.write_png("tests.png".as_ref()).unwrap();
//! ```

mod font;
mod heatmap;
mod image;
mod pictures;
mod sampling;
mod shade;
mod view;

pub use heatmap::{
    HEAT_MAX, HeatmapKind, heat_colour, heatmap_image, legend_height, pixel_costs, render_heatmap,
};
pub use image::Image;
pub use pictures::{Picture, write_scene_pictures};
pub use sampling::{Filter, MAX_SPP, Sampling};
pub use shade::{SHADOW_T_MAX, render_shaded, render_shaded_with};
pub use view::{pixel_ray, view_camera};

use crate::camera::CameraError;
use crate::geometry::RayError;
use std::path::PathBuf;
use thiserror::Error;

/// Largest accepted image side, in pixels.
pub const MAX_SIDE: u32 = 16_384;
/// Largest accepted pixel count (64 megapixels).
pub const MAX_PIXELS: u64 = 1 << 26;

/// Image size of a render or heat map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RenderOptions {
    pub width: u32,
    pub height: u32,
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        RenderOptions::new(512, 512)
    }
}

impl RenderOptions {
    /// An image of `width` x `height` pixels (checked by [`RenderOptions::validate`]).
    pub fn new(width: u32, height: u32) -> RenderOptions {
        RenderOptions { width, height }
    }

    /// Checks `1 <= width, height <= MAX_SIDE` and at most [`MAX_PIXELS`] pixels.
    pub fn validate(&self) -> Result<(), RenderError> {
        let (w, h) = (self.width, self.height);
        if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE || w as u64 * h as u64 > MAX_PIXELS {
            return Err(RenderError::Size(w, h));
        }
        Ok(())
    }
}

// The causes are in the messages, not chained sources, so `{:#}` prints each once.
impl From<CameraError> for RenderError {
    fn from(e: CameraError) -> Self {
        RenderError::Camera(e)
    }
}

impl From<RayError> for RenderError {
    fn from(e: RayError) -> Self {
        RenderError::Ray(e)
    }
}

/// Why a picture could not be made or written.
#[derive(Debug, Error)]
pub enum RenderError {
    #[error(
        "image size {0}x{1} is invalid: width and height must be 1 to {MAX_SIDE}, at most {MAX_PIXELS} pixels in all"
    )]
    Size(u32, u32),
    #[error("camera: {0}")]
    Camera(CameraError),
    #[error("camera ray: {0}")]
    Ray(RayError),
    #[error("{0} samples per pixel is invalid: use 1 to {MAX_SPP}")]
    Samples(u32),
    #[error("cannot write {path}: {message}")]
    Write { path: PathBuf, message: String },
}
