//! Spatial splits (SBVH; Stich, Friedrich and Dietrich 2009, "Spatial Splits in Bounding Volume
//! Hierarchies"). A node whose best object split leaves overlapping children (the overlap's
//! surface area above [`ALPHA`] times the root's) also tries binned spatial splits: planes at
//! equal steps across the node's box on each axis, every reference chopped into the bins it
//! spans ([`Spatial::piece`] in each), scored by the object bins' SAH sweep
//! ([`super::binned::Sweep`]). When the SAH-cheapest spatial split beats the object split, or
//! else the plane that cuts the references' summed box area most cuts it enough ([`AREA_CUT`],
//! estimated from the same bins), the references crossing the plane go to both children as
//! their pieces, or whole to one side when the SAH prefers it (reference unsplitting). A
//! reference is a [`PrimRef`] whose box may be smaller than its
//! primitive's bounds; ids repeat across leaves, never within one leaf (the two pieces of a
//! reference go to different subtrees).
//!
//! Budget: at most `split_budget` references per primitive in the tree ([`budget`]); a node
//! takes the cheapest plane within its budget, and each child gets the extra references its
//! parent may still make in proportion to its reference count ([`share`]), so the tree depends
//! neither on the build order nor on the thread count.
//!
//! Binning estimates a triangle's piece in a bin from the triangle cut to the bin's slab
//! ([`slab_bounds`], within the reference's box); the pieces a split keeps are clipped.
//!
//! # Why the hits stay exact
//!
//! A reference's box is `(clip(p, cell) ± pad) ∩ R`: `clip` the conservative clipped bounds of
//! primitive `p` in `cell` ([`Clip`], `Geometry::clipped_bounds`), `cell` the part of the
//! parent reference's box `R` on its side of the plane, `pad` the scene padding
//! ([`scene_pad`], as for the kd-tree's perfect splits) on every side. At the root `R` is the
//! primitive's bounds, so every box lies inside them and inside its parent reference's (node
//! boxes still contain their children's).
//! - Cover: the two cells of a cut cover `R` and `clip` contains every point of `p` in its cell
//!   (a dropped piece has none), so the exact hit point `x*` lies in the unpadded clipped box of
//!   every reference on a chain from the root to some leaf reference `r`.
//! - Each face of `r`'s box is a face of the primitive's bounds or, by that chain, at least
//!   `pad` outside `x*`. `Geometry::intersect` clamps the kernel's `t` into the computed slab
//!   interval of the primitive's bounds, which on the shared faces is the same bits; on the
//!   other faces `t` is inside the computed slab value whenever the kernel's error on the hit
//!   point plus the slab arithmetic's rounding (`(plane - origin) * inv_dir`, about `2e-7` of
//!   `|plane - origin|`) stays below `pad`. So `t` lies in the computed interval of `r`'s box,
//!   hence (the slab test is monotone) of every ancestor's: the walk neither rejects these boxes
//!   nor culls them (entry `<= t <=` best `t`). No walk-side margin is needed.
//! - Limits, the kd-tree's: `pad` is `1e-5` of the scene's largest coordinate, so origins
//!   farther than about fifty times that, or kernels whose hit point is off by more than about
//!   `pad / 2` (e.g. grazing sphere hits), are outside the argument.

use super::binned::{AxisBins, SLOTS, Sweep};
use super::prim_ref::PrimRef;
use crate::geometry::{Aabb, Triangle};
use crate::index::kit::near_far::scene_pad;
use crate::scene::Geometry;
use glam::Vec3A;

/// Stich's α: a node tries spatial splits when its object split's children overlap in more
/// than this fraction of the root's surface area.
pub const ALPHA: f32 = 1.0e-5;

