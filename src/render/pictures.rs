//! The pictures a report adds per scene: one shaded render and the heat maps of each index,
//! written as PNG files with names that sort by scene, index and kind.

use super::{HeatmapKind, RenderError, RenderOptions, render_heatmap, render_shaded};
use crate::index::TraceIndex;
use crate::scene::Scene;
use std::path::{Path, PathBuf};

/// A written picture and what it shows.
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    pub path: PathBuf,
    /// `shaded`, or the heat map's index and kind (`bvh tests`).
    pub caption: String,
}

/// Writes into `dir` (which must exist) `<scene>_shaded.png`, rendered through `indices[0]`
/// (the image is the same through any index, so pass a fast one first), and
/// `<scene>_<index>_<kind>.png` for every index and [`HeatmapKind`]. Names keep ASCII letters,
/// digits, `-` and `.`; anything else becomes `_` (`stadium:n=1000` gives `stadium_n_1000`).
/// Returns the pictures in that order; nothing for an empty `indices`.
pub fn write_scene_pictures(
    scene: &Scene,
    indices: &[&dyn TraceIndex],
    dir: &Path,
    opts: &RenderOptions,
) -> Result<Vec<Picture>, RenderError> {
    let Some(first) = indices.first() else {
        return Ok(Vec::new());
    };
    let stem = file_safe(&scene.name);
    let path = dir.join(format!("{stem}_shaded.png"));
    render_shaded(scene, *first, opts)?.write_png(&path)?;
    let mut out = vec![Picture {
        path,
        caption: "shaded".to_owned(),
    }];
    for index in indices {
        for kind in HeatmapKind::ALL {
            let name = file_safe(index.name());
            let path = dir.join(format!("{stem}_{name}_{kind}.png"));
            render_heatmap(scene, *index, opts, kind)?.write_png(&path)?;
            out.push(Picture {
                path,
                caption: format!("{} {kind}", index.name()),
            });
        }
    }
    Ok(out)
}

fn file_safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '.' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::TriangleKernelKind;
    use crate::index::{IndexSpec, build_index};

    #[test]
    fn writes_one_render_and_two_heat_maps_per_index() {
        let scene = crate::scene::load_scene("icosphere:n=80").unwrap();
        let idx = build_index(
            &IndexSpec::named("brute"),
            &scene.geometry(),
            TriangleKernelKind::Watertight,
        )
        .unwrap();
        let dir = tempfile::tempdir().unwrap();
        let opts = RenderOptions::new(8, 8);
        let pics = write_scene_pictures(&scene, &[idx.as_ref()], dir.path(), &opts).unwrap();
        let names: Vec<String> = pics
            .iter()
            .map(|p| p.path.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            names,
            [
                "icosphere_n_80_seed_1_shaded.png",
                "icosphere_n_80_seed_1_brute_tests.png",
                "icosphere_n_80_seed_1_brute_nodes.png"
            ]
        );
        assert!(pics.iter().all(|p| p.path.exists()));
        assert_eq!(pics[1].caption, "brute tests");
        assert!(
            write_scene_pictures(&scene, &[], dir.path(), &opts)
                .unwrap()
                .is_empty()
        );
    }
}
