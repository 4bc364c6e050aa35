//! Thread counts for the subcommands: the `--threads` parser and the pool a command runs on.

/// Parses a `--threads` value: a positive count. A count above the machine's cores is taken,
/// with a note on stderr (the threads then share cores, and timings measure that).
pub(crate) fn parse_threads(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if (1..=4096).contains(&n) => {
            let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
            if n > cores {
                eprintln!(
                    "note: --threads {n} is more than the {cores} cores here: threads will share \
                     cores, and timings at {n} threads measure that"
                );
            }
            Ok(n)
        }
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
