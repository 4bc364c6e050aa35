//! Motion specs on the command line: `twist`, `twist:turns=0.5`, `wave:amplitude=0.02,waves=2`,
//! `keyframes` (a scene file's own keys).

use super::cloth::Cloth;
use super::keyframed::keyframed_geometry;
use super::twist::Twist;
use super::wave::Wave;
use super::{Motion, frame_geometry};
use crate::scene::{Scene, SceneGeometry};
use std::fmt;
use std::str::FromStr;

/// A motion by name with its parameters ([`MotionSpec::from_str`] parses and checks them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MotionSpec {
    Twist(Twist),
    Wave(Wave),
    Cloth(Cloth),
    /// The scene's keyframed entries ([`Scene::keyframed`]) move by their keys.
    Keyframes,
}

/// The deformations, with their parameters and defaults, for messages (`keyframes` besides).
const DEFORMATIONS: &str =
    "twist[:turns=0.25], wave[:amplitude=0.02,waves=2], cloth[:drop=0.5,ball=0.3]";

impl MotionSpec {
    /// The motion `animate` uses on `scene` when `asked` for one (`None`: not asked):
    /// `keyframes` by default when the scene has keyframes, else `twist`; an error when
    /// `keyframes` is asked of a scene without any.
    pub fn for_scene(asked: Option<MotionSpec>, scene: &Scene) -> Result<MotionSpec, String> {
        let keyed = !scene.keyframed.is_empty();
        match asked {
            Some(MotionSpec::Keyframes) if !keyed => Err(format!(
                "--motion keyframes: scene '{}' has no keyframes; give a scene file whose \
                 [[mesh]], [[generator]], [[sphere]] or [[shape]] tables have a keyframes key, \
                 or choose one of {DEFORMATIONS}",
                scene.name
            )),
            Some(spec) => Ok(spec),
            None if keyed => Ok(MotionSpec::Keyframes),
            None => "twist".parse(),
        }
    }

    /// The primitives of `scene` at time `t` (`0..=1`) under this motion; an error only where
    /// a keyframed shape cannot be placed ([`keyframed_geometry`]).
    pub fn frame(&self, scene: &Scene, t: f32) -> Result<SceneGeometry, String> {
        let motion: &dyn Motion = match self {
            MotionSpec::Twist(m) => m,
            MotionSpec::Wave(m) => m,
            MotionSpec::Cloth(m) => m,
            MotionSpec::Keyframes => return keyframed_geometry(scene, t),
        };
        Ok(frame_geometry(scene, motion, t))
    }
}

impl fmt::Display for MotionSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MotionSpec::Twist(m) => write!(f, "twist:turns={}", m.turns),
            MotionSpec::Wave(m) => write!(f, "wave:amplitude={},waves={}", m.amplitude, m.waves),
            MotionSpec::Cloth(m) => write!(f, "cloth:drop={},ball={}", m.drop, m.ball),
            MotionSpec::Keyframes => write!(f, "keyframes"),
        }
    }
}

impl FromStr for MotionSpec {
    type Err = String;

