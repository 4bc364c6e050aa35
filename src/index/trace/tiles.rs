//! Packets from screen tiles: when a batch is an image of camera rays in raster order (its width
//! known, [`super::TraceIndex::closest_hits_image`]), the packet modes take each packet from a
//! tile of neighbouring pixels, 4 x 4 for 16 rays, 4 x 2 for 8 and 2 x 2 for 4 ([`tile_shape`]),
//! instead of a segment of one row: a square of pixels spans fewer directions than a row segment
//! of the same count, so its rays part ways later in the tree.
//!
//! The design: the parallel driver cuts such a batch into bands of [`BAND_ROWS`] image rows
//! (each band a contiguous run of the batch, so the answers of a band are a contiguous slice
//! too) and a worker traces its band tile by tile ([`trace_band`]): it gathers a tile's rays
//! into a packet on the stack (copies, no allocation), traces it, and scatters the answers and
//! counters back to the rays' places in the batch. No permutation of the batch is built, so
//! nothing is computed outside the traced region and nothing is allocated per batch; the timed
//! pass includes the gathers and scatters (a few hundred bytes per packet). A band's last row
//! may be partial and the image's last band may have fewer rows; tiles at the right and bottom
//! borders are then smaller packets. Every ray's answer is its single-ray answer whatever the
//! packet it is traced in, so the order changes no result.

use super::batch::BatchIndex;
use super::mode::MAX_PACKET;
use super::query::Query;
use crate::geometry::Ray;
use crate::index::Stats;
use crate::scene::Geometry;

/// Image rows per band of a tiled batch: a multiple of every tile's height.
pub const BAND_ROWS: usize = 4;

/// The tile of a packet of `n` rays as (columns, rows): 4 x 4 for 16, 4 x 2 for 8, 2 x 2 for 4;
/// any other size is a row segment of `n` (at most [`MAX_PACKET`]).
pub fn tile_shape(n: usize) -> (usize, usize) {
    match n {
        16 => (4, 4),
        8 => (4, 2),
        4 => (2, 2),
        n => (n.clamp(1, MAX_PACKET), 1),
    }
}

/// The side of a square image of `len` pixels (`side * side == len`, `side >= 2`), if `len` is
/// one: how the harness's passes recognise the suite's camera sets, which are `side x side`
/// images in raster order.
pub fn square_side(len: usize) -> Option<usize> {
    let side = len.isqrt();
    (side >= 2 && side * side == len).then_some(side)
}

/// Answers query `Q` for one band of an image `width` rays wide (at most [`BAND_ROWS`] rows in
/// raster order, the last possibly partial) in packets of `n` rays from tiles of
/// [`tile_shape`]`(n)`, lane by lane in raster order within the tile (`out` and `stats` as
/// long as `rays`), each packet traced as a beam when `beams` ([`Query::packet`]).
pub fn trace_band<Q: Query, I: BatchIndex, G: Geometry, S: Stats>(
    index: &I,
    geom: &G,
    (n, beams): (usize, bool),
    width: usize,
    rays: &[Ray],
    out: &mut [Q::Answer],
    stats: &mut [S],
) {
    let mut lanes_stats: [S; MAX_PACKET] = std::array::from_fn(|_| S::default());
    for (at, m) in tiles(n, width, rays.len()) {
        let at = &at[..m];
        let packet: [Ray; MAX_PACKET] = std::array::from_fn(|k| rays[at[k.min(m - 1)]]);
        let mut answers = [out[at[0]]; MAX_PACKET];
        for (s, &i) in lanes_stats.iter_mut().zip(at) {
            *s = std::mem::take(&mut stats[i]);
        }
        Q::packet(
            beams,
            index,
            geom,
            &packet[..m],
            &mut answers[..m],
            &mut lanes_stats[..m],
        );
        for (k, &i) in at.iter().enumerate() {
            out[i] = answers[k];
            stats[i] = std::mem::take(&mut lanes_stats[k]);
        }
    }
}

/// The tiles of a band of `len` rays in rows of `width` (the last row possibly partial), left
/// to right in each row of tiles, rows of tiles top to bottom: per tile the rays' places in
/// the band (raster order within the tile) and their number `m >= 1`.
fn tiles(n: usize, width: usize, len: usize) -> impl Iterator<Item = ([usize; MAX_PACKET], usize)> {
    let (tw, th) = tile_shape(n);
    let rows = len.div_ceil(width);
    let corners = (0..rows)
        .step_by(th)
        .flat_map(move |y0| (0..width).step_by(tw).map(move |x0| (x0, y0)));
    corners.filter_map(move |(x0, y0)| {
        let mut at = [0usize; MAX_PACKET];
        let mut m = 0;
        for y in y0..(y0 + th).min(rows) {
            for x in x0..(x0 + tw).min(width) {
                let i = y * width + x;
                if i < len {
                    at[m] = i;
                    m += 1;
                }
            }
        }
        (m > 0).then_some((at, m))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_hold_their_packet_and_squares_are_recognised() {
        for n in [4, 8, 16] {
            let (w, h) = tile_shape(n);
            assert_eq!(w * h, n);
            assert_eq!(BAND_ROWS % h, 0);
        }
        assert_eq!(tile_shape(3), (3, 1));
        assert_eq!(square_side(512 * 512), Some(512));
        assert_eq!(square_side(37 * 37), Some(37));
        assert_eq!(square_side(512 * 511), None);
        assert_eq!(square_side(1), None);
    }

    /// Every ray of a band is in exactly one tile, whose rays are at most the tile's columns
    /// and rows apart: widths that are and are not multiples of the tile, partial last rows.
    #[test]
    fn tiles_cover_every_ray_once() {
        for n in [4, 8, 16] {
            let (tw, th) = tile_shape(n);
            for width in [1, 2, 3, 4, 5, 7, 8, 13, 16] {
                for len in [1, width, 2 * width + 1, 3 * width - 1, 4 * width] {
                    let mut seen = vec![0; len];
                    for (at, m) in tiles(n, width, len) {
                        assert!((1..=n).contains(&m));
                        let (x0, y0) = (at[0] % width, at[0] / width);
                        for &i in &at[..m] {
                            seen[i] += 1;
                            assert!(i % width - x0 < tw && i / width - y0 < th);
                        }
                    }
                    assert!(seen.iter().all(|&c| c == 1), "{n} {width} {len}");
                }
            }
        }
    }
}