/// When no spatial split beats the object split by the SAH, the plane cutting the summed
/// surface area of the references' boxes most is still taken when it cuts it to below this
/// fraction: the greedy SAH charges each child as a leaf, which on long thin primitives (every
/// one crossing the node) favours object splits whose children never shrink, while the pieces'
/// boxes keep shrinking as they are cut further (what a ray pays once the children are
/// subdivided is about their references' areas).
pub const AREA_CUT: f32 = 0.9;

/// The extra references (beyond one per primitive) a tree over `n` primitives may make with at
/// most `per_prim` (at least 1) references per primitive.
pub fn budget(n: usize, per_prim: f32) -> usize {
    (n as f64 * (f64::from(per_prim) - 1.0)) as usize
}

/// `budget` extra references shared by two children of `nl` and `nr` references, in proportion.
pub fn share(budget: usize, nl: usize, nr: usize) -> [usize; 2] {
    let left = (budget as u128 * nl as u128 / (nl + nr).max(1) as u128) as usize;
    [left, budget - left]
}

/// Cutting a primitive to a box, for every geometry.
pub trait Clip: Sync {
    /// Bounds of the part of primitive `id` in the closed box `cell`: they contain every point
    /// of the primitive in `cell` and lie inside its bounds; empty only when there is none.
    fn clip(&self, id: u32, cell: &Aabb) -> Aabb;
    /// The primitive's triangle on triangle-only geometries (for the binning estimate).
    fn triangle(&self, id: u32) -> Option<Triangle>;
}

impl<G: Geometry> Clip for G {
    fn triangle(&self, id: u32) -> Option<Triangle> {
        self.block_triangle(id)
    }

    fn clip(&self, id: u32, cell: &Aabb) -> Aabb {
        let b = self.clipped_bounds(id, cell);
        // Should the clipper's rounding lose a sliver that the conservative overlap test still
        // sees, keep the box overlap.
        if b.is_empty() && self.overlaps_box(id, cell) {
            self.bounds(id).intersection(*cell)
        } else {
            b
        }
    }
}

/// The bins of one node on the three axes (the first `bins` slots of each), and the sweep.
pub struct Scratch {
    min: Box<[[Vec3A; SLOTS]; 3]>,
    max: Box<[[Vec3A; SLOTS]; 3]>,
    enter: [[u32; SLOTS]; 3],
    exit: [[u32; SLOTS]; 3],
    /// Per axis, `grow[k]`: the estimated change of the references' summed box area when the
    /// references crossing plane `k` are cut there (the planes' [`AREA_CUT`] test).
    grow: Box<[[f64; SLOTS]; 3]>,
    /// One reference's estimated pieces in the bins it spans, first bin first.
    pieces: Box<[Aabb; SLOTS]>,
    sweep: Sweep,
}

impl Default for Scratch {
    fn default() -> Scratch {
        Scratch {
            min: Box::new([[Vec3A::INFINITY; SLOTS]; 3]),
            max: Box::new([[Vec3A::NEG_INFINITY; SLOTS]; 3]),
            enter: [[0; SLOTS]; 3],
            exit: [[0; SLOTS]; 3],
            grow: Box::new([[0.0; SLOTS]; 3]),
            pieces: Box::new([Aabb::EMPTY; SLOTS]),
            sweep: Sweep::default(),
        }
    }
}

/// Equal bins across `lo..lo + bins * width` on one axis (`scale = 1 / width`).
#[derive(Debug, Clone, Copy)]
struct Axis {
    axis: usize,
    lo: f32,
    width: f32,
    scale: f32,
    bins: usize,
}

impl Axis {
    /// `bins` equal bins across `bounds` on `axis`; `None` when it has no extent there.
    fn new(bounds: &Aabb, axis: usize, bins: usize) -> Option<Axis> {
        let width = bounds.extent()[axis] / bins as f32;
        let scale = 1.0 / width;
        (scale.is_finite() && width > 0.0).then_some(Axis {
            axis,
            lo: bounds.min[axis],
            width,
            scale,
            bins,
        })
    }

