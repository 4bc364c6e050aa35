//! A dated results page for `docs/results/` (`accelbench report DIR --markdown`): what one
//! report folder measured, headed by the machine, the command and the commit that produced it,
//! so that a page is regenerated from its folder instead of being written by hand.

use super::cost_fit::cost_fits;
use super::run_meta::RunMeta;
use super::run_notes::RunNotes;
use super::suite_report::scenes_markdown;
use super::verdict::{verdict_text, verdicts};
use crate::harness::median_interval::describe;
use crate::harness::suite::ResultRow;
use std::fmt::Write as _;

/// The page: a title line `# YYYY-MM-DD: TITLE` (the run's date), the run's facts, the verdict
/// and every scene's tables as in `summary.md`, without the pictures and charts (they stay in
/// the report folder). `title` defaults to the run's scenes.
pub fn results_page(
    meta: &RunMeta,
    rows: &[ResultRow],
    notes: &RunNotes,
    title: Option<&str>,
) -> String {
    let day = meta.date.get(..10).unwrap_or(&meta.date);
    let scenes = meta.scenes.join(", ");
    let mut s = String::new();
    let _ = writeln!(s, "# {day}: {}\n", title.unwrap_or(&scenes));
    let _ = writeln!(
        s,
        "- **Machine.** {} ({} cores), {}.",
        meta.cpu, meta.cores, meta.os
    );
    let _ = writeln!(s, "- **Command.** `{}`", meta.command);
    let _ = writeln!(
        s,
        "- **Commit.** `{}` (run {}, {}).",
        meta.git_revision, meta.run_id, meta.date
    );
    let _ = writeln!(
        s,
        "- **Timing.** Threads {:?}, kernel {}, median of {} timed repeats; {}.",
        meta.threads,
        meta.kernel,
        meta.repeats,
        describe(meta.repeats)
    );
    let verified = if notes.mismatch_total == 0 {
        "passed: every index of ours returned brute force's hits bit for bit".to_owned()
    } else {
        format!("FAILED, {} mismatching results", notes.mismatch_total)
    };
    let _ = writeln!(
        s,
        "- **Verification.** {verified}; peers' results differing from brute force: {}.\n",
        notes.peer_mismatch_total
    );
    let _ = writeln!(
        s,
        "## Verdict\n\n```text\n{}```\n",
        verdict_text(&verdicts(rows), 4)
    );
    s.push_str(&scenes_markdown(rows, notes, &cost_fits(rows)));
    s
}
