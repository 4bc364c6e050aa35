//! Convex polyhedra cut by planes, for the exact cell surface areas of the general BSP's cost
//! (Ize, Wald & Parker 2008).
//!
//! Computed in `f64` from the `f32` planes the tree stores. Used for cost estimates only: the
//! areas carry rounding error, and a cut that rounding makes degenerate gives an empty part.

use super::Aabb;
use glam::{DVec3, Vec3A};

/// A convex polyhedron as its faces: convex polygons whose vertices run counter-clockwise seen
/// from outside. Empty (no faces) when a cut left nothing of positive volume.
#[derive(Debug, Clone, Default)]
pub struct ConvexPolyhedron {
    faces: Vec<Vec<DVec3>>,
}

/// Twice the vector area of a polygon (`sum v_i x v_{i+1}`): its direction is the normal seen
/// counter-clockwise, its length twice the area.
fn vector_area2(poly: &[DVec3]) -> DVec3 {
    let Some(&o) = poly.first() else {
        return DVec3::ZERO;
    };
    poly.windows(2)
        .skip(1)
        .map(|w| (w[0] - o).cross(w[1] - o))
        .sum()
}

/// Splits a convex polygon by the signed distances `dist` of its vertices (`<= 0`: below,
/// `>= 0`: above), appending the parts to `below` and `above` (vertices on the plane go to
/// both) and the points where its boundary meets the plane to `on_plane`.
fn split_polygon(
    poly: &[DVec3],
    dist: &[f64],
    below: &mut Vec<DVec3>,
    above: &mut Vec<DVec3>,
    on_plane: &mut Vec<DVec3>,
) {
    for i in 0..poly.len() {
        let j = (i + 1) % poly.len();
        let (a, da, db) = (poly[i], dist[i], dist[j]);
        if da <= 0.0 {
            below.push(a);
        }
        if da >= 0.0 {
            above.push(a);
        }
        if da == 0.0 {
            on_plane.push(a);
        } else if (da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0) {
            // From the vertex below, so the face on the other side of the edge gets the same
            // bits.
            let (lo, hi, dl, dh) = if da < 0.0 {
                (a, poly[j], da, db)
            } else {
                (poly[j], a, db, da)
            };
            let p = lo + (hi - lo) * (dl / (dl - dh));
            below.push(p);
            above.push(p);
            on_plane.push(p);
        }
    }
}

impl ConvexPolyhedron {
    /// The six faces of a box (empty when the box is empty).
    pub fn from_box(b: &Aabb) -> ConvexPolyhedron {
        if b.is_empty() {
            return ConvexPolyhedron::default();
        }
        let (lo, hi) = (b.min.as_dvec3(), b.max.as_dvec3());
        let c = |x: bool, y: bool, z: bool| {
            DVec3::new(
                if x { hi.x } else { lo.x },
                if y { hi.y } else { lo.y },
                if z { hi.z } else { lo.z },
            )
        };
        let (f, t) = (false, true);
        let faces = vec![
            vec![c(f, f, f), c(f, f, t), c(f, t, t), c(f, t, f)], // -x
            vec![c(t, f, f), c(t, t, f), c(t, t, t), c(t, f, t)], // +x
            vec![c(f, f, f), c(t, f, f), c(t, f, t), c(f, f, t)], // -y
            vec![c(f, t, f), c(f, t, t), c(t, t, t), c(t, t, f)], // +y
            vec![c(f, f, f), c(f, t, f), c(t, t, f), c(t, f, f)], // -z
            vec![c(f, f, t), c(t, f, t), c(t, t, t), c(f, t, t)], // +z
        ];
        ConvexPolyhedron { faces }
    }

    /// `true` when nothing is left.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// Surface area.
    pub fn area(&self) -> f64 {
        self.faces
            .iter()
            .map(|f| vector_area2(f).length())
            .sum::<f64>()
            * 0.5
    }

