//! `f64` mirrors of the shape kernels (`geometry::shapes`), and the reference built on them.
//!
//! Each mirror follows its `f32` original step by step (same formulas, same acceptance tests)
//! with every value in `f64`, computed from the shape's stored `f32` data (the cone's squared
//! slope and the ellipsoid's unit-sphere map are recomputed in `f64` from the stored sizes and
//! axes). The rim slack of the cylinder and cone is `8 f64::EPSILON` of the same magnitudes, the
//! mirror's own rounding bound, as the `f32` kernels use `8 f32::EPSILON`.
//!
//! Unlike triangles and spheres, the shapes have no exact reference here: the mirror is the
//! reference. To keep that honest every decision the mirror takes (an edge or rim test, a
//! tangent, a slab overlap, `t >= 0`) is compared with a first-order bound on its own rounding
//! error, `DOUBT_ULPS` ulps of the magnitudes involved. When a decision that can change the
//! answer lies within that bound the ray is [`Reference::Unverifiable`] and is left out of the
//! rates (as the triangle reference does when an exact difference is not available).

use super::kernels_f64::Ray64;
use crate::geometry::reference::Reference;
use crate::geometry::shapes::{Cone, Cylinder, Ellipsoid, Obb, Polygon, obb};
use crate::geometry::{Ray, Shape};
use glam::{DMat3, DVec3, Vec3A};

/// How many `f64` ulps of the magnitudes involved a decision must clear to be trusted.
pub const DOUBT_ULPS: f64 = 64.0;
const TOL: f64 = DOUBT_ULPS * f64::EPSILON;

/// The `f64` rim slack (the mirror of `geometry::shapes::cylinder::RIM_SLACK`).
const RIM_SLACK: f64 = 8.0 * f64::EPSILON;

fn v64(v: Vec3A) -> DVec3 {
    glam::Vec3::from(v).as_dvec3()
}

/// A stored `f32` matrix, exactly, in `f64`.
pub(super) fn dmat(m: glam::Mat3A) -> DMat3 {
    glam::Mat3::from(m).as_dmat3()
}

/// Set when a decision that matters lies within its rounding bound.
#[derive(Debug, Default, Clone, Copy)]
pub struct Doubt(pub bool);

/// A candidate crossing: its `t`, whether the mirror accepts it, whether that acceptance is
/// within the rounding bound, and a bound on the error of `t`.
#[derive(Debug, Clone, Copy)]
struct Cand {
    t: f64,
    ok: bool,
    unsure: bool,
    t_err: f64,
}

impl Cand {
    const NONE: Cand = Cand {
        t: f64::NAN,
        ok: false,
        unsure: false,
        t_err: 0.0,
    };
}

/// The mirror of `shapes::first_hit`: the smallest accepted finite candidate `>= t_min`, if it is
/// `<= t_max`. Doubt when a candidate that could be (or beat) the answer has an uncertain
/// acceptance or an uncertain `t >= t_min`.
fn settle(cands: &[Cand], ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let mut best = f64::INFINITY;
    for c in cands {
        if c.ok && c.t >= ray.t_min && c.t < best {
            best = c.t;
        }
    }
    for c in cands.iter().filter(|c| c.t.is_finite()) {
        // Only a candidate that may lie in range and not beyond the answer can change it.
        let matters = c.t + c.t_err >= ray.t_min && c.t - c.t_err <= best;
        if matters && (c.unsure || (c.ok && (c.t - ray.t_min).abs() <= c.t_err)) {
            doubt.0 = true;
        }
    }
    (best.is_finite() && best <= t_max).then_some(best)
}

