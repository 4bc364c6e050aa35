//! The `accelbench` command line: one file per subcommand, all logic in the library.

/// `println!` for the subcommands, shadowing std's (which panics when stdout cannot be
/// written): writes the line through [`out::write_stdout`] and returns its error from the
/// enclosing function with `?`, so the command ends with `error: writing to standard output`.
/// Defined before the subcommand modules, so it is the `println!` they see.
macro_rules! println {
    () => {
        $crate::cli::out::write_stdout(format_args!("\n"))?
    };
    ($($arg:tt)*) => {
        $crate::cli::out::write_stdout(format_args!("{}\n", format_args!($($arg)*)))?
    };
}

/// `print!` for the subcommands, as [`println!`] without the newline.
macro_rules! print {
    ($($arg:tt)*) => {
        $crate::cli::out::write_stdout(format_args!($($arg)*))?
    };
}

mod out;

mod accuracy;
mod animate;
mod compare;
mod gen_obj;
mod info;
mod kernel_arg;
mod merge;
mod rays;
mod render;
mod report;
mod run;
mod scale;
mod stress;
mod suite_args;
mod sweep;
mod threads;
mod trace;
mod verify;

use anyhow::Context;
use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Debug, Parser)]
#[command(
    name = "accelbench",
    version,
    about = "Races ray-casting acceleration structures on the same scenes and rays"
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run the suite: every scene x index x ray set x thread count, verified, with a report.
    Run(run::RunArgs),
    /// A moving scene, frame after frame: refit against rebuild per index, verified per frame.
    Animate(animate::AnimateArgs),
    /// Every index on one generator at growing sizes: build time, memory and rays/s against size.
    Scale(scale::ScaleArgs),
    /// Only verify: every index against brute force and each other, no timing.
    Verify(verify::VerifyArgs),
    /// Primitive counts, bounds and degenerate triangles of a scene.
    Info(info::InfoArgs),
    /// Write a standard ray set of a scene to a .rays file.
    Rays(rays::RaysArgs),
    /// Trace a .rays file with one index and write the .hits file.
    Trace(trace::TraceArgs),
    /// Write a generator's triangles as an .obj or binary .ply file (by default into meshes/).
    Gen(gen_obj::GenArgs),
    /// Render a scene through an index as a PNG: Phong shading with shadows, or a cost heat map.
    Render(render::RenderArgs),
    /// Race one index at many parameter values (`sweep grid`) and write a CSV and charts.
    Sweep(sweep::SweepArgs),
    /// Kernel time against error, and watertightness far from the origin (reports/accuracy/).
    Accuracy(accuracy::AccuracyArgs),
    /// Corner cases on every index against brute force, bad rays, self-intersection (reports/stress/).
    Stress(stress::StressArgs),
    /// Run B against run A per scene x index x ray set x threads (speed ratio, noise, CI gate).
    Compare(compare::CompareArgs),
    /// Combine the report folders of `run --shard K/N` (every K) into one report.
    Merge(merge::MergeArgs),
    /// A report folder's dated results page in Markdown, for docs/results/.
    Report(report::ReportArgs),
}

/// Runs the command line; errors print as `error: ...` with their causes and exit non-zero.
pub fn main() -> ExitCode {
    end_quietly_on_closed_pipe();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_or_help(&e),
    };
    // Every build is held to the default budget; `--memory-budget` replaces it.
    if let Some(b) = crate::harness::memory::Budget::of(None) {
        b.hold_builds();
    }
    let result = match cli.command {
        Command::Run(a) => run::run(a),
        Command::Animate(a) => animate::run(a),
        Command::Verify(a) => verify::run(a),
        Command::Scale(a) => scale::run(a),
        Command::Info(a) => info::run(a),
        Command::Rays(a) => rays::run(a),
        Command::Trace(a) => trace::run(a),
        Command::Gen(a) => gen_obj::run(a),
        Command::Render(a) => render::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::Accuracy(a) => accuracy::run(a),
        Command::Stress(a) => stress::run(a),
        Command::Compare(a) => compare::run(a),
        Command::Merge(a) => merge::run(a),
        Command::Report(a) => report::run(a),
    };
    let result = result.and_then(|()| out::flush_stdout());
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            match e.is::<run::Interrupted>() {
                true => ExitCode::from(130),
                false => ExitCode::FAILURE,
            }
        }
    }
}

/// Prints clap's usage error (stderr, exit 2) or the help or version asked for (stdout, exit 0),
/// failing with exit 1 when that cannot be written.
fn usage_or_help(e: &clap::Error) -> ExitCode {
    let printed =
        (e.print().context("writing to standard output")).and_then(|()| out::flush_stdout());
    match printed {
        Ok(()) => ExitCode::from(e.exit_code().clamp(0, 255) as u8),
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::FAILURE
        }
    }
}

/// Restores the default action of SIGPIPE (end the process), which Rust's runtime sets to
/// "ignore": without this, `accelbench info ... | head` panics with "failed printing to
/// stdout: Broken pipe" when `head` closes the pipe. Every command then ends quietly, as
/// Unix tools do.
fn end_quietly_on_closed_pipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in main, before any thread starts; SIG_DFL is a valid action.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}
