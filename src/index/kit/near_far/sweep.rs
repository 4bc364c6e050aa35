//! The SAH sweep over perfect-split candidates on the three axes, shared by the kd-tree (over
//! event lists kept sorted from the root down, Wald & Havran 2006) and the axis planes of the
//! general BSP (sorted per node).

use crate::geometry::Aabb;
use crate::index::kit::near_far::SahParams;
use std::cmp::Ordering;

/// SAH weights: cost of a primitive test, of a traversal step, and the fraction of the cost
/// saved by a split that leaves one child empty.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Weights {
    pub intersect: f32,
    pub traversal: f32,
    pub empty_bonus: f32,
}

impl From<&SahParams> for Weights {
    fn from(p: &SahParams) -> Weights {
        Weights {
            intersect: p.intersect,
            traversal: p.traversal,
            empty_bonus: p.empty_bonus,
        }
    }
}

/// Largest item number an [`Event`] holds.
pub(crate) const MAX_ITEM: u32 = (1 << 31) - 1;

/// A primitive in a node and conservative bounds of its part there (not grown by the builder's
/// padding).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ref {
    pub prim: u32,
    pub b: Aabb,
}

/// A bound of a reference projected on one axis: its position (the box face grown by the
/// builder's `pad`), the item it belongs to (a primitive id or a reference's index, at most
/// [`MAX_ITEM`]) and whether the reference starts or ends there.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Event {
    pub pos: f32,
    /// `item << 1 | start`.
    tag: u32,
}

impl Event {
    #[inline]
    pub fn start(pos: f32, item: u32) -> Event {
        debug_assert!(item <= MAX_ITEM);
        Event {
            pos,
            tag: (item << 1) | 1,
        }
    }

    #[inline]
    pub fn end(pos: f32, item: u32) -> Event {
        debug_assert!(item <= MAX_ITEM);
        Event {
            pos,
            tag: item << 1,
        }
    }

    #[inline]
    pub fn is_start(&self) -> bool {
        self.tag & 1 != 0
    }

    #[inline]
    pub fn item(&self) -> u32 {
        self.tag >> 1
    }

    /// The sweep order: by position, ends before starts at equal positions (a reference that
    /// ends at `s` is not above `s`; one that starts there is not below it). Planar references
    /// do not occur: the padded bounds of a primitive have `start < end` or are one point.
    #[inline]
    pub fn order(a: &Event, b: &Event) -> Ordering {
        a.pos.total_cmp(&b.pos).then((a.tag & 1).cmp(&(b.tag & 1)))
    }
}

/// The two events of each axis of a reference with conservative box `b`, grown by `pad`.
#[inline]
pub(crate) fn push_events(events: &mut [Vec<Event>; 3], b: &Aabb, pad: f32, item: u32) {
    for (axis, list) in events.iter_mut().enumerate() {
        list.push(Event::start(b.min[axis] - pad, item));
        list.push(Event::end(b.max[axis] + pad, item));
    }
}

/// The cheapest axis plane `(axis, position, cost)` strictly inside `cell` for `n` references
/// whose events on each axis are `events[axis]`, sorted by [`Event::order`]; `None` unless
/// cheaper than a leaf (`intersect * n`). Ties go to the lower axis, then the lower position.
///
/// A reference counts below a plane `s` when its start is before `s` and above when its end is
/// after `s`, the builders' classification. One linear sweep per axis.
pub(crate) fn best_split_sorted(
    events: &[Vec<Event>; 3],
    n: usize,
    cell: &Aabb,
    w: &Weights,
) -> Option<(usize, f32, f32)> {
    let area = cell.surface_area();
    if area <= 0.0 || !area.is_finite() {
        return None;
    }
    let mut best: Option<(usize, f32, f32)> = None;
    let mut best_cost = w.intersect * n as f32;
    for (axis, events) in events.iter().enumerate() {
        let Some(plane) = PlaneCost::new(cell, axis, area, w) else {
            continue;
        };
        // Sweep: below(s) = starts before s, above(s) = ends after s.
        let (mut n_below, mut n_above) = (0usize, n);
        let mut i = 0;
        while i < events.len() {
            let s = events[i].pos;
            let (mut starts, mut ends) = (0usize, 0usize);
            while i < events.len() && events[i].pos == s {
                if events[i].is_start() {
                    starts += 1;
                } else {
                    ends += 1;
                }
                i += 1;
            }
            n_above -= ends;
            if let Some(cost) = plane.cost(s, n_below, n_above)
                && cost < best_cost
            {
                best_cost = cost;
                best = Some((axis, s, cost));
            }
            n_below += starts;
        }
    }
    best
}

/// The SAH cost of the planes across one axis of a cell: `traversal + intersect * bonus *
/// (A(below) n_below + A(above) n_above) / A(cell)`, with `bonus = 1 - empty_bonus` when a side
/// is empty.
pub(crate) struct PlaneCost {
    lo: f32,
    hi: f32,
    /// Twice the area of a face across the axis, and twice the perimeter of such a face.
    cap: f32,
    side: f32,
    area: f32,
    w: Weights,
}

impl PlaneCost {
    /// The costs across `axis` of `cell` (surface area `area > 0`); `None` when the cell is flat
    /// on that axis.
    #[inline]
    pub fn new(cell: &Aabb, axis: usize, area: f32, w: &Weights) -> Option<PlaneCost> {
        let (lo, hi) = (cell.min[axis], cell.max[axis]);
        let e = cell.extent();
        let (e1, e2) = (e[(axis + 1) % 3], e[(axis + 2) % 3]);
        (hi > lo).then_some(PlaneCost {
            lo,
            hi,
            cap: 2.0 * e1 * e2,
            side: 2.0 * (e1 + e2),
            area,
            w: *w,
        })
    }

    /// The cost of the plane at `s` with `n_below` and `n_above` references on its sides;
    /// `None` unless `s` lies strictly inside the cell.
    #[inline]
    pub fn cost(&self, s: f32, n_below: usize, n_above: usize) -> Option<f32> {
        if !(s > self.lo && s < self.hi) {
            return None;
        }
        let a_below = self.cap + (s - self.lo) * self.side;
        let a_above = self.cap + (self.hi - s) * self.side;
        let bonus = if n_below == 0 || n_above == 0 {
            1.0 - self.w.empty_bonus
        } else {
            1.0
        };
        Some(
            self.w.traversal
                + self.w.intersect * bonus * (a_below * n_below as f32 + a_above * n_above as f32)
                    / self.area,
        )
    }
}

/// [`best_split_sorted`] for `n` references with conservative boxes `bounds(i)` (grown by
/// `pad`), sorting their events first: `O(n log n)` per node. `events` is scratch space.
pub(crate) fn best_axis_split(
    n: usize,
    bounds: impl Fn(usize) -> Aabb,
    cell: &Aabb,
    pad: f32,
    w: &Weights,
    events: &mut [Vec<Event>; 3],
) -> Option<(usize, f32, f32)> {
    events.iter_mut().for_each(Vec::clear);
    for i in 0..n {
        push_events(events, &bounds(i), pad, i as u32);
    }
    for list in events.iter_mut() {
        list.sort_unstable_by(Event::order);
    }
    best_split_sorted(events, n, cell, w)
}