/// The mirror of the shape's kernel (a box by its front planes if `box_front_planes`, else slabs).
pub fn mirror(
    box_front_planes: bool,
    shape: &Shape,
    ray: &Ray64,
    t_max: f64,
    d: &mut Doubt,
) -> Option<f64> {
    match (box_front_planes, shape) {
        (true, Shape::Box(b)) => self::box_front_planes(b, ray, t_max, d),
        (_, Shape::Box(b)) => box_slabs(b, ray, t_max, d),
        (_, Shape::ConvexPolygon(p)) => convex_polygon(p, ray, t_max, d),
        (_, Shape::ConcavePolygon(p)) => concave_polygon(p, ray, t_max, d),
        (_, Shape::Cylinder(c)) => cylinder(c, ray, t_max, d),
        (_, Shape::Cone(c)) => cone(c, ray, t_max, d),
        (_, Shape::Ellipsoid(e)) => ellipsoid(e, ray, t_max, d),
    }
}

/// The reference for one ray against one shape: the mirror over `[0, +inf]`, or
/// [`Reference::Unverifiable`] when one of its decisions is within its rounding bound.
pub fn reference(box_front_planes: bool, shape: &Shape, ray: &Ray) -> Reference {
    let r = Ray64::from_ray(ray);
    let mut doubt = Doubt::default();
    let hit = mirror(box_front_planes, shape, &r, f64::INFINITY, &mut doubt);
    match (doubt.0, hit) {
        (true, _) => Reference::Unverifiable,
        (false, Some(t)) => Reference::Hit(t),
        (false, None) => Reference::Miss,
    }
}

/// The ray in the box frame, and `|origin - center|` (the scale of the frame change's rounding).
fn box_local(b: &Obb, ray: &Ray64) -> (DVec3, DVec3, f64) {
    let to_local = dmat(b.axes()).transpose();
    let v = ray.origin - v64(b.center());
    (to_local * v, to_local * ray.dir, v.length())
}

/// Bound on the error of a face-plane parameter `t = (±h_i - o_i) / d_i`.
fn plane_t_err(h: DVec3, o: DVec3, v_len: f64, t: f64, ray: &Ray64, d_i: f64) -> f64 {
    TOL * (h.max_element() + o.abs().max_element() + v_len + t.abs() * ray.dir.length()) / d_i.abs()
}

/// Mirrors `shapes::obb::intersect_slabs` (the slab test of `aabb_kernel::slab_first_hit`).
pub fn box_slabs(b: &Obb, ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let (o, d, v_len) = box_local(b, ray);
    let h = v64(b.half_extents());
    let inv = DVec3::ONE / d;
    let t_lo = (-h - o) * inv;
    let t_hi = (h - o) * inv;
    let (mut enter, mut exit) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut ie, mut ix) = (None, None);
    // A NaN (origin on a face plane, zero direction on that axis) puts no constraint: it
    // stands for `none` in the min or max that takes it.
    let or_none = |t: f64, none: f64| if t.is_nan() { none } else { t };
    for i in 0..3 {
        let near = or_none(t_lo[i], f64::NEG_INFINITY).min(or_none(t_hi[i], f64::NEG_INFINITY));
        let far = or_none(t_lo[i], f64::INFINITY).max(or_none(t_hi[i], f64::INFINITY));
        if near > enter {
            (enter, ie) = (near, Some(i));
        }
        if far < exit {
            (exit, ix) = (far, Some(i));
        }
    }
    let err = |t: f64, i: Option<usize>| i.map_or(0.0, |i| plane_t_err(h, o, v_len, t, ray, d[i]));
    let (e_err, x_err) = (err(enter, ie), err(exit, ix));
    let ok = enter <= exit;
    let unsure = (enter - exit).abs() <= e_err + x_err;
    let cand = |t, t_err| Cand {
        t,
        ok,
        unsure,
        t_err,
    };
    // The original returns the first of [enter, exit] in range: the smaller one, as enter <= exit.
    settle(&[cand(enter, e_err), cand(exit, x_err)], ray, t_max, doubt)
}

