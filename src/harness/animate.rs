//! `accelbench animate`: a scene that moves ([`crate::scene::motion`]), traced frame after
//! frame by every index, each kept up to date by a refit (`INDEX+refit`, where the index has
//! one) and by a rebuild (`INDEX+rebuild`), so a reader sees what each update costs, what it
//! does to the trace time, and when a refitted tree has degraded enough that rebuilding pays.
//!
//! Per frame and row: the update time (frame 0: the first build, shared by both rows of an
//! index), the median trace time of each ray set over the repeats, their sum, the tree's SAH
//! cost where the index reports one, and the verification: every row's hits against brute
//! force on that frame's primitives for a sample of the rays (all of them when the scene is
//! small; `verify_budget` bounds primitives times sampled rays), closest and any hit, bit for
//! bit. The rays stay the same on every frame (the camera does not move), made from the rest
//! pose's bounds.

use super::contain::contained;
use super::timing::timed_pass;
use super::verify::compare_with_expected;
use super::workload::{RaySet, SetSizes, camera_model_set, incoherent, primary};
use crate::geometry::{Hit, Ray, TriangleKernelKind};
use crate::index::{BuildError, IndexSpec, TraceIndex, build_index, is_peer};
use crate::scene::motion::MotionSpec;
use crate::scene::{Scene, SceneGeometry};
use serde::Serialize;
use std::time::{Duration, Instant};

/// What to animate and measure.
#[derive(Debug, Clone)]
pub struct AnimateConfig {
    /// `keyframes` only for a scene with keyframes ([`MotionSpec::for_scene`]).
    pub motion: MotionSpec,
    /// Frames, at least 2: frame `f` is the motion at time `f / (frames - 1)`.
    pub frames: usize,
    pub indices: Vec<IndexSpec>,
    /// Camera and incoherent sets only (the secondary sets follow from a frame's hits).
    pub sets: Vec<RaySet>,
    pub sizes: SetSizes,
    /// Timed passes per set and frame (the median is kept).
    pub repeats: usize,
    pub kernel: TriangleKernelKind,
    /// Most primitive-ray tests brute force makes per frame for the verification sample.
    pub verify_budget: u64,
}

/// How a row keeps its index up to date.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Update {
    Refit,
    Rebuild,
}

/// One row of one frame.
#[derive(Debug, Clone, Serialize)]
pub struct FrameRow {
    pub frame: usize,
    /// `INDEX+refit` or `INDEX+rebuild`.
    pub row: String,
    pub index: String,
    pub update: Update,
    /// Frame 0: the first build; then the refit or the rebuild, in milliseconds.
    pub update_ms: f64,
    /// Sum over the ray sets of the median trace time, in milliseconds.
    pub trace_ms: f64,
    pub total_ms: f64,
    /// Rays of every set over `trace_ms`.
    pub mrays_per_s: f64,
    /// The tree's SAH cost relative to its root (empty for indices that report none).
    pub sah_cost: Option<f64>,
    pub verified_rays: usize,
    pub mismatches: usize,
}

/// What went wrong with one row (a panic or an error in its build, refit or trace): the row is
/// dropped from that frame on, the others go on.
#[derive(Debug, Clone)]
pub struct RowFailure {
    pub row: String,
    pub frame: usize,
    pub reason: String,
}

/// Every frame's rows and the failures.
#[derive(Debug, Clone, Default)]
pub struct Animation {
    pub rows: Vec<FrameRow>,
    pub failures: Vec<RowFailure>,
    /// First mismatch of each row that had one, for the message.
    pub first_mismatches: Vec<(String, usize, String)>,
    /// A SIGINT stopped the animation before its last frame ([`super::interrupt`]): `rows`
    /// hold the frames finished before.
    pub interrupted: bool,
}

/// The ray sets of the rest pose, with their names; an error for a set `animate` cannot make.
pub fn animation_rays(
    scene: &Scene,
    cfg: &AnimateConfig,
) -> Result<Vec<(RaySet, Vec<Ray>)>, String> {
    cfg.sets
        .iter()
        .map(|&set| {
            let rays = match (set, set.camera_model()) {
                (RaySet::Primary, _) => primary(scene, &cfg.sizes).map_err(|e| e.to_string())?,
                (RaySet::Incoherent, _) => incoherent(scene, &cfg.sizes),
                (_, Some(kind)) => {
                    camera_model_set(scene, &cfg.sizes, kind).map_err(|e| e.to_string())?
                }
                _ => {
                    return Err(format!(
                        "ray set '{}' follows from a frame's hits, which animate does not \
                         trace: choose from primary, incoherent, dof, motion, lens",
                        set.name()
                    ));
                }
            };
            Ok((set, rays))
        })
        .collect()
}

