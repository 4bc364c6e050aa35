//! `accelbench run`: the suite. Every scene x index x ray set x thread count, timed and counted,
//! every hit verified, and a report under `reports/<run id>/`, written whole into place at the
//! end ([`ReportDir`]) with its status: `complete`, `interrupted` (SIGINT) or `failed: ...`.

use super::suite_args::SuiteArgs;
use super::threads::parse_threads;
use crate::harness::interrupt;
use crate::harness::suite::{SuiteResult, check_specs, run_suite_with};
use crate::harness::workload::RaySet;
use crate::index::{TraceIndex, build_index};
use crate::render::{Picture, RenderOptions, write_scene_pictures};
use crate::report::report_dir::ReportDir;
use crate::report::run_notes::PictureRef;
use crate::report::suite_report::{RunMeta, RunStatus, run_id_now, write_suite_report};
use crate::report::verdict::{verdict_text, verdicts};
use crate::scene::Scene;
use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

#[derive(Debug, clap::Args)]
pub struct RunArgs {
    #[command(flatten)]
    suite: SuiteArgs,
    /// Thread counts, comma-separated [default: all cores; with --full 1 and all cores].
    #[arg(long, value_delimiter = ',', value_parser = parse_threads)]
    threads: Vec<usize>,
    /// The thorough configuration: all eight ray sets (ambient occlusion and the camera models
    /// too) at 1 thread and at all cores, about four times the default run's work (primary,
    /// shadow, diffuse and incoherent rays at all cores). --rays and --threads still choose.
    #[arg(long, conflicts_with = "quick")]
    full: bool,
    /// Timed repeats per measurement: the median is reported with its interval, which covers
    /// the median with at least 95% from 6 repeats on [default: 6, quick 3].
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1000))]
    repeats: Option<u64>,
    /// Report directory [default: reports/<run id>].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Side of the per-scene shaded render and heat maps in the report; 0 for none
    /// [default: 256, quick 128].
    #[arg(long, value_parser = clap::value_parser!(u32).range(0..=4096))]
    picture_size: Option<u32>,
}

/// A progress bar on stderr, hidden with `--quiet` or when stderr is not a terminal.
pub(crate) fn progress_bar(quiet: bool) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
    pb.set_style(
        ProgressStyle::with_template("{elapsed_precise} [{bar:30}] {pos}/{len} {wide_msg}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    pb
}

/// The thread counts of a run: those given, else all cores, and with `full` also 1.
fn default_threads(given: &[usize], full: bool) -> Vec<usize> {
    let mut t = if !given.is_empty() {
        given.to_vec()
    } else if full {
        vec![1, rayon::current_num_threads()]
    } else {
        vec![rayon::current_num_threads()]
    };
    t.sort_unstable();
    t.dedup();
    t
}

/// The report's pictures: per scene a shaded render and every index's heat maps (brute force's
/// are left out: it tests every primitive on every ray, one flat colour at great cost).
struct ScenePictures {
    dir: PathBuf,
    side: u32,
    written: Vec<(String, Vec<Picture>)>,
    error: Option<anyhow::Error>,
}

impl ScenePictures {
    fn new(dir: PathBuf, side: u32) -> ScenePictures {
        ScenePictures {
            dir,
            side,
            written: Vec::new(),
            error: None,
        }
    }

    fn add(&mut self, scene: &Scene, indices: &[&dyn TraceIndex]) {
        let fast: Vec<&dyn TraceIndex> = indices
            .iter()
            .copied()
            .filter(|i| i.name() != "brute")
            .collect();
        if self.side == 0 || fast.is_empty() || self.error.is_some() {
            return;
        }
        let opts = RenderOptions::new(self.side, self.side);
        let r = std::fs::create_dir_all(&self.dir)
            .map_err(anyhow::Error::from)
            .and_then(|()| Ok(write_scene_pictures(scene, &fast, &self.dir, &opts)?));
        match r {
            Ok(p) => self.written.push((scene.name.clone(), p)),
            Err(e) => self.error = Some(e.context(format!("rendering {}", scene.name))),
        }
    }

    /// The pictures written, by paths relative to the report folder `report`, and the error
    /// that stopped the rendering, if one did.
    fn into_refs(self, report: &Path) -> (Vec<PictureRef>, Option<anyhow::Error>) {
        let rel = |p: &Picture| {
            let r = p.path.strip_prefix(report).unwrap_or(&p.path);
            let parts: Vec<String> = r
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            parts.join("/")
        };
        let refs = self
            .written
            .iter()
            .flat_map(|(scene, pics)| {
                pics.iter().map(|p| PictureRef {
                    scene: scene.clone(),
                    caption: p.caption.clone(),
                    path: rel(p),
                })
            })
            .collect();
        (refs, self.error)
    }
}

/// `run` or `animate` stopped by a SIGINT; the command exits with 130, the shell's code for it.
#[derive(Debug, thiserror::Error)]
#[error(
    "interrupted: the report in {0} holds what was measured before the SIGINT (status: interrupted)"
)]
pub struct Interrupted(pub PathBuf);

