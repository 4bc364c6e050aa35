//! `accelbench verify`: only the suite's verification (no timing): every index against brute
//! force and against each other on every scene and ray set. Exits non-zero on any mismatch,
//! printing the rays' bits.

use super::run::progress_bar;
use super::suite_args::SuiteArgs;
use crate::harness::suite::{check_specs, run_suite};

#[derive(Debug, clap::Args)]
pub struct VerifyArgs {
    #[command(flatten)]
    suite: SuiteArgs,
}

pub fn run(a: VerifyArgs) -> anyhow::Result<()> {
    let cfg = a
        .suite
        .config(vec![rayon::current_num_threads()], 1, false)?;
    check_specs(&cfg.indices, cfg.kernel)?;
    let scenes = a.suite.load_scenes()?;
    a.suite.check_memory(&scenes, &cfg)?;
    let res = run_suite(&scenes, &cfg, &progress_bar(a.suite.quiet))?;
    for v in &res.verification {
        println!("{} / {}: {}", v.scene, v.what, v.reason);
    }
    for n in &res.notes {
        println!("{} / {}: {}", n.scene, n.what, n.reason);
    }
    for m in &res.mismatches {
        let peer = crate::index::is_peer(&m.index);
        eprintln!(
            "{} {} / {} / {} vs {}: {}",
            if peer {
                "peer mismatch (reported)"
            } else {
                "MISMATCH"
            },
            m.scene,
            m.index,
            m.ray_set.name(),
            m.against,
            m.mismatch
        );
    }
    let checked = res.rows.len();
    anyhow::ensure!(
        res.mismatch_total == 0,
        "verification failed: {} mismatching results (first ones above)",
        res.mismatch_total
    );
    anyhow::ensure!(
        res.failure_total == 0,
        "{} of our indices failed to build or trace (see above)",
        res.failure_total
    );
    println!(
        "verified: {checked} scene x index x ray set combinations, {} indices, no mismatch",
        cfg.indices.len()
    );
    Ok(())
}
