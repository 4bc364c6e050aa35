//! `run --packets N` changes no hit: `bvh`, `bvh4` and `bvh8` trace packets of 4 and 8 neighbouring rays with
//! one shared traversal and an active mask, the other indices ray by ray; every ray gets
//! brute force's closest hit bit for bit and the same any-hit answer.

mod common;

use accelbench::index::TraceMode;

#[test]
fn packets_of_four_change_no_hit() {
    common::assert_mode_agrees(TraceMode::Packets(4));
}

#[test]
fn packets_of_eight_change_no_hit() {
    common::assert_mode_agrees(TraceMode::Packets(8));
}