    /// `NAME` or `NAME:key=value,...`; every value a finite number in its range, every key
    /// known and given once.
    fn from_str(s: &str) -> Result<MotionSpec, String> {
        let (name, rest) = s.split_once(':').unwrap_or((s, ""));
        let (keys, limits): (&[&str], &[(f32, f32)]) = match name.trim() {
            "twist" => (&["turns"], &[(-16.0, 16.0)]),
            "wave" => (&["amplitude", "waves"], &[(0.0, 1.0), (0.0, 64.0)]),
            "cloth" => (&["drop", "ball"], &[(0.0, 4.0), (0.0, 1.0)]),
            "keyframes" => (&[], &[]),
            other => {
                return Err(format!(
                    "unknown motion '{other}': choose one of {DEFORMATIONS}, keyframes"
                ));
            }
        };
        let mut values: Vec<Option<f32>> = vec![None; keys.len()];
        for item in rest.split(',').map(str::trim).filter(|i| !i.is_empty()) {
            let (k, v) = item
                .split_once('=')
                .ok_or_else(|| format!("'{item}' in motion '{s}' is not key=value"))?;
            let k = k.trim();
            let at = keys.iter().position(|&key| key == k).ok_or_else(|| {
                let takes = match keys.is_empty() {
                    true => "none".to_owned(),
                    false => keys.join(", "),
                };
                format!("motion '{name}' has no parameter '{k}': it takes {takes}")
            })?;
            if values[at].is_some() {
                return Err(format!(
                    "'{k}' is given twice in motion '{s}': give it once"
                ));
            }
            let (lo, hi) = limits[at];
            let x = v
                .trim()
                .parse::<f32>()
                .ok()
                .filter(|x| x.is_finite() && (lo..=hi).contains(x))
                .ok_or_else(|| {
                    format!(
                        "{k} = '{}' in motion '{s}': use a number from {lo} to {hi}",
                        v.trim()
                    )
                })?;
            values[at] = Some(x);
        }
        Ok(match name.trim() {
            "twist" => MotionSpec::Twist(Twist {
                turns: values[0].unwrap_or(0.25),
            }),
            "wave" => MotionSpec::Wave(Wave {
                amplitude: values[0].unwrap_or(0.02),
                waves: values[1].unwrap_or(2.0),
            }),
            "cloth" => MotionSpec::Cloth(Cloth {
                drop: values[0].unwrap_or(0.5),
                ball: values[1].unwrap_or(0.3),
            }),
            _ => MotionSpec::Keyframes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_defaults_parameters_and_refuses_bad_ones() {
        let twist = MotionSpec::Twist(Twist { turns: 0.25 });
        let wave = MotionSpec::Wave(Wave {
            amplitude: 0.1,
            waves: 3.0,
        });
        let cloth = MotionSpec::Cloth(Cloth {
            drop: 0.5,
            ball: 0.25,
        });
        for (text, spec) in [
            ("twist", twist),
            ("wave:waves=3, amplitude=0.1", wave),
            ("cloth:ball=0.25", cloth),
            ("keyframes", MotionSpec::Keyframes),
        ] {
            let parsed: MotionSpec = text.parse().unwrap();
            assert_eq!(parsed, spec, "{text}");
            assert_eq!(parsed.to_string().parse::<MotionSpec>().unwrap(), parsed);
        }
        for (bad, says) in [
            ("spin", "unknown motion 'spin'"),
            ("twist:angle=3", "has no parameter 'angle'"),
            ("twist:turns", "is not key=value"),
            ("twist:turns=1,turns=2", "given twice"),
            ("twist:turns=nan", "use a number from"),
            ("wave:amplitude=2", "use a number from 0 to 1"),
            ("cloth:drop=5", "use a number from 0 to 4"),
            (
                "keyframes:speed=2",
                "has no parameter 'speed': it takes none",
            ),
        ] {
            let e = bad.parse::<MotionSpec>().unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn keyframes_are_the_default_for_a_scene_with_keys_and_refused_without() {
        use crate::scene::keyframes::{Key, KeyframedObject, Track};
        let plain = Scene {
            name: "plain".into(),
            ..Scene::default()
        };
        let twist = MotionSpec::Twist(Twist { turns: 0.25 });
        assert_eq!(MotionSpec::for_scene(None, &plain), Ok(twist));
        let e = MotionSpec::for_scene(Some(MotionSpec::Keyframes), &plain).unwrap_err();
        assert!(e.contains("scene 'plain' has no keyframes"), "{e}");
        let track = Track::new(vec![Key::new(0.0, None, [0.0; 3])], glam::DVec3::ZERO).unwrap();
        let keyed = Scene {
            keyframed: vec![KeyframedObject {
                entry: String::new(),
                triangles: 0..0,
                spheres: 0..0,
                shapes: 0..0,
                track,
            }],
            ..Scene::default()
        };
        let keys = MotionSpec::Keyframes;
        assert_eq!(MotionSpec::for_scene(None, &keyed), Ok(keys));
        assert_eq!(MotionSpec::for_scene(Some(twist), &keyed), Ok(twist));
    }
}