    /// Bounds of the vertices, rounded outward to `f32` (empty when the polyhedron is).
    pub fn bounds(&self) -> Aabb {
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        for v in self.faces.iter().flatten() {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let down = |x: f64| {
            let f = x as f32;
            if f as f64 > x { f.next_down() } else { f }
        };
        let up = |x: f64| {
            let f = x as f32;
            if (f as f64) < x { f.next_up() } else { f }
        };
        Aabb::new(
            Vec3A::new(down(lo.x), down(lo.y), down(lo.z)),
            Vec3A::new(up(hi.x), up(hi.y), up(hi.z)),
        )
    }

    /// Surface areas of the parts where `normal . p <= offset` (below) and `>= offset` (above),
    /// without building them. The cut face's area is the length of the sum of the other faces'
    /// vector areas (a closed surface's vector areas sum to zero).
    pub fn split_areas(&self, normal: Vec3A, offset: f32) -> (f64, f64) {
        let (mut area_b, mut area_a) = (0.0, 0.0);
        let (mut sum_b, mut sum_a) = (DVec3::ZERO, DVec3::ZERO);
        let cut = self.cut_faces(normal.as_dvec3(), offset as f64, |below, above| {
            let (vb, va) = (vector_area2(below), vector_area2(above));
            area_b += vb.length();
            area_a += va.length();
            sum_b += vb;
            sum_a += va;
        });
        let (any_b, any_a) = (cut.any_below, cut.any_above);
        // A part with no vertex strictly on its side has no volume; the other part is all.
        if !any_a {
            return (self.area(), 0.0);
        }
        if !any_b {
            return (0.0, self.area());
        }
        (
            0.5 * (area_b + sum_b.length()),
            0.5 * (area_a + sum_a.length()),
        )
    }

    /// Cuts each face by the plane `n . p = d` ([`split_polygon`]) and hands its parts below and
    /// above to `parts` (buffers reused from face to face: take what you keep).
    fn cut_faces(
        &self,
        n: DVec3,
        d: f64,
        mut parts: impl FnMut(&mut Vec<DVec3>, &mut Vec<DVec3>),
    ) -> Cut {
        let (mut below, mut above, mut dist) = (Vec::new(), Vec::new(), Vec::new());
        let mut cut = Cut {
            any_below: false,
            any_above: false,
            on_plane: Vec::new(),
        };
        for f in &self.faces {
            dist.clear();
            dist.extend(f.iter().map(|p| n.dot(*p) - d));
            cut.any_below |= dist.iter().any(|&x| x < 0.0);
            cut.any_above |= dist.iter().any(|&x| x > 0.0);
            below.clear();
            above.clear();
            split_polygon(f, &dist, &mut below, &mut above, &mut cut.on_plane);
            parts(&mut below, &mut above);
        }
        cut
    }

    /// The parts where `normal . p <= offset` (below) and `>= offset` (above), each closed by
    /// the cut face; a part the plane leaves no volume to is empty.
    pub fn split(&self, normal: Vec3A, offset: f32) -> (ConvexPolyhedron, ConvexPolyhedron) {
        let n = normal.as_dvec3();
        let (mut below, mut above) = (Vec::new(), Vec::new());
        let cut = self.cut_faces(n, offset as f64, |b, a| {
            if vector_area2(b) != DVec3::ZERO {
                below.push(std::mem::take(b));
            }
            if vector_area2(a) != DVec3::ZERO {
                above.push(std::mem::take(a));
            }
        });
        let (any_b, any_a) = (cut.any_below, cut.any_above);
        let cap = cut_face(&cut.on_plane, n);
        // A part with no vertex strictly on its side has no volume; the other part is all.
        if !any_a {
            return (self.clone(), ConvexPolyhedron::default());
        }
        if !any_b {
            return (ConvexPolyhedron::default(), self.clone());
        }
        let close = |mut faces: Vec<Vec<DVec3>>, cap: Option<Vec<DVec3>>| {
            faces.extend(cap);
            ConvexPolyhedron { faces }
        };
        let cap_above = cap.as_ref().map(|c| c.iter().rev().copied().collect());
        (close(below, cap), close(above, cap_above))
    }
}

/// What cutting every face of a polyhedron by a plane leaves besides the parts.
struct Cut {
    /// Some vertex lies strictly below the plane, some strictly above.
    any_below: bool,
    any_above: bool,
    /// The points where the faces' boundaries meet the plane (the cut face's corners, repeated).
    on_plane: Vec<DVec3>,
}

/// The cut face through the points `on` of the plane with unit normal `n`, counter-clockwise
/// seen from `+n` (the outside of the part below); `None` when they span no area.
fn cut_face(on: &[DVec3], n: DVec3) -> Option<Vec<DVec3>> {
    if on.len() < 3 {
        return None;
    }
    let c = on.iter().sum::<DVec3>() / on.len() as f64;
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let mut pts: Vec<(f64, DVec3)> = on
        .iter()
        .map(|p| {
            let q = *p - c;
            (q.dot(v).atan2(q.dot(u)), *p)
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Vertices on the plane come once per face that holds them.
    pts.dedup_by(|a, b| a.1 == b.1);
    if pts.len() > 1 && pts[0].1 == pts[pts.len() - 1].1 {
        pts.pop();
    }
    let face: Vec<DVec3> = pts.into_iter().map(|(_, p)| p).collect();
    (vector_area2(&face) != DVec3::ZERO).then_some(face)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> ConvexPolyhedron {
        ConvexPolyhedron::from_box(&Aabb::new(Vec3A::ZERO, Vec3A::ONE))
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn box_faces_face_outward() {
        let p = unit();
        assert!(close(p.area(), 6.0));
        for f in &p.faces {
            let c = f.iter().sum::<DVec3>() / 4.0 - DVec3::splat(0.5);
            assert!(vector_area2(f).dot(c) > 0.0, "{f:?}");
        }
    }

    #[test]
    fn axis_cut_matches_the_box_formula() {
        let (b, a) = unit().split_areas(Vec3A::X, 0.25);
        assert!(close(b, 2.0 * (1.0 + 0.25 * 2.0)), "{b}");
        assert!(close(a, 2.0 * (1.0 + 0.75 * 2.0)), "{a}");
        let (pb, pa) = unit().split(Vec3A::X, 0.25);
        assert!(close(pb.area(), b) && close(pa.area(), a));
        assert_eq!(
            pb.bounds(),
            Aabb::new(Vec3A::ZERO, Vec3A::new(0.25, 1.0, 1.0))
        );
    }

    #[test]
    fn diagonal_cut_gives_two_prisms() {
        // x + y <= 1 halves the cube into two triangular prisms: two right triangles of area
        // 1/2, two unit squares and the diagonal rectangle sqrt(2) x 1.
        let n = Vec3A::new(1.0, 1.0, 0.0).normalize();
        let want = 1.0 + 2.0 + 2f64.sqrt();
        let (b, a) = unit().split_areas(n, n.dot(Vec3A::new(0.5, 0.5, 0.0)));
        assert!(
            (b - want).abs() < 1e-6 && (a - want).abs() < 1e-6,
            "{b} {a}"
        );
        let (pb, pa) = unit().split(n, n.dot(Vec3A::new(0.5, 0.5, 0.0)));
        assert!((pb.area() - want).abs() < 1e-6 && (pa.area() - want).abs() < 1e-6);
        // A corner cut off the prism: areas still add up around a second cut.
        let (qb, qa) = pb.split(Vec3A::Z, 0.5);
        let (sb, sa) = pb.split_areas(Vec3A::Z, 0.5);
        assert!(close(qb.area(), sb) && close(qa.area(), sa));
        assert!(close(qb.area() + qa.area(), pb.area() + 2.0 * 0.5));
    }

    #[test]
    fn a_plane_missing_the_cell_leaves_one_side_empty() {
        let (b, a) = unit().split_areas(Vec3A::Z, 2.0);
        assert!(close(b, 6.0) && close(a, 0.0));
        let (pb, pa) = unit().split(Vec3A::Z, 2.0);
        assert!(close(pb.area(), 6.0) && pa.is_empty() && pa.bounds().is_empty());
        // A plane through a face: no volume above it.
        let (pb, pa) = unit().split(Vec3A::Z, 1.0);
        assert!(close(pb.area(), 6.0) && pa.is_empty());
    }
}
