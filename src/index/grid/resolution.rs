//! How many cells per axis: the cube-root heuristic (Cleary & Wyvill 1988; Ize, Shirley &
//! Parker 2007) or an explicit resolution, both checked against the cell cap.

use glam::Vec3A;

/// Most cells a grid may have (64M): the cell offsets alone then take 256 MiB.
pub const MAX_CELLS: u64 = 1 << 26;

/// Cells per primitive the heuristic aims at when no `lambda` is given.
pub const DEFAULT_LAMBDA: f32 = 4.0;

/// Largest accepted `lambda` (cells per primitive); the cell cap applies anyway.
pub const MAX_LAMBDA: f32 = 1.0e6;

/// Cells per axis from the cube-root heuristic: `ext_i * cbrt(lambda * prims / volume)`, so the
/// grid has about `lambda * prims` roughly cubic cells.
///
/// Axes whose share would be under one cell (zero or tiny extent: flat scenes) get exactly one
/// cell and the density is recomputed over the remaining axes (`sqrt` for a plane, the prims
/// themselves for a line), so a flat scene is not over-refined. The result has at least one cell
/// per axis and at most [`MAX_CELLS`] cells in all (scaled down evenly when the heuristic asks for
/// more). `lambda` must be finite and positive (checked by the caller).
pub fn heuristic_resolution(extent: Vec3A, prims: usize, lambda: f32) -> [u32; 3] {
    let ext = extent.to_array().map(|e| f64::from(e.max(0.0)));
    let target = f64::from(lambda) * prims.max(1) as f64;
    let mut active: Vec<usize> = (0..3).filter(|&a| ext[a] > 0.0).collect();
    let mut cells = [1.0f64; 3];
    while !active.is_empty() {
        let volume: f64 = active.iter().map(|&a| ext[a]).product();
        let density = (target / volume).powf(1.0 / active.len() as f64);
        let before = active.len();
        active.retain(|&a| ext[a] * density >= 1.0);
        if active.len() == before {
            for &a in &active {
                cells[a] = ext[a] * density;
            }
            break;
        }
    }
    let mut res = cells.map(|c| c.round().clamp(1.0, MAX_CELLS as f64) as u32);
    cap_cells(&mut res);
    res
}

/// Scales `res` down evenly (each axis at least 1) until it has at most [`MAX_CELLS`] cells.
fn cap_cells(res: &mut [u32; 3]) {
    while total_cells(*res) > MAX_CELLS {
        let shrink = (MAX_CELLS as f64 / total_cells(*res) as f64).cbrt();
        let before = *res;
        for r in res.iter_mut() {
            *r = ((*r as f64 * shrink).floor() as u32).max(1);
        }
        if *res == before {
            // Rounding kept every axis: take one cell off the finest.
            let a = (0..3).max_by_key(|&a| res[a]).unwrap_or(0);
            res[a] -= 1;
        }
    }
}

/// Total cells of a resolution (no overflow: at most `(2^32)^3 < 2^96`, computed in `u128`).
pub fn total_cells(res: [u32; 3]) -> u64 {
    let t = res.iter().map(|&r| r as u128).product::<u128>();
    u64::try_from(t).unwrap_or(u64::MAX)
}

/// Checks an explicit resolution: at least one cell per axis, at most [`MAX_CELLS`] in all.
pub fn check_resolution(res: [u32; 3]) -> Result<(), String> {
    if res.contains(&0) {
        return Err(format!(
            "res = {res:?} has an axis with 0 cells: give at least 1 cell per axis"
        ));
    }
    let total = total_cells(res);
    if total > MAX_CELLS {
        return Err(format!(
            "res = {res:?} is {total} cells; at most {MAX_CELLS} are allowed: lower the resolution"
        ));
    }
    Ok(())
}

/// Checks a heuristic density: finite, positive, at most [`MAX_LAMBDA`].
pub fn check_lambda(lambda: f32) -> Result<(), String> {
    if lambda.is_finite() && lambda > 0.0 && lambda <= MAX_LAMBDA {
        Ok(())
    } else {
        Err(format!(
            "lambda = {lambda} must be a number of cells per primitive in (0, {MAX_LAMBDA}]"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_gets_about_lambda_n_cubic_cells() {
        let res = heuristic_resolution(Vec3A::ONE, 1000, 8.0);
        assert_eq!(res, [20, 20, 20]);
        // A box twice as long in x gets twice the cells there (cells stay cubic).
        let res = heuristic_resolution(Vec3A::new(2.0, 1.0, 1.0), 1000, 16.0);
        assert_eq!(res, [40, 20, 20]);
    }

    #[test]
    fn flat_and_thin_axes_get_one_cell_and_the_rest_is_two_dimensional() {
        assert_eq!(
            heuristic_resolution(Vec3A::new(1.0, 0.0, 1.0), 100, 4.0),
            [20, 1, 20]
        );
        // Tiny but nonzero extent behaves like zero (no explosion of x and z).
        assert_eq!(
            heuristic_resolution(Vec3A::new(1.0, 1e-30, 1.0), 100, 4.0),
            [20, 1, 20]
        );
        // A line, and a point (one degenerate primitive).
        assert_eq!(
            heuristic_resolution(Vec3A::new(0.0, 0.0, 3.0), 10, 4.0),
            [1, 1, 40]
        );
        assert_eq!(heuristic_resolution(Vec3A::ZERO, 1, 4.0), [1, 1, 1]);
    }

    #[test]
    fn heuristic_is_capped_and_explicit_resolution_is_checked() {
        let res = heuristic_resolution(Vec3A::ONE, 100_000_000, MAX_LAMBDA);
        assert!(total_cells(res) <= MAX_CELLS && total_cells(res) > MAX_CELLS / 2);
        assert!(check_resolution([1, 1, 1]).is_ok());
        assert!(check_resolution([0, 4, 4]).unwrap_err().contains("0 cells"));
        assert!(
            check_resolution([100_000, 100_000, 100_000])
                .unwrap_err()
                .contains("at most")
        );
        assert!(check_resolution([u32::MAX; 3]).is_err());
        for bad in [0.0, -1.0, f32::NAN, f32::INFINITY, 2.0e6] {
            assert!(check_lambda(bad).is_err(), "{bad}");
        }
        assert!(check_lambda(4.0).is_ok());
    }
}