/// How the run ended, and the error the command ends with when it did not end well: our
/// indices' mismatches, their failures, or a failed rendering (each keeps what was measured).
fn outcome(
    res: &SuiteResult,
    dir: &Path,
    pictures: Option<anyhow::Error>,
) -> (RunStatus, Option<anyhow::Error>) {
    if res.interrupted {
        return (RunStatus::Interrupted, Some(Interrupted(dir.into()).into()));
    }
    if res.mismatch_total > 0 {
        let status = format!(
            "verification failed, {} mismatching results",
            res.mismatch_total
        );
        let e = anyhow::anyhow!(
            "verification failed: {} mismatching results; the rays are in {}",
            res.mismatch_total,
            dir.join("mismatches.txt").display()
        );
        return (RunStatus::Failed(status), Some(e));
    }
    if res.failure_total > 0 {
        let status = format!("{} failures of our indices", res.failure_total);
        let e = anyhow::anyhow!(
            "some of our indices failed (the report has the rest):\n{}",
            failure_lines(res).join("\n")
        );
        return (RunStatus::Failed(status), Some(e));
    }
    match pictures {
        Some(e) => (RunStatus::Failed(format!("{e:#}")), Some(e)),
        None => (RunStatus::Complete, None),
    }
}

/// Every failure note, `scene / what: reason`.
fn failure_lines(res: &SuiteResult) -> Vec<String> {
    res.notes
        .iter()
        .filter(|n| n.is_failure())
        .map(|n| format!("{} / {}: {}", n.scene, n.what, n.reason))
        .collect()
}

pub fn run(mut a: RunArgs) -> anyhow::Result<()> {
    let repeats = a
        .repeats
        .map_or(if a.suite.quick { 3 } else { 6 }, |r| r as usize);
    if a.suite.rays.is_empty() && !a.full {
        a.suite.rays = RaySet::FIRST_RUN.to_vec();
    }
    let cfg = a
        .suite
        .config(default_threads(&a.threads, a.full), repeats, true)?;
    let run_id = format!(
        "{}{}",
        run_id_now(),
        if a.suite.quick { "-quick" } else { "" }
    );
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("reports").join(&run_id));
    let claim = ReportDir::claim(&dir)?;
    check_specs(&cfg.indices, cfg.kernel)?;
    let scenes = a.suite.load_scenes()?;
    a.suite.check_memory(&scenes, &cfg)?;
    interrupt::stop_on_sigint().context("installing the SIGINT handler")?;
    let command = std::env::args().collect::<Vec<_>>().join(" ");
    let pb = progress_bar(a.suite.quiet);
    let side = a
        .picture_size
        .unwrap_or(if a.suite.quick { 128 } else { 256 });
    let mut pictures = ScenePictures::new(claim.path().join("pictures"), side);
    let kernel = cfg.kernel;
    // Without a terminal (a pipe, a log file, CI) the progress bar is hidden: a line per
    // finished scene says how far the run is instead.
    let plain = !a.suite.quiet && !std::io::stderr().is_terminal();
    let (start, total) = (std::time::Instant::now(), scenes.len());
    let mut done = 0;
    let res = run_suite_with(
        &scenes,
        &cfg,
        &pb,
        &|s, g| build_index(s, g, kernel),
        &mut |scene, indices| {
            pictures.add(scene, indices);
            done += 1;
            if plain {
                eprintln!(
                    "[{:>5.0} s] scene {done}/{total} done: {}",
                    start.elapsed().as_secs_f64(),
                    scene.name
                );
            }
        },
    )?;
    let names = scenes.iter().map(|s| s.name.clone()).collect();
    let mut meta = RunMeta::collect(run_id, command, &cfg, names);
    let (pictures, picture_error) = pictures.into_refs(claim.path());
    let (status, error) = outcome(&res, &dir, picture_error);
    meta.status = status;
    write_suite_report(claim.path(), &meta, &res, pictures)
        .and_then(|()| claim.publish())
        .with_context(|| format!("writing the report to {}", dir.display()))?;
    // Skips and failures, one line each, also with --quiet (the report has them too).
    for n in &res.notes {
        eprintln!("note: {} / {}: {}", n.scene, n.what, n.reason);
    }
    print!("{}", verdict_text(&verdicts(&res.rows), 4));
    println!(
        "\nreport: {} (tables: {})",
        dir.join("index.html").display(),
        dir.join("summary.md").display()
    );
    if res.peer_mismatch_total > 0 {
        eprintln!(
            "note: peers ({}) differed from brute force on {} results (see mismatches.txt)",
            crate::report::differing_peers(&res.rows).join(", "),
            res.peer_mismatch_total
        );
    }
    error.map_or(Ok(()), Err)
}
