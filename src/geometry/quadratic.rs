//! The stable roots of `|f + t d|^2 = r^2`, the quadratic behind the sphere, the unit sphere of
//! the ellipsoid and the side of the cylinder (`f`, `d` projected off its axis).

use super::real::{Real, RealVec};

/// Both roots `(lo, hi)` of `|f + t d|^2 = r^2`, or `None` when the line misses (or `d = 0`),
/// in the precision of `f` and `d`.
///
/// The stable form of Haines et al. (Ray Tracing Gems ch. 7): the discriminant as `r^2 - |f - (f.d/d.d) d|^2`, the squared distance of the line
/// from the centre subtracted from `r^2`, so there is no cancellation between `b^2` and `4ac`;
/// the roots as `c/q` and `q/a` with `q = -(b' + sign(b') sqrt(a disc))`, so neither root
/// subtracts two nearly equal numbers.
#[inline(always)]
pub fn ball_roots<S: Real, V: RealVec<Scalar = S>>(f: V, d: V, r: S) -> Option<(S, S)> {
    let a = d.dot(d);
    if a == S::ZERO {
        return None;
    }
    let b = f.dot(d); // half of the usual b
    let c = f.dot(f) - r * r;
    let l = f - d * (b / a);
    let disc = r * r - l.dot(l);
    if disc < S::ZERO {
        return None;
    }
    let root = (a * disc).sqrt();
    let q = -(b + root.copysign(b));
    if q == S::ZERO {
        // b == 0 and disc == 0: tangent at t = 0.
        return Some((S::ZERO, S::ZERO));
    }
    let (t0, t1) = (c / q, q / a);
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    #[test]
    fn hand_computed_roots() {
        // From x = -3 along +x through the unit ball: t = 2 and 4.
        assert_eq!(
            ball_roots(Vec3A::new(-3.0, 0.0, 0.0), Vec3A::X, 1.0),
            Some((2.0, 4.0))
        );
        // Starting at the centre: t = -1 and 1 (the caller takes the one >= t_min).
        assert_eq!(
            ball_roots(Vec3A::ZERO, Vec3A::X * 2.0, 1.0),
            Some((-0.5, 0.5))
        );
        assert_eq!(ball_roots(Vec3A::new(-3.0, 1.5, 0.0), Vec3A::X, 1.0), None);
        assert_eq!(ball_roots(Vec3A::ZERO, Vec3A::ZERO, 1.0), None);
    }

    #[test]
    fn far_small_ball_keeps_its_digits() {
        let (t0, t1) = ball_roots(Vec3A::new(0.0, 0.0, -1.0e4), Vec3A::Z, 0.01).unwrap();
        assert!((t0 - 9999.99).abs() <= 1e-3 && (t1 - 10000.01).abs() <= 1e-3);
    }
}
