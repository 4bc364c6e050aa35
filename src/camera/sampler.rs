//! Stratified samples for cameras, without allocation: `n` samples of one group (the `spp`
//! samples of a pixel, or the pixels of a 4 x 4 tile of a one-sample-per-pixel ray set) are
//! spread over `n` strata in every dimension. A 2D dimension (film, lens) uses a jittered
//! `m x m` grid when `n = m^2`, else `n` rooks (one sample per row and per column); the 1D
//! dimension (shutter time) uses `n` intervals. Each dimension assigns strata to samples by
//! its own hashed permutation (Kensler 2013, "Correlated Multi-Jittered Sampling"), so the
//! dimensions are not correlated, and jitters within strata come from SplitMix64 seeded by
//! `(seed, group, sample)`: the same inputs give the same samples on any thread.

use crate::random::SplitMix64;

/// One sample's unit-square coordinates: film offset within the pixel, lens point, shutter
/// time; each component in `[0, 1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitSample {
    pub film: [f64; 2],
    pub lens: [f64; 2],
    pub time: f64,
}

/// Side of the pixel tiles over which one-sample-per-pixel ray sets stratify.
pub const TILE: u32 = 4;

/// Sample `k` of the `n` samples (`k < n`) of group `group`.
pub fn stratified(n: u32, k: u32, group: u64, seed: u64) -> UnitSample {
    debug_assert!(k < n);
    let mut rng = SplitMix64::new(mix(seed, group, k as u64 + 1));
    let scramble = |dim: u64| mix(seed, group, dim << 40) as u32;
    let mut jitter = || rng.next_unit();
    let film = stratum_2d(n, k, scramble(1), [jitter(), jitter()]);
    let lens = stratum_2d(n, k, scramble(2), [jitter(), jitter()]);
    let time = (permute(k, n, scramble(3)) as f64 + jitter()) / n as f64;
    UnitSample { film, lens, time }
}

/// The sample of pixel `(i, j)` in a one-sample-per-pixel image: the pixels of each
/// [`TILE`] x [`TILE`] tile are the 16 strata of one group.
pub fn per_pixel(i: u32, j: u32, width: u32, seed: u64) -> UnitSample {
    let tiles_x = width.div_ceil(TILE) as u64;
    let group = (j / TILE) as u64 * tiles_x + (i / TILE) as u64;
    stratified(TILE * TILE, (j % TILE) * TILE + i % TILE, group, seed)
}

/// Sample `k`'s point in the unit square: cell `permute(k)` of the `m x m` grid when
/// `n = m^2`, else row `k`, column `permute(k)` of `n x n` (rooks), jittered by `j`.
fn stratum_2d(n: u32, k: u32, scramble: u32, j: [f64; 2]) -> [f64; 2] {
    let m = n.isqrt();
    if m * m == n {
        let cell = permute(k, n, scramble);
        let m = m as f64;
        [
            ((cell % n.isqrt()) as f64 + j[0]) / m,
            ((cell / n.isqrt()) as f64 + j[1]) / m,
        ]
    } else {
        let n_f = n as f64;
        [
            (k as f64 + j[0]) / n_f,
            (permute(k, n, scramble) as f64 + j[1]) / n_f,
        ]
    }
}

/// A seed from three values (SplitMix64's finalizer over their combination).
fn mix(seed: u64, group: u64, salt: u64) -> u64 {
    SplitMix64::new(
        seed ^ group.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ salt.wrapping_mul(0xD1B5_4A32_D192_ED03),
    )
    .next_u64()
}

/// Kensler's hashed permutation: element `i` of a pseudo-random permutation of `0..l` chosen
/// by `p` (cycle-walking a bijection on the next power of two).
pub fn permute(mut i: u32, l: u32, p: u32) -> u32 {
    let mut w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & w) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | p >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= w;
        i ^= i >> 5;
        if i < l {
            break;
        }
    }
    // `p % l` first: `i + p` wrapping at 2^32 would map two elements to one.
    (i + p % l) % l
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permute_is_a_permutation() {
        for l in [1, 2, 3, 7, 16, 17, 100] {
            for p in [0, 1, 0xdead_beef, u32::MAX] {
                let mut seen = vec![false; l as usize];
                for i in 0..l {
                    let v = permute(i, l, p) as usize;
                    assert!(!seen[v], "l {l} p {p}: {v} twice");
                    seen[v] = true;
                }
            }
        }
    }

    #[test]
    fn every_stratum_gets_one_sample() {
        for n in [1u32, 4, 5, 16] {
            let samples: Vec<UnitSample> = (0..n).map(|k| stratified(n, k, 7, 3)).collect();
            let mut times: Vec<u32> = samples.iter().map(|s| (s.time * n as f64) as u32).collect();
            times.sort();
            assert_eq!(times, (0..n).collect::<Vec<_>>());
            let m = n.isqrt();
            if m * m == n {
                let mut cells: Vec<u32> = samples
                    .iter()
                    .map(|s| (s.lens[0] * m as f64) as u32 + m * (s.lens[1] * m as f64) as u32)
                    .collect();
                cells.sort();
                assert_eq!(cells, (0..n).collect::<Vec<_>>());
            }
            for s in &samples {
                for v in s.film.iter().chain(&s.lens).chain([&s.time]) {
                    assert!((0.0..1.0).contains(v));
                }
            }
        }
        assert_eq!(per_pixel(5, 6, 20, 1), per_pixel(5, 6, 20, 1));
        assert_ne!(per_pixel(5, 6, 20, 1), per_pixel(5, 6, 20, 2));
    }
}
