//! `run --last-hit` ("check last hit first") changes no hit: every index of ours, tracing in
//! image order with the previous ray's hit tested first, returns brute force's closest hits
//! bit for bit (ties and the kernel's clamp included) and the same any-hit answers.

use crate::common;

use accelbench::index::TraceMode;

#[test]
fn last_hit_first_changes_no_hit() {
    common::assert_mode_agrees(TraceMode::LastHit);
}
