//! The `accelbench` command line: one file per subcommand, all logic in the library.

mod accuracy;
mod gen_obj;
mod info;
mod rays;
mod stress;
mod trace;

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
    /// Primitive counts, bounds and degenerate triangles of a scene.
    Info(info::InfoArgs),
    /// Write a standard ray set of a scene to a .rays file.
    Rays(rays::RaysArgs),
    /// Trace a .rays file with one index and write the .hits file.
    Trace(trace::TraceArgs),
    /// Write a generator's triangles as an .obj file (by default into meshes/).
    Gen(gen_obj::GenArgs),
    /// Kernel time against error, and watertightness far from the origin (reports/accuracy/).
    Accuracy(accuracy::AccuracyArgs),
    /// Corner cases on every index against brute force, bad rays, self-intersection (reports/stress/).
    Stress(stress::StressArgs),
}

/// Runs the command line; errors print as `error: ...` with their causes and exit non-zero.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(a) => info::run(a),
        Command::Rays(a) => rays::run(a),
        Command::Trace(a) => trace::run(a),
        Command::Gen(a) => gen_obj::run(a),
        Command::Accuracy(a) => accuracy::run(a),
        Command::Stress(a) => stress::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// Parses a `--threads` value: a positive count.
pub(crate) fn parse_threads(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if (1..=4096).contains(&n) => Ok(n),
        _ => Err(format!(
            "'{s}' is not a thread count: give a whole number from 1 to 4096"
        )),
    }
}

/// Runs `f` on a rayon pool of `threads` threads.
pub(crate) fn with_threads<R: Send>(
    threads: usize,
    f: impl FnOnce() -> R + Send,
) -> anyhow::Result<R> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    Ok(pool.install(f))
}
