//! A chunk of rays walked several at a time, one step of each in turn ([`super::walk`]'s
//! paused walks): neighbouring rays in lockstep pairs ([`closest_hits_lockstep`]) or three walks
//! each moving on to the next ray as its ray finishes ([`closest_hits_interleaved`]). The same
//! walks and hits, with one ray's memory waits and dependency chains overlapped by the others'
//! work; [`coherent`] tells which suits a chunk.

use super::tree::BoxTree;
use super::walk::{ClosestWalk, closest_hit, enters_root};
use crate::geometry::{Hit, Ray};
use crate::index::Stats;
use crate::index::kit::stack::Stack;
use crate::scene::Geometry;

/// Whether the chunk's rays look like camera rays: the directions of its first, last and three
/// evenly spaced rays between lie within about 25 degrees of the first's (cosine above 0.9; no
/// square root, so the check costs a few operations per chunk). Camera rays (a segment of an
/// image row) walk nearly the same nodes, and neighbours take nearly the same branches: walked
/// in lockstep pairs ([`closest_hits_lockstep`]) the two walks stay in phase and the processor
/// predicts one's branches from the other's. Refilled slots ([`closest_hits_interleaved`])
/// drift out of phase and mix the two histories (on the bunny's primary rays Callgrind's branch
/// model counts 2.8 times the mispredictions, and the rays ran 9% to 18% slower).
pub fn coherent(rays: &[Ray]) -> bool {
    let Some(first) = rays.first() else {
        return true;
    };
    let d0 = first.dir;
    let n = rays.len() - 1;
    [n / 4, n / 2, 3 * n / 4, n].iter().all(|&i| {
        let d = rays[i].dir;
        let dot = d.dot(d0);
        dot > 0.0 && dot * dot > 0.81 * d.length_squared() * d0.length_squared()
    })
}

/// Closest hits of `rays` in lockstep pairs: rays `2k` and `2k + 1` start together and take one
/// step each in turn until one is done, then the other finishes alone; a pair is not refilled,
/// so two neighbouring camera rays stay in phase (see [`coherent`]). Each walk is
/// [`closest_hit`]'s own, so every hit is the same. A pair with a ray that needs the safe slab
/// variant, and an odd last ray, are traced by [`closest_hit`].
#[inline(always)]
pub fn closest_hits_lockstep<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [Option<Hit>],
    stats: &mut [S],
) {
    let Some(first) = rays.first() else {
        return;
    };
    let root = tree.top().root;
    let (mut stack_a, mut stack_b) = (Stack::new(), Stack::new());
    let mut a = ClosestWalk::<N>::new(root, first, &mut stack_a);
    let mut b = ClosestWalk::<N>::new(root, first, &mut stack_b);
    let pairs = rays.len() / 2;
    for p in 0..pairs {
        let i = 2 * p;
        let (ra, rb) = (&rays[i], &rays[i + 1]);
        let [sa, sb] = &mut stats[i..i + 2] else {
            unreachable!("a pair's counters");
        };
        if !(ra.fast_slabs() && rb.fast_slabs()) {
            out[i] = closest_hit(tree, geom, ra, sa);
            out[i + 1] = closest_hit(tree, geom, rb, sb);
            continue;
        }
        let mut a_live = enters_root(tree, ra, sa);
        let mut b_live = enters_root(tree, rb, sb);
        a.restart(root, ra);
        b.restart(root, rb);
        while a_live && b_live {
            a_live = a.step::<false, T, G, S>(tree, geom, sa);
            b_live = b.step::<false, T, G, S>(tree, geom, sb);
        }
        while a_live {
            a_live = a.step::<false, T, G, S>(tree, geom, sa);
        }
        while b_live {
            b_live = b.step::<false, T, G, S>(tree, geom, sb);
        }
        out[i] = a.answer();
        out[i + 1] = b.answer();
    }
    if rays.len() % 2 == 1 {
        let i = rays.len() - 1;
        out[i] = closest_hit(tree, geom, &rays[i], &mut stats[i]);
    }
}

/// The rays of a chunk handed out one by one to the walks of [`closest_hits_interleaved`].
struct Feed<'r> {
    rays: &'r [Ray],
    next: usize,
}

impl Feed<'_> {
    /// No ray left.
    const NONE: usize = usize::MAX;

    /// The index of the next ray that needs a walk of the fast slab variant, or [`Self::NONE`];
    /// the rays before it are answered at once: those of the safe variant by [`closest_hit`],
    /// those that miss the root box with no hit.
    #[inline(always)]
    fn start<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
        &mut self,
        tree: &T,
        geom: &G,
        out: &mut [Option<Hit>],
        stats: &mut [S],
    ) -> usize {
        while let Some(ray) = self.rays.get(self.next) {
            let i = self.next;
            self.next += 1;
            if !ray.fast_slabs() {
                out[i] = closest_hit(tree, geom, ray, &mut stats[i]);
            } else if enters_root(tree, ray, &mut stats[i]) {
                return i;
            } else {
                out[i] = None;
            }
        }
        Self::NONE
    }
}

