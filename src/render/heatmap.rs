//! Per-pixel cost heat maps: each camera ray coloured by the primitive tests or the node/cell
//! visits it cost, on a fixed scale, with the legend drawn into the image so pictures of
//! different indices compare at a glance.
//!
//! Scale: 0 is black; 1 to [`HEAT_MAX`] map logarithmically (base 2) onto 256 colours of the
//! Turbo colour map (dark blue, cyan, green, yellow, red, dark red); values above [`HEAT_MAX`]
//! get the top colour (the legend's last tick reads `1024+`).

use super::font::{draw_text, text_height, text_width};
use super::view::{pixel_ray, view_camera};
use super::{Image, RenderError, RenderOptions};
use crate::index::{Counters, TraceIndex};
use crate::scene::Scene;
use rayon::prelude::*;
use std::fmt;
use std::str::FromStr;

/// The cost at and above which the colour scale is saturated.
pub const HEAT_MAX: u64 = 1024;

/// Number of colours of the scale (besides black for 0).
const LEVELS: u32 = 256;

/// Legend band colours.
const BAND: [u8; 3] = [24, 24, 24];
const INK: [u8; 3] = [230, 230, 230];

/// Which count of a camera ray a heat map shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HeatmapKind {
    /// Ray–primitive kernel calls ([`Counters::prim_tests`]).
    Tests,
    /// Nodes or cells visited ([`Counters::node_visits`]).
    Nodes,
}

impl HeatmapKind {
    pub const ALL: [HeatmapKind; 2] = [HeatmapKind::Tests, HeatmapKind::Nodes];

    pub fn name(self) -> &'static str {
        match self {
            HeatmapKind::Tests => "tests",
            HeatmapKind::Nodes => "nodes",
        }
    }

    /// The count this kind shows.
    pub fn of(self, c: &Counters) -> u64 {
        match self {
            HeatmapKind::Tests => c.prim_tests,
            HeatmapKind::Nodes => c.node_visits,
        }
    }
}

impl fmt::Display for HeatmapKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for HeatmapKind {
    type Err = String;
    fn from_str(s: &str) -> Result<HeatmapKind, String> {
        HeatmapKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| format!("unknown heat map '{s}': choose tests or nodes"))
    }
}

/// The cost of each pixel's camera ray (row-major, `width * height` values): the closest-hit
/// query's count of `kind`, as [`TraceIndex::closest_hit_counted`] reports it. Parallel over
/// rows; no allocation per ray.
pub fn pixel_costs(
    scene: &Scene,
    index: &dyn TraceIndex,
    opts: &RenderOptions,
    kind: HeatmapKind,
) -> Result<Vec<u64>, RenderError> {
    let cam = view_camera(scene, opts)?;
    pixel_ray(&cam, 0, 0)?;
    let w = opts.width as usize;
    let mut costs = vec![0u64; w * opts.height as usize];
    costs.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
        for (i, cost) in row.iter_mut().enumerate() {
            if let Ok(ray) = pixel_ray(&cam, i as u32, j as u32) {
                let mut c = Counters::default();
                index.closest_hit_counted(&ray, &mut c);
                *cost = kind.of(&c);
            }
        }
    });
    Ok(costs)
}

/// The heat map of `scene` through `index`: [`pixel_costs`] drawn by [`heatmap_image`].
pub fn render_heatmap(
    scene: &Scene,
    index: &dyn TraceIndex,
    opts: &RenderOptions,
    kind: HeatmapKind,
) -> Result<Image, RenderError> {
    let costs = pixel_costs(scene, index, opts, kind)?;
    Ok(heatmap_image(&costs, opts.width, opts.height))
}

/// The colour of cost `v`: black for 0, else Turbo at level
/// `round(255 * min(log2(v) / log2(HEAT_MAX), 1))`.
pub fn heat_colour(v: u64) -> [u8; 3] {
    if v == 0 {
        return [0; 3];
    }
    let t = ((v as f64).log2() / (HEAT_MAX as f64).log2()).min(1.0);
    level_colour((t * (LEVELS - 1) as f64).round() as u32)
}

/// Colour `level` (0 to 255) of the scale: Turbo by the polynomial fit of Mikhailov (Google AI,
/// 2019), evaluated in `f64` over `[0.1, 1]` (its first tenth is too close to black, the colour
/// of 0).
fn level_colour(level: u32) -> [u8; 3] {
    let x = 0.1 + 0.9 * (level.min(LEVELS - 1) as f64 / (LEVELS - 1) as f64);
    let poly = |c: [f64; 6]| c.iter().rev().fold(0.0, |acc, k| acc * x + k);
    let r = poly([
        0.135_721_38,
        4.615_392_6,
        -42.660_322_58,
        132.131_082_34,
        -152.942_393_96,
        59.286_379_43,
    ]);
    let g = poly([
        0.091_402_61,
        2.194_188_39,
        4.842_966_58,
        -14.185_033_33,
        4.277_298_57,
        2.829_566_04,
    ]);
    let b = poly([
        0.106_673_3,
        12.641_946_08,
        -60.582_048_36,
        110.362_767_71,
        -89.903_109_12,
        27.348_249_73,
    ]);
    [r, g, b].map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
}

/// Scale of the legend's font and spacing: 2 from 256 pixels wide, else 1.
fn legend_scale(width: u32) -> u32 {
    if width >= 256 { 2 } else { 1 }
}