    /// The bin of coordinate `x` (clamped into the bins).
    fn bin(&self, x: f32) -> usize {
        (((x - self.lo) * self.scale).max(0.0) as usize).min(self.bins - 1)
    }

    /// The plane between bins `k - 1` and `k`.
    fn plane(&self, k: usize) -> f32 {
        self.lo + k as f32 * self.width
    }

    /// The first and last bins of `r`'s box.
    fn span(&self, r: &PrimRef) -> (usize, usize) {
        (self.bin(r.min()[self.axis]), self.bin(r.max()[self.axis]))
    }

    /// `b` cut to `lo..=hi` on this axis.
    fn slab(&self, b: Aabb, lo: f32, hi: f32) -> Aabb {
        let (mut min, mut max) = (b.min, b.max);
        min[self.axis] = min[self.axis].max(lo);
        max[self.axis] = max[self.axis].min(hi);
        Aabb::new(min, max)
    }
}

/// A spatial split plane: between bins `plane - 1` and `plane` of `on`, with the binned
/// estimate of the children's boxes and reference counts (both counts > 0).
#[derive(Debug, Clone, Copy)]
struct Candidate {
    on: Axis,
    plane: usize,
    boxes: [Aabb; 2],
    counts: [u32; 2],
}

/// The spatial splits [`Spatial::find`] proposes for one node, among the planes within its
/// reference budget: the cheapest by the SAH, and the one whose cut leaves the smallest summed
/// surface area of the references' boxes (binned estimate: `area[0]` before, `area[1]` after).
#[derive(Debug, Clone, Copy)]
pub struct Found {
    /// The SAH cost of `sah`, `area(left) * n_left + area(right) * n_right`.
    pub cost: f32,
    sah: Candidate,
    by_area: Candidate,
    area: [f64; 2],
}

/// Spatial splits of one build: the geometry's clipping, the padding, the overlap threshold.
pub struct Spatial<'a> {
    clip: &'a dyn Clip,
    pad: Vec3A,
    min_overlap: f32,
    /// The SAH's count rounding ([`super::params::BuildConfig::sah_block`]).
    block: u32,
}

/// The references of one child of a spatial split with their bounds and centroid bounds.
pub type Side = (Vec<PrimRef>, (Aabb, Aabb));

