//! Classifying a peer's or GPU index's disagreements with a reference, as the suite does.

use accelbench::geometry::{Hit, Ray};
use accelbench::harness::peer_check::{PeerCounts, Verdict, classify};
use accelbench::harness::timing::Query;
use accelbench::harness::verify::compare_closest;
use accelbench::scene::Scene;

/// Classifies every ray where `got` differs from `expected` (`harness::peer_check`), printing
/// the wrong ones.
pub fn judge(
    what: &str,
    scene: &Scene,
    rays: &[Ray],
    expected: &[Option<Hit>],
    got: &[Option<Hit>],
) -> PeerCounts {
    let mut counts = PeerCounts::default();
    for m in compare_closest(rays, expected, got) {
        let v = classify(scene, &rays[m.ray_index], Query::Closest, m.expected, m.got);
        if v == Verdict::Wrong {
            eprintln!("{what}: wrong: {m}");
        }
        counts.add(v);
    }
    counts
}