/// One index's live rows: the refitted index (where it has a refit) carried from frame to frame.
struct Contender {
    spec: IndexSpec,
    refitted: Option<Box<dyn TraceIndex>>,
    refit_failed: bool,
    rebuild_failed: bool,
}

/// Runs the animation on the current rayon pool; `progress` is told each frame as it starts.
/// A SIGINT ([`super::interrupt::requested`]) stops it before the next frame.
pub fn run_animation(
    scene: &Scene,
    cfg: &AnimateConfig,
    mut progress: impl FnMut(usize),
) -> Result<Animation, String> {
    let sets = animation_rays(scene, cfg)?;
    let all_rays: usize = sets.iter().map(|(_, r)| r.len()).sum();
    let sample = verification_sample(&sets, scene.len(), cfg.verify_budget);
    let mut contenders: Vec<Contender> = cfg
        .indices
        .iter()
        .map(|spec| Contender {
            spec: spec.clone(),
            refitted: None,
            refit_failed: false,
            rebuild_failed: false,
        })
        .collect();
    let mut out = Animation::default();
    for frame in 0..cfg.frames {
        if super::interrupt::requested() {
            out.interrupted = true;
            break;
        }
        progress(frame);
        let t = frame as f32 / (cfg.frames - 1) as f32;
        let geom = cfg.motion.frame(scene, t)?;
        let expected = brute_hits(&geom, cfg.kernel, &sample)?;
        for c in &mut contenders {
            let measure = |index: &dyn TraceIndex, update: Update, update_time: Duration| {
                measure_row(
                    index,
                    update,
                    update_time,
                    frame,
                    &sets,
                    all_rays,
                    cfg.repeats,
                )
            };
            let check = |row: FrameRow, index: &dyn TraceIndex, out: &mut Animation| {
                let found = compare_with_expected(index, &sample, &expected);
                if let Some(first) = found.first() {
                    out.first_mismatches
                        .push((row.row.clone(), frame, first.to_string()));
                }
                out.rows.push(FrameRow {
                    verified_rays: sample.len(),
                    mismatches: found.len(),
                    ..row
                });
            };
            let rebuild_row = format!("{}+rebuild", c.spec.name);
            if frame == 0 {
                let started = Instant::now();
                match guarded(|| build_index(&c.spec, &geom, cfg.kernel)) {
                    Ok(index) => {
                        let build = started.elapsed();
                        let refit = index.can_refit();
                        for update in [Update::Refit, Update::Rebuild] {
                            if update == Update::Refit && !refit {
                                continue;
                            }
                            let row = measure(index.as_ref(), update, build);
                            check(row, index.as_ref(), &mut out);
                        }
                        c.refit_failed = !refit;
                        c.refitted = refit.then_some(index);
                    }
                    Err(reason) => {
                        c.refit_failed = true;
                        c.rebuild_failed = true;
                        out.failures
                            .push(failure(rebuild_row.clone(), frame, reason));
                    }
                }
                continue;
            }
            if let (false, Some(index)) = (c.refit_failed, c.refitted.as_mut()) {
                let started = Instant::now();
                match guarded(|| index.refit(&geom)) {
                    Ok(()) => {
                        let row = measure(index.as_ref(), Update::Refit, started.elapsed());
                        check(row, index.as_ref(), &mut out);
                    }
                    Err(reason) => refit_failed(c, &mut out, frame, reason),
                }
            }
            if !c.rebuild_failed {
                let started = Instant::now();
                match guarded(|| build_index(&c.spec, &geom, cfg.kernel)) {
                    Ok(index) => {
                        let row = measure(index.as_ref(), Update::Rebuild, started.elapsed());
                        check(row, index.as_ref(), &mut out);
                    }
                    Err(reason) => {
                        c.rebuild_failed = true;
                        out.failures
                            .push(failure(rebuild_row.clone(), frame, reason));
                    }
                }
            }
        }
    }
    Ok(out)
}

/// `f`'s result, its error or its panic ([`contained`]) as the reason.
fn guarded<R>(f: impl FnOnce() -> Result<R, BuildError>) -> Result<R, String> {
    contained(f).and_then(|r| r.map_err(|e| e.to_string()))
}

fn failure(row: String, frame: usize, reason: String) -> RowFailure {
    RowFailure { row, frame, reason }
}

fn refit_failed(c: &mut Contender, out: &mut Animation, frame: usize, reason: String) {
    c.refit_failed = true;
    c.refitted = None;
    let row = format!("{}+refit", c.spec.name);
    out.failures.push(failure(row, frame, reason));
}

