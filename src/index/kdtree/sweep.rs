//! The SAH sweep over perfect-split candidates on the three axes, shared by the kd-tree and the
//! axis planes of the general BSP.

use crate::geometry::Aabb;

/// SAH weights: cost of a primitive test, of a traversal step, and the fraction of the cost
/// saved by a split that leaves one child empty.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Weights {
    pub intersect: f32,
    pub traversal: f32,
    pub empty_bonus: f32,
}

/// A bound of a reference projected on one axis.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Event {
    pos: f32,
    start: bool,
}

/// The cheapest axis plane `(axis, position, cost)` strictly inside `cell` for `n` references
/// with conservative boxes `bounds(i)`, if cheaper than a leaf (`intersect * n`).
///
/// Candidates are the boxes' faces grown by `pad`; a reference counts below a plane `s` when
/// `min - pad < s` and above when `max + pad > s`, the builders' classification. One sort of
/// the events per axis, then one sweep: `O(n log n)` per node. `events` is scratch space.
pub(crate) fn best_axis_split(
    n: usize,
    bounds: impl Fn(usize) -> Aabb,
    cell: &Aabb,
    pad: f32,
    w: &Weights,
    events: &mut Vec<Event>,
) -> Option<(usize, f32, f32)> {
    let area = cell.surface_area();
    if area <= 0.0 || !area.is_finite() {
        return None;
    }
    let mut best: Option<(usize, f32, f32)> = None;
    let mut best_cost = w.intersect * n as f32;
    let e = cell.extent();
    for axis in 0..3 {
        let (lo, hi) = (cell.min[axis], cell.max[axis]);
        if hi <= lo {
            continue;
        }
        let (e1, e2) = (e[(axis + 1) % 3], e[(axis + 2) % 3]);
        events.clear();
        for i in 0..n {
            let b = bounds(i);
            events.push(Event {
                pos: b.min[axis] - pad,
                start: true,
            });
            events.push(Event {
                pos: b.max[axis] + pad,
                start: false,
            });
        }
        events.sort_unstable_by(|a, b| a.pos.total_cmp(&b.pos));
        // Sweep: below(s) = starts before s, above(s) = ends after s.
        let (mut n_below, mut n_above) = (0usize, n);
        let mut i = 0;
        while i < events.len() {
            let s = events[i].pos;
            let (mut starts, mut ends) = (0usize, 0usize);
            while i < events.len() && events[i].pos == s {
                if events[i].start {
                    starts += 1;
                } else {
                    ends += 1;
                }
                i += 1;
            }
            n_above -= ends;
            if s > lo && s < hi {
                let cap = e1 * e2;
                let side = e1 + e2;
                let a_below = 2.0 * (cap + (s - lo) * side);
                let a_above = 2.0 * (cap + (hi - s) * side);
                let bonus = if n_below == 0 || n_above == 0 {
                    1.0 - w.empty_bonus
                } else {
                    1.0
                };
                let cost = w.traversal
                    + w.intersect * bonus * (a_below * n_below as f32 + a_above * n_above as f32)
                        / area;
                if cost < best_cost {
                    best_cost = cost;
                    best = Some((axis, s, cost));
                }
            }
            n_below += starts;
        }
    }
    best
}
