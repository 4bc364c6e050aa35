//! Polygons, fans and strips as triangle corners (the three vertex indices of each triangle,
//! in order), the one way every loader triangulates them.

/// A polygon of `n >= 3` vertices fan-triangulated `(v0, vi, vi+1)`, as the OBJ loader does
/// (PLY faces).
pub fn push_polygon(out: &mut Vec<[u32; 3]>, poly: &[u32]) {
    for i in 1..poly.len().saturating_sub(1) {
        out.push([poly[0], poly[i], poly[i + 1]]);
    }
}

/// A triangle strip as glTF defines it: triangle `i` is `(v_i, v_{i+1+i%2}, v_{i+2-i%2})`, so
/// every triangle keeps the first one's orientation (PLY `tristrips` runs and glTF
/// `TRIANGLE_STRIP`). A triangle with a repeated index is left out: it is the zero-area join
/// by which strips are concatenated, not a surface.
pub fn push_strip(out: &mut Vec<[u32; 3]>, strip: &[u32]) {
    for i in 0..strip.len().saturating_sub(2) {
        let odd = i % 2;
        let t = [strip[i], strip[i + 1 + odd], strip[i + 2 - odd]];
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            out.push(t);
        }
    }
}

/// A glTF `TRIANGLE_FAN`: triangle `i` is `(v_{i+1}, v_{i+2}, v_0)`, as the glTF specification
/// writes it.
pub fn push_fan(out: &mut Vec<[u32; 3]>, fan: &[u32]) {
    for i in 0..fan.len().saturating_sub(2) {
        out.push([fan[i + 1], fan[i + 2], fan[0]]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with(f: fn(&mut Vec<[u32; 3]>, &[u32]), v: &[u32]) -> Vec<u32> {
        let mut out = Vec::new();
        f(&mut out, v);
        out.concat()
    }

    #[test]
    fn polygons_strips_and_fans() {
        assert_eq!(with(push_polygon, &[0, 1, 2, 3]), [0, 1, 2, 0, 2, 3]);
        assert_eq!(with(push_polygon, &[0, 1]), [0u32; 0]);
        assert_eq!(
            with(push_strip, &[0, 1, 2, 3, 4]),
            [0, 1, 2, 1, 3, 2, 2, 3, 4]
        );
        // A join repeating index 2: its two degenerate triangles are dropped.
        assert_eq!(with(push_strip, &[0, 1, 2, 2, 5, 6]), [0, 1, 2, 2, 6, 5]);
        assert_eq!(with(push_fan, &[0, 1, 2, 3]), [1, 2, 0, 2, 3, 0]);
    }
}
