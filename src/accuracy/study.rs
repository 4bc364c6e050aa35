//! The time-against-error study: every triangle and sphere kernel in `f32` and `f64`, and every
//! shape kernel in `f32`, on every ray family that applies, at every offset, measured against the
//! reference (exact for triangles and spheres, the `f64` mirror for shapes: false misses, false
//! hits, wrong primitives, relative `t` error) and timed (ns per primitive test).

use super::families::{Family, family_rays, full_offsets, icosphere_at, object_size, spheres_at};
use super::kernels::{Prims, kernel_closest, time_variant, variants};
use super::kernels_f64::Ray64;
use super::metrics::{Tally, rate, reference_closest};
use super::shape_families::{self, shape_at, shape_rays};
use crate::geometry::triangle::exact::fallback_count;
use crate::geometry::{Ray, ShapeError};
use rayon::prelude::*;
use serde::Serialize;

pub use super::kernels::{Kernel, Precision};

/// What to run.
#[derive(Debug, Clone)]
pub struct AccuracyConfig {
    /// Rays per family and offset.
    pub rays: usize,
    /// Translations from the origin (scene units, on every axis).
    pub offsets: Vec<f64>,
    /// Subdivision level of the icosphere mesh (`20 * 4^level` triangles).
    pub icosphere_level: u32,
    /// Timing repeats per kernel and family (best is kept); 0 skips timing (`ns_per_test` NaN).
    pub timing_repeats: usize,
    pub seed: u64,
}

impl AccuracyConfig {
    /// The command line's default: offsets `0, 1e0 .. 1e7`.
    pub fn full(rays: usize) -> AccuracyConfig {
        AccuracyConfig {
            rays,
            offsets: full_offsets(),
            icosphere_level: 2,
            timing_repeats: 3,
            seed: 7,
        }
    }

    /// A small configuration (tests, `--quick`).
    pub fn quick(rays: usize) -> AccuracyConfig {
        AccuracyConfig {
            offsets: vec![0.0, 1e3, 1e5, 1e7],
            icosphere_level: 1,
            timing_repeats: 1,
            ..AccuracyConfig::full(rays)
        }
    }
}

/// One line of `accuracy.csv`: a kernel in one precision on one family at one offset.
#[derive(Debug, Clone, Serialize)]
pub struct AccuracyRow {
    pub kernel: Kernel,
    pub precision: Precision,
    pub family: Family,
    pub offset: f64,
    /// Object size at this offset (scene units).
    pub object_size: f64,
    pub rays: usize,
    /// Rays the reference could not certify (left out of every rate).
    pub unverifiable: usize,
    /// Rays the exact reference says hit something.
    pub reference_hits: usize,
    pub false_misses: usize,
    pub false_hits: usize,
    pub wrong_primitives: usize,
    /// `false_misses / reference_hits` (leaks).
    pub false_miss_rate: f64,
    /// `false_hits / reference misses`.
    pub false_hit_rate: f64,
    /// `wrong_primitives / reference_hits`.
    pub wrong_primitive_rate: f64,
    /// `|t - t_ref| / t_ref` over rays where kernel and reference hit the same primitive (or a
    /// tied one).
    pub max_rel_t_error: f64,
    pub mean_rel_t_error: f64,
    /// Nanoseconds per primitive test on this family at the first offset, single thread, best
    /// of `timing_repeats`, each over at least `kernels::MIN_TIMED_TESTS` tests (NaN when not
    /// timed).
    pub ns_per_test: f64,
    /// The exact kernel's edge functions decided by its exact fallback, over all its edge
    /// functions (three per primitive test) on this family and offset; NaN for other kernels.
    pub exact_fallback_rate: f64,
}