impl<'a> Spatial<'a> {
    /// Spatial splits over primitives clipped by `clip`, whose bounds' union is `root`, scored
    /// with the SAH's counts rounded up to multiples of `block`.
    pub fn new(clip: &'a dyn Clip, root: &Aabb, block: u32) -> Spatial<'a> {
        Spatial {
            clip,
            pad: Vec3A::splat(scene_pad(root)),
            min_overlap: ALPHA * root.surface_area(),
            block,
        }
    }

    /// Whether a node whose object split gives children boxes `a` and `b` tries spatial splits.
    pub fn worth_trying(&self, a: &Aabb, b: &Aabb) -> bool {
        a.intersection(*b).surface_area() > self.min_overlap
    }

    /// The box of `r`'s piece in `cell` (inside `r`'s box): its clipped bounds grown by the
    /// padding on every side, cut to `r`'s box; empty when the primitive has no point there.
    fn piece(&self, r: &PrimRef, cell: &Aabb) -> Aabb {
        let c = self.clip.clip(r.id(), cell);
        if c.is_empty() {
            return Aabb::EMPTY;
        }
        Aabb::new(c.min - self.pad, c.max + self.pad).intersection(r.bounds())
    }

    /// The binned spatial splits of `refs` (whose bounds' union is `bounds`) with `bins` bins
    /// per axis, among those making at most `budget` extra references: the SAH-cheapest and the
    /// one cutting the references' summed box area most. `None` when no plane qualifies.
    pub fn find(
        &self,
        refs: &[PrimRef],
        bounds: &Aabb,
        bins: u32,
        budget: usize,
        s: &mut Scratch,
    ) -> Option<Found> {
        let bins = (bins as usize).clamp(2, SLOTS);
        let max_refs = u32::try_from(refs.len().saturating_add(budget)).unwrap_or(u32::MAX);
        let area = |b: &Aabb| f64::from(b.surface_area());
        let total: f64 = refs.iter().map(|r| area(&r.bounds())).sum();
        let mut best = None;
        // (growth of the summed area, axis, plane, counts) of the plane cutting it most
        let mut cut: Option<(f64, usize, usize, [u32; 2])> = None;
        for on in (0..3).filter_map(|axis| Axis::new(bounds, axis, bins)) {
            let a = on.axis;
            let (min, max) = (&mut s.min[a][..bins], &mut s.max[a][..bins]);
            let (enter, exit) = (&mut s.enter[a][..bins], &mut s.exit[a][..bins]);
            let grow = &mut s.grow[a][..bins];
            min.fill(Vec3A::INFINITY);
            max.fill(Vec3A::NEG_INFINITY);
            enter.fill(0);
            exit.fill(0);
            grow.fill(0.0);
            for r in refs {
                let (first, last) = on.span(r);
                enter[first] += 1;
                exit[last] += 1;
                if first == last {
                    min[first] = min[first].min(r.min());
                    max[first] = max[first].max(r.max());
                    continue;
                }
                let (b, tri) = (r.bounds(), self.clip.triangle(r.id()));
                let pieces = &mut s.pieces[..=last - first];
                for (k, piece) in (first..=last).zip(pieces.iter_mut()) {
                    let cell = on.slab(b, on.plane(k), on.plane(k + 1));
                    *piece = match &tri {
                        Some(t) => slab_bounds(t, a, cell.min[a], cell.max[a]).intersection(cell),
                        None => self.piece(r, &cell),
                    };
                    min[k] = min[k].min(piece.min);
                    max[k] = max[k].max(piece.max);
                }
                // Cut at plane `k` (first < k <= last), `r` becomes the union of its pieces
                // below `k` and the union of those from `k` up.
                let whole = area(&b);
                let mut side = Aabb::EMPTY;
                for (k, piece) in (first + 1..=last).zip(pieces.iter()) {
                    side = side.union(*piece);
                    grow[k] += area(&side) - whole;
                }
                side = Aabb::EMPTY;
                for (k, piece) in (first + 1..=last).rev().zip(pieces.iter().rev()) {
                    side = side.union(*piece);
                    grow[k] += area(&side);
                }
            }
            let view = AxisBins {
                min,
                max,
                enter,
                exit,
                block: self.block,
            };
            s.sweep.axis(a, &view, max_refs, &mut best);
            // The sweep's admissible planes: both sides non-empty, within the budget.
            let (mut nl, mut nr) = (0u32, refs.len() as u32);
            for k in 1..bins {
                nl += enter[k - 1];
                nr -= exit[k - 1];
                if nl > 0
                    && nr > 0
                    && nl.saturating_add(nr) <= max_refs
                    && cut.is_none_or(|(g, ..)| grow[k] < g)
                {
                    cut = Some((grow[k], a, k, [nl, nr]));
                }
            }
        }
        let p = best?;
        let (grow, axis, plane, counts) = cut?;
        let (lo, hi) = (&s.min[axis][..bins], &s.max[axis][..bins]);
        let side = |r: std::ops::Range<usize>| {
            r.fold(Aabb::EMPTY, |b, k| b.union(Aabb::new(lo[k], hi[k])))
        };
        Some(Found {
            cost: p.cost,
            sah: Candidate {
                on: Axis::new(bounds, p.axis, bins)?,
                plane: p.plane,
                boxes: [p.left, p.right],
                counts: p.counts,
            },
            by_area: Candidate {
                on: Axis::new(bounds, axis, bins)?,
                plane,
                boxes: [side(0..plane), side(plane..bins)],
                counts,
            },
            area: [total, total + grow],
        })
    }

    /// Splits `refs` into the children's references ([`Spatial::cut`]) at `f`'s SAH plane
    /// when its SAH `f.cost` is below `object`'s (the node's best object split; `None` when
    /// there is none), or else at its area-cutting plane when that leaves at most
    /// [`AREA_CUT`] times the references' summed box area. `None` when neither is worth it,
    /// or when a side would be empty.
    pub fn apply(&self, refs: &[PrimRef], f: &Found, object: Option<f32>) -> Option<[Side; 2]> {
        let c = match object {
            Some(o) if f.cost >= o => {
                let [before, after] = f.area;
                if after >= f64::from(AREA_CUT) * before {
                    return None;
                }
                &f.by_area
            }
            _ => &f.sah,
        };
        let mut sides: [Side; 2] =
            std::array::from_fn(|_| (Vec::new(), (Aabb::EMPTY, Aabb::EMPTY)));
        self.cut(refs, c, |side, r| {
            let (refs, (b, cb)) = &mut sides[side];
            *b = b.union(r.bounds());
            *cb = cb.grown(r.centroid());
            refs.push(r);
        });
        let [left, right] = sides;
        (!left.0.is_empty() && !right.0.is_empty()).then_some([left, right])
    }

    /// Hands `emit` each child reference of a split of `refs` at `c`'s plane with its side (0
    /// left, 1 right), in `refs` order: references in bins below the plane go left, from it up
    /// right, the others as their pieces on both sides (an empty piece dropped), or whole on one
    /// side when that is cheaper by the SAH against the estimated children (Stich's
    /// unsplitting).
    fn cut(&self, refs: &[PrimRef], c: &Candidate, mut emit: impl FnMut(usize, PrimRef)) {
        let on = c.on;
        let at = on.plane(c.plane);
        let [la, ra] = c.boxes.map(|b| b.surface_area());
        let [nl, nr] = c.counts.map(|n| n as f32);
        let split_cost = la * nl + ra * nr;
        for r in refs {
            let (first, last) = on.span(r);
            if last < c.plane || first >= c.plane {
                emit(usize::from(first >= c.plane), *r);
                continue;
            }
            let b = r.bounds();
            let whole_left = c.boxes[0].union(b).surface_area() * nl + ra * (nr - 1.0);
            let whole_right = la * (nl - 1.0) + c.boxes[1].union(b).surface_area() * nr;
            if whole_left < split_cost.min(whole_right) {
                emit(0, *r);
            } else if whole_right < split_cost {
                emit(1, *r);
            } else {
                let cells = [
                    on.slab(b, f32::NEG_INFINITY, at),
                    on.slab(b, at, f32::INFINITY),
                ];
                for (side, cell) in cells.iter().enumerate() {
                    let piece = self.piece(r, cell);
                    if !piece.is_empty() {
                        emit(side, PrimRef::new(piece, r.id()));
                    }
                }
            }
        }
    }
}

/// Bounds of the part of `t` with `lo <= p[axis] <= hi`: its corners there and its edges'
/// crossings of both planes (empty when there is none). Rounded, not conservative: an
/// estimate for binning only.
fn slab_bounds(t: &Triangle, axis: usize, lo: f32, hi: f32) -> Aabb {
    let mut b = Aabb::EMPTY;
    for i in 0..3 {
        let (p, q) = (t.v[i], t.v[(i + 1) % 3]);
        if (lo..=hi).contains(&p[axis]) {
            b = b.grown(p);
        }
        for plane in [lo, hi] {
            let (dp, dq) = (p[axis] - plane, q[axis] - plane);
            if (dp < 0.0) != (dq < 0.0) {
                b = b.grown(p + (q - p) * (dp / (dp - dq)));
            }
        }
    }
    b
}

#[cfg(test)]
#[path = "spatial_tests.rs"]
mod tests;