/// The timed passes of one row on one frame (verification fields left at zero).
fn measure_row(
    index: &dyn TraceIndex,
    update: Update,
    update_time: Duration,
    frame: usize,
    sets: &[(RaySet, Vec<Ray>)],
    all_rays: usize,
    repeats: usize,
) -> FrameRow {
    let trace: Duration = sets
        .iter()
        .map(|(set, rays)| timed_pass(index, set.query(), rays, repeats).0.median)
        .sum();
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    let name = index.name().to_owned();
    let sah_cost = index
        .info()
        .extra
        .iter()
        .find(|(k, _)| k == "sah_cost")
        .map(|(_, v)| *v);
    FrameRow {
        frame,
        row: format!(
            "{name}+{}",
            match update {
                Update::Refit => "refit",
                Update::Rebuild => "rebuild",
            }
        ),
        index: name,
        update,
        update_ms: ms(update_time),
        trace_ms: ms(trace),
        total_ms: ms(update_time + trace),
        mrays_per_s: all_rays as f64 / trace.as_secs_f64().max(1e-12) / 1e6,
        sah_cost,
        verified_rays: 0,
        mismatches: 0,
    }
}

/// Every `k`-th ray of every set, `k` the smallest stride keeping `primitives` times the
/// sample within `budget` (every ray when it fits).
fn verification_sample(sets: &[(RaySet, Vec<Ray>)], primitives: usize, budget: u64) -> Vec<Ray> {
    let all: usize = sets.iter().map(|(_, r)| r.len()).sum();
    let fits = (budget / primitives.max(1) as u64).max(1) as usize;
    let stride = all.div_ceil(fits).max(1);
    sets.iter()
        .flat_map(|(_, rays)| rays.iter().step_by(stride).copied())
        .collect()
}

/// Brute force's closest hits on `rays` over one frame.
fn brute_hits(
    geom: &SceneGeometry,
    kernel: TriangleKernelKind,
    rays: &[Ray],
) -> Result<Vec<Option<Hit>>, String> {
    let brute = build_index(&IndexSpec::named("brute"), geom, kernel).map_err(|e| e.to_string())?;
    let mut hits = vec![None; rays.len()];
    brute.closest_hits(rays, &mut hits);
    Ok(hits)
}

/// The first frame from which rebuilding `index` costs less per frame (update plus trace) than
/// refitting it, and stays so to the last frame; `None` when it never does (or the index has
/// no refit row).
pub fn rebuild_overtakes(rows: &[FrameRow], index: &str) -> Option<usize> {
    let total = |update: Update, frame: usize| {
        rows.iter()
            .find(|r| r.index == index && r.update == update && r.frame == frame)
            .map(|r| r.total_ms)
    };
    let last = rows
        .iter()
        .filter(|r| r.index == index)
        .map(|r| r.frame)
        .max()?;
    let cheaper = |f: usize| match (total(Update::Rebuild, f), total(Update::Refit, f)) {
        (Some(rebuild), Some(refit)) => rebuild < refit,
        _ => false,
    };
    (1..=last).find(|&f| (f..=last).all(cheaper))
}

/// Whether a row's mismatches fail the run: ours do; a peer's are reported only.
pub fn mismatches_fail(row: &FrameRow) -> bool {
    row.mismatches > 0 && !is_peer(&row.index)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(frame: usize, update: Update, total_ms: f64) -> FrameRow {
        FrameRow {
            frame,
            row: String::new(),
            index: "bvh".into(),
            update,
            update_ms: 0.0,
            trace_ms: 0.0,
            total_ms,
            mrays_per_s: 0.0,
            sah_cost: None,
            verified_rays: 0,
            mismatches: 0,
        }
    }

    #[test]
    fn rebuild_overtakes_from_the_first_frame_it_stays_cheaper() {
        // Frame 0 is the shared build; rebuild is cheaper on frame 1, dearer on 2, then cheaper.
        let refit = [5.0, 4.0, 5.0, 8.0, 9.0];
        let rebuild = [5.0, 3.0, 6.0, 7.0, 7.0];
        let mut rows = Vec::new();
        for f in 0..5 {
            rows.push(row(f, Update::Refit, refit[f]));
            rows.push(row(f, Update::Rebuild, rebuild[f]));
        }
        assert_eq!(rebuild_overtakes(&rows, "bvh"), Some(3));
        rows.last_mut().unwrap().total_ms = 10.0;
        assert_eq!(rebuild_overtakes(&rows, "bvh"), None);
        assert_eq!(rebuild_overtakes(&rows, "grid"), None);
    }

    #[test]
    fn the_verification_sample_fits_the_budget() {
        let rays = vec![Ray::infinite(glam::Vec3::ZERO, glam::Vec3::X).unwrap(); 1000];
        let sets = vec![(RaySet::Primary, rays.clone()), (RaySet::Incoherent, rays)];
        assert_eq!(verification_sample(&sets, 10, 1_000_000).len(), 2000);
        let sample = verification_sample(&sets, 1000, 100_000);
        assert!(
            sample.len() * 1000 <= 100_000 && sample.len() >= 50,
            "{}",
            sample.len()
        );
    }
}
