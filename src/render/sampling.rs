//! Supersampling of shaded renders (`render --spp N --filter box|tent --camera MODEL`): each
//! pixel averages `spp` camera rays whose film positions, lens points and shutter times are
//! stratified ([`sampler::stratified`], seeded by pixel), weighted by a box or tent filter.
//! With one sample a ray goes through the pixel centre (the unsupersampled image).

use crate::camera::sampler::stratified;
use crate::camera::{CameraSample, ModelKind};
use crate::index::TraceMode;

/// Largest accepted number of samples per pixel.
pub const MAX_SPP: u32 = 4096;

/// Reconstruction filter over a pixel's own samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Filter {
    /// Every sample weighs the same.
    #[default]
    Box,
    /// A sample weighs `(1 - |dx|) (1 - |dy|)`, `dx`, `dy` its offsets from the pixel centre
    /// in pixels (a tent of radius one pixel, restricted to the pixel's own samples).
    Tent,
}

/// How a shaded render samples each pixel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sampling {
    /// Samples per pixel, 1 to [`MAX_SPP`].
    pub spp: u32,
    pub filter: Filter,
    pub camera: ModelKind,
    /// Seed of the strata's permutations and jitters.
    pub seed: u64,
    /// How each row's camera rays are traced as a batch (the image is the same in every mode).
    pub mode: TraceMode,
}

impl Default for Sampling {
    fn default() -> Sampling {
        Sampling {
            spp: 1,
            filter: Filter::Box,
            camera: ModelKind::Pinhole,
            seed: 1,
            mode: TraceMode::Single,
        }
    }
}

impl Sampling {
    /// Sample `k` of pixel `(i, j)` (`pixel` its row-major number): the camera sample and its
    /// filter weight.
    pub fn sample(&self, i: u32, j: u32, pixel: u64, k: u32) -> (CameraSample, f32) {
        let u = stratified(self.spp, k, pixel, self.seed);
        let film = if self.spp == 1 { [0.5, 0.5] } else { u.film };
        let weight = match self.filter {
            Filter::Box => 1.0,
            Filter::Tent => ((1.0 - (film[0] - 0.5).abs()) * (1.0 - (film[1] - 0.5).abs())) as f32,
        };
        let s = CameraSample {
            film: [i as f64 + film[0], j as f64 + film[1]],
            lens: u.lens,
            time: u.time,
        };
        (s, weight)
    }
}
