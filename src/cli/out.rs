//! Standard output for the subcommands, where a write error (a full disk, `> /dev/full`) is an
//! error of the command rather than a panic. `cli/mod.rs` shadows `println!` and `print!` for
//! every subcommand with macros that write through [`write_stdout`] and return its error with
//! `?`, so a subcommand's output lines look like std's and still end it on a failed write;
//! [`flush_stdout`] catches what is left in the buffer when the command ends.
//! [`refuse_overwriting`] keeps an output file from replacing the command's own input.

use anyhow::Context;
use std::io::Write;
use std::path::Path;

/// Writes `args` to stdout (line-buffered: a line's write error shows at its newline).
pub fn write_stdout(args: std::fmt::Arguments) -> anyhow::Result<()> {
    std::io::stdout()
        .write_fmt(args)
        .context("writing to standard output")
}

/// Flushes stdout: the last, unterminated piece of output is written only here.
pub fn flush_stdout() -> anyhow::Result<()> {
    std::io::stdout()
        .flush()
        .context("writing to standard output")
}

/// Fails when `output` (given as `flag`) names the same existing file as `input`, which writing
/// it would destroy before, or while, it is read.
pub fn refuse_overwriting(input: &Path, output: &Path, flag: &str) -> anyhow::Result<()> {
    let same = match (input.canonicalize(), output.canonicalize()) {
        (Ok(i), Ok(o)) => i == o,
        _ => false,
    };
    anyhow::ensure!(
        !same,
        "{flag} {} is the input file {}: writing it would overwrite the input; give another path",
        output.display(),
        input.display()
    );
    Ok(())
}
