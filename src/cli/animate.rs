//! `accelbench animate`: a moving scene traced frame after frame, every index kept up to date by
//! a refit (where it has one) and by a rebuild, with the cost per frame, the tree's quality and
//! every frame verified against brute force ([`crate::harness::animate`]).

use super::kernel_arg::parse_kernel;
use super::run::{Interrupted, progress_bar};
use super::suite_args::{parse_index_specs, split_list};
use super::threads::{parse_threads, with_threads};
use crate::geometry::TriangleKernelKind;
use crate::harness::animate::{AnimateConfig, mismatches_fail, run_animation};
use crate::harness::interrupt;
use crate::harness::suite::check_specs;
use crate::harness::workload::{RaySet, SetSizes};
use crate::index::is_peer;
use crate::report::animate_report::{summary_markdown, write_animate_report};
use crate::report::report_dir::ReportDir;
use crate::report::suite_report::run_id_now;
use crate::scene::load_scene;
use crate::scene::motion::MotionSpec;
use anyhow::Context;
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(Debug, clap::Args)]
pub struct AnimateArgs {
    /// A mesh (.obj, .ply, .gltf, .glb) or .toml path, or a built-in scene name
    /// (`terrain`, `icosphere:n=100000`): its rest pose.
    #[arg(long)]
    scene: String,
    /// How the scene moves: `twist[:turns=0.25]` (about the vertical axis, more with height),
    /// `wave[:amplitude=0.02,waves=2]` (a travelling wave along x lifts it along y),
    /// `cloth[:drop=0.5,ball=0.3]` (it falls like a sheet and drapes over a ball) or
    /// `keyframes` (a scene file's keyframed objects move by their keys) [default: keyframes
    /// for a scene file with keyframes, else twist].
    #[arg(long)]
    motion: Option<MotionSpec>,
    /// Frames, the first being the motion's start (time 0) and the last its end (time 1).
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..=10_000))]
    frames: u32,
    /// Indices, comma-separated, with optional parameters; bvh, bvh4 and bvh8 get a refit row
    /// beside their rebuild row.
    #[arg(long, default_value = "bvh,bvh4,bvh8,kdtree,grid")]
    indices: String,
    /// Ray sets, comma-separated: primary, incoherent, dof, motion, lens (the same rays on every
    /// frame, from the rest pose's bounds).
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "primary,incoherent"
    )]
    rays: Vec<RaySet>,
    /// Width and height of the primary image.
    #[arg(long, default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=2048))]
    primary_size: u32,
    /// Number of incoherent rays.
    #[arg(long, default_value_t = 65_536, value_parser = clap::value_parser!(u64).range(1..=(1u64 << 22)))]
    incoherent: u64,
    /// Timed passes per ray set and frame (the median is kept).
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(1..=100))]
    repeats: u32,
    /// Most primitive-ray tests brute force makes per frame for its verification sample.
    #[arg(long, default_value_t = 200_000_000, value_parser = clap::value_parser!(u64).range(1..))]
    verify_budget: u64,
    /// Worker threads [default: all cores].
    #[arg(long, value_parser = parse_threads)]
    threads: Option<usize>,
    /// Triangle kernel every index uses.
    #[arg(long, default_value = "exact", value_parser = parse_kernel)]
    kernel: TriangleKernelKind,
    /// Report directory [default: reports/animate-<run id>].
    #[arg(long)]
    out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

pub fn run(a: AnimateArgs) -> anyhow::Result<()> {
    let indices = parse_index_specs(&split_list(&a.indices))?;
    check_specs(&indices, a.kernel)?;
    let scene = load_scene(&a.scene).with_context(|| format!("loading scene '{}'", a.scene))?;
    let motion = MotionSpec::for_scene(a.motion, &scene).map_err(anyhow::Error::msg)?;
    if motion != MotionSpec::Keyframes && !scene.keyframed.is_empty() {
        eprintln!("note: --motion {motion} deforms the static placement; the keyframes are unused");
    }
    let dir = a
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("reports").join(format!("animate-{}", run_id_now())));
    // Claimed first: a second run on the same folder is refused before anything is measured.
    let claim = ReportDir::claim(&dir)?;
    let cfg = AnimateConfig {
        motion,
        frames: a.frames as usize,
        indices,
        sets: a.rays,
        sizes: SetSizes {
            primary_side: a.primary_size,
            incoherent: a.incoherent as usize,
            ao_fraction: 0.05,
        },
        repeats: a.repeats as usize,
        kernel: a.kernel,
        verify_budget: a.verify_budget,
    };
    let threads = a.threads.unwrap_or_else(rayon::current_num_threads);
    interrupt::stop_on_sigint().context("installing the SIGINT handler")?;
    let pb = progress_bar(a.quiet);
    pb.set_length(cfg.frames as u64);
    // Without a terminal (a log, a test), one line per frame instead of the bar.
    let plain = !a.quiet && !std::io::stderr().is_terminal();
    let anim = with_threads(threads, || {
        run_animation(&scene, &cfg, |f| {
            pb.set_position(f as u64);
            pb.set_message(format!("frame {f}"));
            if plain {
                eprintln!("frame {}/{} started", f + 1, cfg.frames);
            }
        })
    })?
    .map_err(anyhow::Error::msg)?;
    pb.finish_and_clear();
    let title = format!(
        "{} ({} primitives), {}, {} frames, {threads} thread{}",
        scene.name,
        scene.len(),
        cfg.motion,
        cfg.frames,
        if threads == 1 { "" } else { "s" }
    );
    let wrong: usize = (anim.rows.iter())
        .filter(|r| mismatches_fail(r))
        .map(|r| r.mismatches)
        .sum();
    let failed: Vec<&str> = (anim.failures.iter())
        .filter(|f| !is_peer(f.row.split('+').next().unwrap_or_default()))
        .map(|f| f.row.as_str())
        .collect();
    let status = if anim.interrupted {
        "interrupted".to_owned()
    } else if wrong > 0 {
        format!("failed: verification failed, {wrong} mismatching results")
    } else if !failed.is_empty() {
        format!("failed: {} failed ({})", failed.len(), failed.join(", "))
    } else {
        "complete".to_owned()
    };
    let files = write_animate_report(claim.path(), &title, &status, &anim)?;
    let meta = serde_json::json!({
        "command": std::env::args().collect::<Vec<_>>().join(" "),
        "scene": scene.name,
        "motion": cfg.motion.to_string(),
        "frames": cfg.frames,
        "frames_done": anim.rows.iter().map(|r| r.frame + 1).max().unwrap_or(0),
        "threads": threads,
        "kernel": cfg.kernel.to_string(),
        "status": status,
    });
    std::fs::write(claim.path().join("meta.json"), format!("{meta:#}\n"))
        .context("writing meta.json")?;
    claim.publish()?;
    print!("{}", summary_markdown(&title, &status, &anim));
    eprintln!("report: {} ({} files)", dir.display(), files.len() + 1);
    for (row, frame, first) in &anim.first_mismatches {
        eprintln!("MISMATCH {row} at frame {frame}: {first}");
    }
    if anim.interrupted {
        return Err(Interrupted(dir).into());
    }
    anyhow::ensure!(
        wrong == 0,
        "verification failed: {wrong} mismatching results against brute force (above)"
    );
    anyhow::ensure!(
        failed.is_empty(),
        "{} failed (see the summary above): {}",
        failed.len(),
        failed.join(", ")
    );
    Ok(())
}