/// Mirrors `shapes::obb::intersect_front_planes`.
pub fn box_front_planes(b: &Obb, ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let (o, d, v_len) = box_local(b, ray);
    let h = v64(b.half_extents());
    for back in [false, true] {
        let mut cand = [Cand::NONE; 3];
        for (i, c) in cand.iter_mut().enumerate() {
            let Some(t) = obb::face_plane_t(h[i], o[i], d[i], back) else {
                continue;
            };
            let t_err = plane_t_err(h, o, v_len, t, ray, d[i]);
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            // Margin of |o_m + t d_m| <= h_m, and a bound on its error.
            let margin = |m: usize| h[m] - (o[m] + t * d[m]).abs();
            let m_err = |m: usize| {
                TOL * (h[m] + o[m].abs() + (t * d[m]).abs() + v_len) + t_err * d[m].abs()
            };
            let (mj, mk) = (margin(j), margin(k));
            let (ej, ek) = (m_err(j), m_err(k));
            *c = Cand {
                t,
                ok: mj >= 0.0 && mk >= 0.0,
                unsure: mj >= -ej && mk >= -ek && (mj.abs() <= ej || mk.abs() <= ek),
                t_err,
            };
        }
        let mut first = Doubt::default();
        if let Some(t) = settle(&cand, ray, f64::INFINITY, &mut first) {
            doubt.0 |= first.0;
            return (t <= t_max).then_some(t);
        }
        // Nothing on the front faces: an uncertain one there could have been the answer.
        doubt.0 |= first.0;
    }
    None
}

/// The plane crossing of a polygon and a bound on its error.
fn polygon_plane(p: &Polygon, ray: &Ray64) -> (f64, f64) {
    let n = v64(p.normal());
    let to_anchor = v64(p.anchor()) - ray.origin;
    let denom = n.dot(ray.dir);
    let t = n.dot(to_anchor) / denom;
    let t_err = TOL * (to_anchor.length() + t.abs() * ray.dir.length()) / denom.abs();
    (t, t_err)
}

/// Mirrors `shapes::polygon::intersect_convex`.
pub fn convex_polygon(p: &Polygon, ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let (t, t_err) = polygon_plane(p, ray);
    let n = v64(p.normal());
    let hit = ray.origin + ray.dir * t;
    let hit_err = TOL * (ray.origin.length() + (ray.dir * t).length()) + t_err * ray.dir.length();
    let v: Vec<DVec3> = p.vertices().iter().map(|&v| v64(v)).collect();
    let (mut ok, mut clearly_out, mut near) = (true, false, false);
    let mut a = v[v.len() - 1];
    for &b in &v {
        let e = (b - a).cross(hit - a).dot(n);
        let e_err = (b - a).length() * (hit_err + TOL * ((hit - a).length() + (b - a).length()));
        ok &= e >= 0.0;
        clearly_out |= e < -e_err;
        near |= e.abs() <= e_err;
        a = b;
    }
    let c = Cand {
        t,
        ok,
        unsure: near && !clearly_out,
        t_err,
    };
    settle(&[c], ray, t_max, doubt)
}

/// Mirrors `shapes::polygon::intersect_concave` (crossing number in the ray's shear frame).
pub fn concave_polygon(p: &Polygon, ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let (t, t_err) = polygon_plane(p, ray);
    // Projected (x, y) of a vertex and a bound on the error of each coordinate.
    let project = |v: Vec3A| {
        let q = v64(v) - ray.origin;
        let s = &ray.shear;
        let xy = (q[s.kx] - s.sx * q[s.kz], q[s.ky] - s.sy * q[s.kz]);
        let err = TOL * (q.abs().element_sum() * (1.0 + s.sx.abs() + s.sy.abs()));
        (xy, err)
    };
    let verts = p.vertices();
    let (mut inside, mut near) = (false, false);
    let mut a = project(verts[verts.len() - 1]);
    for &v in verts {
        let b = project(v);
        let (lo, hi) = if a.0.1 <= b.0.1 { (a, b) } else { (b, a) };
        let ((lx, ly), le) = lo;
        let ((hx, hy), he) = hi;
        let straddles = ly <= 0.0 && hy > 0.0;
        let det = lx * hy - ly * hx;
        if straddles && det > 0.0 {
            inside = !inside;
        }
        // A crossing (or a vertex on the half-line) whose side of the ray is uncertain.
        let det_err = TOL * ((lx * hy).abs() + (ly * hx).abs())
            + le * (hx.abs() + hy.abs())
            + he * (lx.abs() + ly.abs())
            + le * he;
        let could_straddle = ly <= le && hy > -he;
        near |= could_straddle && det.abs() <= det_err;
        a = b;
    }
    let c = Cand {
        t,
        ok: inside,
        unsure: near,
        t_err,
    };
    settle(&[c], ray, t_max, doubt)
}