/// Height of the legend band [`heatmap_image`] adds under an image of this width.
pub fn legend_height(width: u32) -> u32 {
    18 * legend_scale(width)
}

/// Colours `costs` (row-major, `width * height`) by [`heat_colour`] and adds a legend band of
/// [`legend_height`] rows underneath: a black swatch for 0, then the colour bar from 1 to
/// [`HEAT_MAX`] with ticks at 1, 4, 16, 64, 256 and `1024+`. Pixel `(i, j)` for `j < height` is
/// `heat_colour(costs[j * width + i])`.
///
/// Panics if `costs.len() != width * height` (a caller bug, like a batch query's output slice).
pub fn heatmap_image(costs: &[u64], width: u32, height: u32) -> Image {
    assert_eq!(
        costs.len(),
        width as usize * height as usize,
        "one cost per pixel"
    );
    let mut img = Image::new(width, height);
    for (row, c) in img
        .rows_mut()
        .zip(costs.chunks_exact(width.max(1) as usize))
    {
        for (px, v) in row.chunks_exact_mut(3).zip(c) {
            px.copy_from_slice(&heat_colour(*v));
        }
    }
    img.stack(&legend(width))
}

/// The legend band.
fn legend(width: u32) -> Image {
    let s = legend_scale(width);
    let mut img = Image::new(width, legend_height(width));
    img.fill(0, 0, width, img.height(), BAND);
    let (pad, bar_h, swatch) = (3 * s, 6 * s, 6 * s);
    let label_y = pad + bar_h + 3 * s;
    // Swatch for 0.
    img.fill(pad, pad, pad + swatch, pad + bar_h, [0; 3]);
    draw_text(
        &mut img,
        pad + (swatch - text_width("0", s)) / 2,
        label_y,
        "0",
        s,
        INK,
    );
    // Colour bar over [x0, x1].
    let x0 = pad + swatch + 4 * s;
    // The bar ends half a top label short of the right edge, so that label sits centred.
    let x1 = width.saturating_sub(pad + 1 + text_width("1024+", s) / 2);
    if x1 <= x0 + 2 {
        return img;
    }
    let span = (x1 - x0) as f64;
    for x in x0..=x1 {
        let level = ((x - x0) as f64 / span * (LEVELS - 1) as f64).round() as u32;
        img.fill(x, pad, x + 1, pad + bar_h, level_colour(level));
    }
    // Ticks, and labels where they fit: the first and last always, an inner one when it clears
    // its drawn neighbour and the last label.
    let ticks: [(u64, &str); 6] = [
        (1, "1"),
        (4, "4"),
        (16, "16"),
        (64, "64"),
        (256, "256"),
        (HEAT_MAX, "1024+"),
    ];
    let place = |v: u64, label: &str| {
        let t = (v as f64).log2() / (HEAT_MAX as f64).log2();
        let x = x0 + (t * span).round() as u32;
        let tw = text_width(label, s);
        (
            x,
            x.saturating_sub(tw / 2).min(width.saturating_sub(tw)),
            tw,
        )
    };
    let (_, last_x, _) = place(HEAT_MAX, "1024+");
    let mut free_from = 0;
    for (k, (v, label)) in ticks.iter().enumerate() {
        let (x, lx, tw) = place(*v, label);
        img.fill(x, pad + bar_h, x + s, pad + bar_h + 2 * s, INK);
        let last = k == ticks.len() - 1;
        if k == 0 || last || (lx >= free_from && lx + tw + 2 * s <= last_x) {
            draw_text(&mut img, lx, label_y, label, s, INK);
            free_from = lx + tw + 2 * s;
        }
    }
    debug_assert!(label_y + text_height(s) <= img.height());
    img
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_is_monotone_fixed_and_clamped() {
        assert_eq!(heat_colour(0), [0; 3]);
        assert_eq!(heat_colour(1), level_colour(0));
        assert_eq!(heat_colour(32), level_colour(128)); // 2^5: the middle
        assert_eq!(heat_colour(HEAT_MAX), level_colour(255));
        assert_eq!(heat_colour(u64::MAX), level_colour(255));
        // Turbo runs from blue to red: blue dominates the bottom, red the top.
        let lo = level_colour(0);
        let hi = level_colour(255);
        assert!(lo[2] > lo[0] && hi[0] > hi[2], "{lo:?} {hi:?}");
        // Distinct from 0 (black) at every level.
        assert!((0..LEVELS).all(|l| level_colour(l) != [0; 3]));
    }

    #[test]
    fn image_is_costs_then_legend_at_every_width() {
        let empty = heatmap_image(&[], 0, 0);
        assert_eq!(empty.height(), legend_height(0));
        for w in [1u32, 5, 40, 64, 100, 256, 600] {
            let h = 3;
            let costs: Vec<u64> = (0..(w * h) as u64).map(|k| k * 7).collect();
            let img = heatmap_image(&costs, w, h);
            assert_eq!(img.height(), h + legend_height(w));
            for j in 0..h {
                for i in 0..w {
                    let v = costs[(j * w + i) as usize];
                    assert_eq!(img.pixel(i, j), heat_colour(v));
                }
            }
        }
    }

    #[test]
    fn kinds_parse() {
        assert_eq!("nodes".parse::<HeatmapKind>(), Ok(HeatmapKind::Nodes));
        assert!(
            "cost"
                .parse::<HeatmapKind>()
                .unwrap_err()
                .contains("tests or nodes")
        );
    }
}
