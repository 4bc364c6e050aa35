//! The keys every object table of the scene format shares: `scale`, `rotate`, `translate` (the
//! object's transform), `material` and `keyframes`. Object tables are declared with
//! [`placed_entry!`], so the shared keys are written once and every table rejects unknown keys.

use crate::scene::Material;
use crate::scene::keyframes::{Key, KeyframeError, Track};
use crate::scene::transform::{Transform, TransformError};
use glam::DVec3;
use serde::Deserialize;

/// `scale = s` (uniform) or `scale = [sx, sy, sz]`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(untagged, expecting = "a number or an array [sx, sy, sz]")]
pub enum ScaleSpec {
    Uniform(f64),
    PerAxis([f64; 3]),
}

impl ScaleSpec {
    pub fn factors(self) -> [f64; 3] {
        match self {
            ScaleSpec::Uniform(s) => [s; 3],
            ScaleSpec::PerAxis(s) => s,
        }
    }
}

/// `rotate = { axis = [x, y, z], degrees = a }`: a right-handed rotation about `axis` through
/// the origin.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RotateSpec {
    pub axis: [f64; 3],
    pub degrees: f64,
}

/// One of `keyframes = [{ t = 0 }, { t = 1, translate = [x, y, z], rotate = { ... } }]`: the
/// rigid pose at time `t` (`0..=1`), after the static placement; `translate` and `rotate`
/// default to none.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeySpec {
    pub t: f64,
    pub translate: Option<[f64; 3]>,
    pub rotate: Option<RotateSpec>,
}

/// The track of a `keyframes` key (`None` when absent), its rotations about `pivot` (the
/// entry's `translate`, else the origin).
pub fn track(
    keyframes: Option<&[KeySpec]>,
    pivot: Option<[f64; 3]>,
) -> Result<Option<Track>, KeyframeError> {
    let Some(keys) = keyframes else {
        return Ok(None);
    };
    let keys = keys.iter().map(|k| {
        let rotate = k.rotate.map(|r| (r.axis, r.degrees));
        Key::new(k.t, rotate, k.translate.unwrap_or([0.0; 3]))
    });
    let pivot = DVec3::from(pivot.unwrap_or([0.0; 3]));
    Track::new(keys.collect(), pivot).map(Some)
}

/// An object's `material`: the name of a `[material.NAME]` table, or an inline table.
#[derive(Debug, Clone, Deserialize)]
#[serde(
    untagged,
    expecting = "a material name (from a [material.NAME] table) or an inline table like { color = [r, g, b], diffuse = 0.7 } with keys color, ambient, diffuse, specular, shininess, emission"
)]
pub enum MaterialRef {
    Named(String),
    Inline(Material),
}

/// An object table with the shared keys.
pub trait Placed {
    /// The transform of the `scale`, `rotate` and `translate` keys (identity when absent).
    fn transform(&self) -> Result<Transform, TransformError>;
    /// The `material` key.
    fn material_ref(&self) -> Option<&MaterialRef>;
    /// The `keyframes` key's track (`None` when absent), turning about the `translate` key.
    fn track(&self) -> Result<Option<Track>, KeyframeError>;
}

/// The transform of the `scale`, `rotate` and `translate` keys.
pub fn transform(
    scale: Option<ScaleSpec>,
    rotate: Option<RotateSpec>,
    translate: Option<[f64; 3]>,
) -> Result<Transform, TransformError> {
    Transform::new(
        scale.map_or([1.0; 3], ScaleSpec::factors),
        rotate.map(|r| (r.axis, r.degrees)),
        translate.unwrap_or([0.0; 3]),
    )
}

/// Declares an object table: its own keys as given, then the shared optional `scale`,
/// `rotate`, `translate`, `material` and `keyframes` keys; unknown keys rejected; implements
/// [`Placed`].
macro_rules! placed_entry {
    ($(#[$meta:meta])* $name:ident { $($(#[$fmeta:meta])* $field:ident: $ty:ty,)* }) => {
        $(#[$meta])*
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $($(#[$fmeta])* pub $field: $ty,)*
            pub scale: Option<$crate::scene::file::placed::ScaleSpec>,
            pub rotate: Option<$crate::scene::file::placed::RotateSpec>,
            pub translate: Option<[f64; 3]>,
            pub material: Option<$crate::scene::file::placed::MaterialRef>,
            pub keyframes: Option<Vec<$crate::scene::file::placed::KeySpec>>,
        }

        impl $crate::scene::file::placed::Placed for $name {
            fn transform(
                &self,
            ) -> Result<$crate::scene::transform::Transform, $crate::scene::transform::TransformError>
            {
                $crate::scene::file::placed::transform(self.scale, self.rotate, self.translate)
            }
            fn material_ref(&self) -> Option<&$crate::scene::file::placed::MaterialRef> {
                self.material.as_ref()
            }
            fn track(
                &self,
            ) -> Result<
                Option<$crate::scene::keyframes::Track>,
                $crate::scene::keyframes::KeyframeError,
            > {
                $crate::scene::file::placed::track(self.keyframes.as_deref(), self.translate)
            }
        }
    };
}
pub(crate) use placed_entry;