/// The roots `(t0, t1)` of `|f + t d|^2 = r^2` by the stable form of `shapes::quadratic`, with
/// bounds on their errors, `g` bounding the absolute error of `f` (in units of `TOL`). `None`
/// when the line misses; doubt when it is tangent within the bound.
fn ball_roots(f: DVec3, d: DVec3, r: f64, g: f64, doubt: &mut Doubt) -> Option<[(f64, f64); 2]> {
    let a = d.dot(d);
    if a == 0.0 {
        return None;
    }
    let b = f.dot(d);
    let c = f.dot(f) - r * r;
    let l = f - d * (b / a);
    let disc = r * r - l.dot(l);
    let disc_err = TOL * (r + g + f.length()).powi(2);
    if disc.abs() <= disc_err {
        doubt.0 = true;
    }
    if disc < 0.0 {
        return None;
    }
    let root = (a * disc).sqrt();
    let q = -(b + root.copysign(b));
    if q == 0.0 {
        return Some([(0.0, 0.0), (0.0, 0.0)]);
    }
    let (a_err, b_err) = (TOL * a, TOL * a.sqrt() * (f.length() + g));
    let c_err = TOL * (f.length() + g + r).powi(2);
    let root_err = 0.5 * root * (TOL + disc_err / disc.max(f64::MIN_POSITIVE));
    let q_err = b_err + root_err;
    let t0 = (c / q, (c_err + (c / q).abs() * q_err) / q.abs());
    let t1 = (q / a, (q_err + (q / a).abs() * a_err) / a);
    Some(if t0.0 <= t1.0 { [t0, t1] } else { [t1, t0] })
}

/// The axial/radial split of a ray relative to a point on a unit axis: `(oz, dz, op, dp)`.
fn split(o: DVec3, d: DVec3, axis: DVec3) -> (f64, f64, DVec3, DVec3) {
    let (oz, dz) = (o.dot(axis), d.dot(axis));
    (oz, dz, o - axis * oz, d - axis * dz)
}

/// The side range test of the cylinder and cone (mirror, with its slack) as a candidate.
fn on_side(t: f64, t_err: f64, oz: f64, dz: f64, height: f64, g: f64) -> Cand {
    let z = oz + t * dz;
    let slack = RIM_SLACK * (oz.abs() + (t * dz).abs());
    let z_err = TOL * (g + (t * dz).abs()) + t_err * dz.abs();
    let ok = z >= -slack && z <= height + slack;
    let near = (z + slack).abs() <= z_err || (z - height - slack).abs() <= z_err;
    Cand {
        t,
        ok,
        unsure: near,
        t_err,
    }
}

/// The cap test (plane `z = zc` within the radius, mirror with its slack) as a candidate.
fn on_cap(zc: f64, oz: f64, dz: f64, op: DVec3, dp: DVec3, radius: f64, g: f64) -> Cand {
    if dz == 0.0 {
        return Cand::NONE;
    }
    let t = (zc - oz) / dz;
    let t_err = TOL * (g + zc.abs()) / dz.abs();
    let reach = radius + RIM_SLACK * (op.length() + t.abs() * dp.length());
    let rho = (op + dp * t).length();
    let rho_err = TOL * (g + (dp * t).length()) + t_err * dp.length();
    Cand {
        t,
        ok: rho * rho <= reach * reach,
        unsure: (rho - reach).abs() <= rho_err,
        t_err,
    }
}