/// Runs the study: one row per kernel, precision, family and offset (shape kernels in `f32`
/// only: their `f64` mirrors are the reference). Errors only if a study shape cannot be built.
pub fn run(config: &AccuracyConfig) -> Result<Vec<AccuracyRow>, ShapeError> {
    let mut rows = Vec::new();
    for family in Family::MESH {
        for spheres in [false, true] {
            if spheres && family.is_edges() {
                continue;
            }
            rows.extend(measure(
                config,
                family,
                &variants(spheres),
                |offset, seed| {
                    if spheres {
                        let s = spheres_at(offset);
                        let rays = family_rays(family, &s, offset, config.rays, seed);
                        Ok((Prims::Spheres(s), rays))
                    } else {
                        let t = icosphere_at(config.icosphere_level, offset);
                        let rays = family_rays(family, &t, offset, config.rays, seed);
                        Ok((Prims::Tris(t), rays))
                    }
                },
            )?);
        }
    }
    for kernel in Kernel::SHAPES {
        for family in shape_families::families(kernel) {
            rows.extend(measure(
                config,
                family,
                &[(kernel, Precision::F32)],
                |offset, seed| {
                    let shape = shape_at(kernel, offset)?;
                    let rays = shape_rays(family, &shape, offset, config.rays, seed);
                    let shapes = vec![shape];
                    Ok((Prims::Shapes { shapes, kernel }, rays))
                },
            )?);
        }
    }
    Ok(rows)
}

/// The rows of some kernel variants on one family at every offset; `make` gives the primitives
/// and rays at an offset (with a seed per offset). Timed at the first offset.
fn measure(
    config: &AccuracyConfig,
    family: Family,
    vars: &[(Kernel, Precision)],
    make: impl Fn(f64, u64) -> Result<(Prims, Vec<Ray>), ShapeError>,
) -> Result<Vec<AccuracyRow>, ShapeError> {
    let mut rows = Vec::new();
    let mut timings: Vec<f64> = Vec::new();
    for (oi, &offset) in config.offsets.iter().enumerate() {
        let seed = config.seed ^ (oi as u64) << 32;
        let (prims, rays) = make(offset, seed)?;
        if oi == 0 {
            timings = vars
                .iter()
                .map(|&(k, p)| time_variant(k, p, &prims, &rays, config.timing_repeats))
                .collect();
        }
        let bsph: Vec<_> = (0..prims.len()).map(|i| prims.bounding_sphere(i)).collect();
        let tallies = rays
            .par_iter()
            .fold(
                || vec![Tally::default(); vars.len()],
                |mut acc, ray| {
                    let r = reference_closest(&prims, &bsph, ray);
                    let r64 = Ray64::from_ray(ray);
                    for (slot, &(k, p)) in acc.iter_mut().zip(vars) {
                        let before = fallback_count();
                        let got = kernel_closest(k, p, &prims, ray, &r64);
                        slot.fallbacks += fallback_count() - before;
                        slot.tests += prims.len() as u64;
                        slot.score(&prims, ray, r, got, p);
                    }
                    acc
                },
            )
            .reduce(
                || vec![Tally::default(); vars.len()],
                |a, b| a.into_iter().zip(b).map(|(x, y)| x.merge(y)).collect(),
            );
        for ((&(kernel, precision), t), &ns) in vars.iter().zip(tallies).zip(&timings) {
            rows.push(AccuracyRow {
                kernel,
                precision,
                family,
                offset,
                object_size: object_size(offset),
                rays: t.rays,
                unverifiable: t.unverifiable,
                reference_hits: t.ref_hits,
                false_misses: t.false_misses,
                false_hits: t.false_hits,
                wrong_primitives: t.wrong,
                false_miss_rate: rate(t.false_misses, t.ref_hits),
                false_hit_rate: rate(t.false_hits, t.ref_misses),
                wrong_primitive_rate: rate(t.wrong, t.ref_hits),
                max_rel_t_error: t.err_max,
                mean_rel_t_error: if t.err_n == 0 {
                    0.0
                } else {
                    t.err_sum / t.err_n as f64
                },
                ns_per_test: ns,
                exact_fallback_rate: if kernel == Kernel::Exact {
                    t.fallbacks as f64 / (3 * t.tests.max(1)) as f64
                } else {
                    f64::NAN
                },
            });
        }
    }
    Ok(rows)
}