impl<'r, const N: usize> ClosestWalk<'r, '_, N> {
    /// One step of the walk of ray `*id` of the feed; when that ray is done, its hit goes to
    /// `out` and the walk restarts with the feed's next ray (`*id` becomes [`Feed::NONE`] when
    /// there is none).
    #[inline(always)]
    fn advance<T: BoxTree<N>, G: Geometry, S: Stats>(
        &mut self,
        id: &mut usize,
        feed: &mut Feed<'r>,
        (tree, geom): (&T, &G),
        out: &mut [Option<Hit>],
        stats: &mut [S],
    ) {
        if !self.step::<false, T, G, S>(tree, geom, &mut stats[*id]) {
            out[*id] = self.answer();
            *id = feed.start(tree, geom, out, stats);
            if *id != Feed::NONE {
                self.restart(tree.top().root, &feed.rays[*id]);
            }
        }
    }
}

/// Closest hits of `rays`, three walks at a time, one step of each in turn, each walk moving on
/// to the chunk's next ray when its ray is done. Each walk is [`closest_hit`]'s own, on its
/// own stack, so every hit is the same; the steps of different rays are independent, so the
/// processor overlaps one ray's memory waits and dependency chains with the others' work.
/// Three walks, not two: +13% on the 1.31M icosphere's incoherent rays, whose nodes and
/// leaves miss the caches, and as fast on the bunny's.
#[inline(always)]
pub fn closest_hits_interleaved<const N: usize, T: BoxTree<N>, G: Geometry, S: Stats>(
    tree: &T,
    geom: &G,
    rays: &[Ray],
    out: &mut [Option<Hit>],
    stats: &mut [S],
) {
    let Some(last) = rays.last() else {
        return;
    };
    let root = tree.top().root;
    let mut feed = Feed { rays, next: 0 };
    let mut ids = [(); 3].map(|_| feed.start(tree, geom, out, stats));
    // A walk without a ray holds one of the last ray that is never stepped.
    let ray = |id: usize| rays.get(id).unwrap_or(last);
    let (mut sa, mut sb, mut sc) = (Stack::new(), Stack::new(), Stack::new());
    let mut a = ClosestWalk::<N>::new(root, ray(ids[0]), &mut sa);
    let mut b = ClosestWalk::<N>::new(root, ray(ids[1]), &mut sb);
    let mut c = ClosestWalk::<N>::new(root, ray(ids[2]), &mut sc);
    // Written out once per walk, not as a loop over an array of walks: each walk's branches get
    // their own sites in the code, and no loop counter runs between the steps.
    let [ia, ib, ic] = &mut ids;
    while *ia != Feed::NONE && *ib != Feed::NONE && *ic != Feed::NONE {
        a.advance(ia, &mut feed, (tree, geom), out, stats);
        b.advance(ib, &mut feed, (tree, geom), out, stats);
        c.advance(ic, &mut feed, (tree, geom), out, stats);
    }
    // No ray is left to start: the walks still under way finish one after the other.
    for (walk, i) in [(&mut a, *ia), (&mut b, *ib), (&mut c, *ic)] {
        if i != Feed::NONE {
            while walk.step::<false, T, G, S>(tree, geom, &mut stats[i]) {}
            out[i] = walk.answer();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;
    use glam::{Vec3, Vec3A};

    fn rays(dirs: impl IntoIterator<Item = Vec3>) -> Vec<Ray> {
        dirs.into_iter()
            .map(|d| Ray::infinite(Vec3::ZERO, d).unwrap())
            .collect()
    }

    /// A segment of an image row spanning 20 degrees (directions of any length) is coherent;
    /// one spanning 30 degrees, one with its last direction reversed, or scattered directions
    /// are not.
    #[test]
    fn camera_rows_are_coherent_and_scattered_directions_are_not() {
        let row = |spread_deg: f32, n: usize| {
            rays((0..n).map(|i| {
                let a = (i as f32 / (n - 1).max(1) as f32 * spread_deg).to_radians();
                Vec3::new(a.sin(), 0.0, -a.cos()) * (1.0 + i as f32)
            }))
        };
        assert!(coherent(&[]));
        assert!(coherent(&row(0.0, 1)));
        assert!(coherent(&row(20.0, 64)));
        assert!(!coherent(&row(30.0, 64)));
        let mut reversed = row(1.0, 64);
        reversed[63] = Ray::infinite(Vec3::ZERO, -Vec3::from(reversed[63].dir)).unwrap();
        assert!(!coherent(&reversed));
        let scattered = rays((0..64).map(|i| {
            let a = i as f32 * 2.4;
            Vec3::new(a.cos(), (i as f32 * 0.7).sin(), a.sin())
        }));
        assert!(!coherent(&scattered));
    }

    /// The protocol camera's rays, 160 to a row, in chunks of 63 (as `tests/it/wbvh.rs` traces
    /// them): those within one row pass the camera check (about 3 in 5), those that span two
    /// rows do not.
    #[test]
    fn protocol_camera_chunks_are_coherent() {
        let b = Aabb::new(Vec3A::splat(-1.0), Vec3A::splat(1.0));
        let rays = crate::rays::primary_rays(&b, 160, 160).unwrap();
        let chunks = rays.len().div_ceil(63);
        let camera = rays.chunks(63).filter(|c| coherent(c)).count();
        assert!(camera * 2 > chunks, "{camera} of {chunks}");
        assert!(camera < chunks, "{camera} of {chunks}");
    }
}