/// Mirrors `shapes::cylinder::intersect`.
pub fn cylinder(c: &Cylinder, ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let (axis, h, r) = (v64(c.axis()), c.height() as f64, c.radius() as f64);
    let o = ray.origin - v64(c.base());
    let (oz, dz, op, dp) = split(o, ray.dir, axis);
    let g = o.length() + h + r;
    let mut cands = [Cand::NONE; 4];
    if let Some(roots) = ball_roots(op, dp, r, g, doubt) {
        for (slot, (t, t_err)) in cands.iter_mut().zip(roots) {
            *slot = on_side(t, t_err, oz, dz, h, g);
        }
    }
    cands[2] = on_cap(0.0, oz, dz, op, dp, r, g);
    cands[3] = on_cap(h, oz, dz, op, dp, r, g);
    settle(&cands, ray, t_max, doubt)
}

/// Mirrors `shapes::cone::intersect` (Lagrange's identity for the discriminant).
pub fn cone(c: &Cone, ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let (axis, h, r) = (v64(c.axis()), c.height() as f64, c.radius() as f64);
    let k = r / h;
    let k2 = k * k;
    let o = ray.origin - v64(c.apex());
    let (oz, dz, op, dp) = split(o, ray.dir, axis);
    let a = dp.dot(dp) - k2 * dz * dz;
    let b = op.dot(dp) - k2 * oz * dz;
    let cc = op.dot(op) - k2 * oz * oz;
    let disc = k2 * (dp * oz - op * dz).length_squared() - op.cross(dp).length_squared();
    let g = o.length() + h + r;
    let dl = ray.dir.length();
    let disc_err = TOL * 4.0 * (1.0 + k2) * (dl * g).powi(2);
    let mut cands = [Cand::NONE; 3];
    if disc.abs() <= disc_err {
        doubt.0 = true;
    }
    if disc >= 0.0 {
        let q = -(b + disc.sqrt().copysign(b));
        let (a_err, b_err, c_err) = (
            TOL * (1.0 + k2) * dl * dl,
            TOL * (1.0 + k2) * dl * g,
            TOL * (1.0 + k2) * g * g,
        );
        let q_err = b_err + 0.5 * disc_err / disc.sqrt().max(f64::MIN_POSITIVE);
        let roots = if q != 0.0 {
            [
                (cc / q, (c_err + (cc / q).abs() * q_err) / q.abs()),
                (q / a, (q_err + (q / a).abs() * a_err) / a.abs()),
            ]
        } else if a != 0.0 {
            [(0.0, c_err / a.abs()); 2]
        } else {
            [(f64::NAN, 0.0); 2]
        };
        for (slot, (t, t_err)) in cands.iter_mut().zip(roots) {
            *slot = on_side(t, t_err, oz, dz, h, g);
        }
    }
    cands[2] = on_cap(h, oz, dz, op, dp, r, g);
    settle(&cands, ray, t_max, doubt)
}

/// Mirrors `shapes::ellipsoid::intersect`: the unit-sphere frame (`diag(1 / radii) axes^T`,
/// computed in `f64`), then the stable sphere quadratic.
pub fn ellipsoid(e: &Ellipsoid, ray: &Ray64, t_max: f64, doubt: &mut Doubt) -> Option<f64> {
    let inv = DVec3::ONE / v64(e.radii());
    let to_unit = DMat3::from_diagonal(inv) * dmat(e.axes()).transpose();
    let f = to_unit * (ray.origin - v64(e.center()));
    let d = to_unit * ray.dir;
    let roots = ball_roots(f, d, 1.0, f.length() + 1.0, doubt)?;
    let cands = roots.map(|(t, t_err)| Cand {
        t,
        ok: true,
        unsure: false,
        t_err,
    });
    settle(&cands, ray, t_max, doubt)
}

#[cfg(test)]
#[path = "shapes_f64_tests.rs"]
mod tests;
