//! Keyframed rigid transforms of scene-file objects: a [`Track`] of keys (a time, a rotation, a
//! translation) turned into the object's rigid pose at any time `t` in `[0, 1]`, and the
//! [`KeyframedObject`]s a scene remembers (which primitives each keyframed entry produced).
//!
//! A pose is applied after the entry's static placement: the rotation turns the placed object
//! about its pivot (the entry's `translate`, else the origin), then the translation moves it.
//! Between two keys the translation is interpolated linearly and the rotation by slerp (the
//! shorter way round); before the first key the first pose holds, after the last the last. At a
//! key's own time the pose is that key's, exactly (no interpolation rounding).

use super::transform::{Transform, TransformError};
use glam::{DMat3, DQuat, DVec3};
use std::ops::Range;

/// One key: the rigid pose at time `t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Key {
    /// In `[0, 1]`, in `f32` like the frames' times, so a key at `0.3` is met exactly by a
    /// frame at `0.3`.
    pub t: f32,
    /// A unit quaternion: the turn about the pivot.
    pub rotation: DQuat,
    /// Added after the turn, in scene units.
    pub translate: DVec3,
}

/// What is wrong with one key; the message says what to fix.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KeyProblem {
    #[error("t = {0} is invalid: it must be a finite number from 0 to 1")]
    Time(f64),
    #[error(
        "t = {t} is not after the previous key's t = {previous}: the keys' times must increase strictly"
    )]
    NotIncreasing { t: f32, previous: f32 },
    #[error(transparent)]
    Transform(#[from] TransformError),
}

/// Why a list of keys is not a track.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KeyframeError {
    #[error(
        "keyframes = [] has no key: give at least one, like {{ t = 0, translate = [0, 0, 0] }}"
    )]
    Empty,
    /// `key` counts from 1.
    #[error("keyframe {key} of {count}: {problem}")]
    Key {
        key: usize,
        count: usize,
        problem: KeyProblem,
    },
    #[error(
        "keyframes on [[instance]] are not supported: instances stay where they are placed; \
         use a [[mesh]] or [[generator]] table for an object that moves"
    )]
    NotOnInstances,
}

impl Key {
    /// A checked key: `t` finite in `[0, 1]`, `rotate` (axis, degrees) with a finite non-zero
    /// axis of any length and a finite angle, a finite `translate`.
    pub fn new(
        t: f64,
        rotate: Option<([f64; 3], f64)>,
        translate: [f64; 3],
    ) -> Result<Key, KeyProblem> {
        if !(t.is_finite() && (0.0..=1.0).contains(&t)) {
            return Err(KeyProblem::Time(t));
        }
        Transform::new([1.0; 3], rotate, translate)?;
        let rotation = match rotate {
            None => DQuat::IDENTITY,
            Some((axis, degrees)) => {
                let axis = DVec3::from(axis)
                    .try_normalize()
                    .ok_or(TransformError::Axis(axis))?;
                DQuat::from_axis_angle(axis, degrees.to_radians())
            }
        };
        Ok(Key {
            t: t as f32,
            rotation,
            translate: DVec3::from(translate),
        })
    }
}

/// The keys of one object, times strictly increasing, with the pivot its rotations turn about.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    keys: Vec<Key>,
    pivot: DVec3,
}

impl Track {
    /// A track of at least one key, times strictly increasing (compared as `f32`). `keys` are
    /// the entry's keys in file order, each already checked ([`Key::new`]) or its problem.
    pub fn new(keys: Vec<Result<Key, KeyProblem>>, pivot: DVec3) -> Result<Track, KeyframeError> {
        let count = keys.len();
        if count == 0 {
            return Err(KeyframeError::Empty);
        }
        let mut checked: Vec<Key> = Vec::with_capacity(count);
        for (i, key) in keys.into_iter().enumerate() {
            let bad = |problem| KeyframeError::Key {
                key: i + 1,
                count,
                problem,
            };
            let key = key.map_err(bad)?;
            if let Some(previous) = checked.last().filter(|p| p.t >= key.t) {
                return Err(bad(KeyProblem::NotIncreasing {
                    t: key.t,
                    previous: previous.t,
                }));
            }
            checked.push(key);
        }
        Ok(Track {
            keys: checked,
            pivot,
        })
    }

    pub fn keys(&self) -> &[Key] {
        &self.keys
    }

    /// The rigid placement at time `t` (a NaN `t` holds the first key): the identity, bit for
    /// bit, when the pose is (no turn, no move).
    pub fn at(&self, t: f32) -> Transform {
        let after = self.keys.partition_point(|k| k.t <= t);
        let (rotation, translate) = match after {
            0 => self.pose(0),
            n if n == self.keys.len() => self.pose(n - 1),
            n if self.keys[n - 1].t == t => self.pose(n - 1),
            n => {
                let (a, b) = (&self.keys[n - 1], &self.keys[n]);
                let s = (f64::from(t) - f64::from(a.t)) / (f64::from(b.t) - f64::from(a.t));
                let rotation = a.rotation.slerp(b.rotation, s).normalize();
                (rotation, a.translate + (b.translate - a.translate) * s)
            }
        };
        let rotation = DMat3::from_quat(rotation);
        Transform {
            scale: DVec3::ONE,
            rotation,
            translate: self.pivot + translate - rotation * self.pivot,
        }
    }

    fn pose(&self, i: usize) -> (DQuat, DVec3) {
        (self.keys[i].rotation, self.keys[i].translate)
    }
}

/// A keyframed entry of a scene file and the primitives it produced, as ranges of each kind's
/// own list (`Scene::triangles`, `spheres`, `shapes`; a sphere's primitive id is the scene's
/// triangle count plus its index there, a shape's adds the sphere count too).
#[derive(Debug, Clone, PartialEq)]
pub struct KeyframedObject {
    /// The entry, for messages: `line 12, [[mesh]] path = "tri.obj"`.
    pub entry: String,
    pub triangles: Range<usize>,
    pub spheres: Range<usize>,
    pub shapes: Range<usize>,
    pub track: Track,
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3A;

    /// A key's `t`, rotation (axis, degrees) and translation.
    type KeyArgs = (f64, Option<([f64; 3], f64)>, [f64; 3]);

    fn track(keys: &[KeyArgs], pivot: DVec3) -> Track {
        let keys = keys.iter().map(|&(t, r, d)| Key::new(t, r, d)).collect();
        Track::new(keys, pivot).unwrap()
    }

    fn near(a: Vec3A, b: Vec3A) -> bool {
        (a - b).abs().max_element() < 1e-6
    }

    #[test]
    fn holds_interpolates_and_meets_the_keys_exactly() {
        let quarter = Some(([0.0, 2.0, 0.0], 90.0));
        let k = track(
            &[(0.25, None, [0.0; 3]), (0.75, quarter, [2.0, 0.0, 0.0])],
            DVec3::ZERO,
        );
        // Held before the first key (the identity, bit for bit) and after the last.
        assert!(k.at(0.0).is_identity() && k.at(0.25).is_identity());
        assert!(k.at(f32::NAN).is_identity());
        let end = Transform::new([1.0; 3], quarter, [2.0, 0.0, 0.0]).unwrap();
        assert!(near(k.at(1.0).point(Vec3A::X), end.point(Vec3A::X)));
        assert_eq!(k.at(1.0), k.at(0.75));
        // (1, 0, 0) turned a quarter about +y is (0, 0, -1), then moved by (2, 0, 0).
        assert!(near(k.at(0.75).point(Vec3A::X), Vec3A::new(2.0, 0.0, -1.0)));
        // Half way: half the move and half the turn (45 degrees).
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let mid = k.at(0.5).point(Vec3A::X);
        assert!(near(mid, Vec3A::new(1.0 + h, 0.0, -h)), "{mid}");
    }

    #[test]
    fn rotations_turn_about_the_pivot() {
        let pivot = DVec3::new(5.0, 0.0, 0.0);
        let k = track(&[(0.0, Some(([0.0, 0.0, 1.0], 180.0)), [0.0; 3])], pivot);
        let p = k.at(0.5).point(Vec3A::new(6.0, 0.0, 0.0));
        assert!(near(p, Vec3A::new(4.0, 0.0, 0.0)), "{p}");
        assert!(near(
            k.at(0.5).point(Vec3A::new(5.0, 0.0, 0.0)),
            Vec3A::X * 5.0
        ));
    }

    #[test]
    fn bad_keys_are_named() {
        let err = |keys: Vec<Result<Key, KeyProblem>>| Track::new(keys, DVec3::ZERO).unwrap_err();
        assert_eq!(err(vec![]), KeyframeError::Empty);
        for (t, says) in [
            (1.5, "t = 1.5 is invalid"),
            (f64::NAN, "t = NaN is invalid"),
        ] {
            let e = err(vec![
                Key::new(0.0, None, [0.0; 3]),
                Key::new(t, None, [0.0; 3]),
            ]);
            assert!(e.to_string().starts_with("keyframe 2 of 2: "), "{e}");
            assert!(e.to_string().contains(says), "{e}");
        }
        let e = err(vec![
            Key::new(0.5, None, [0.0; 3]),
            Key::new(0.5, None, [0.0; 3]),
        ]);
        assert!(
            e.to_string()
                .contains("not after the previous key's t = 0.5"),
            "{e}"
        );
        let zero = Key::new(0.0, Some(([0.0; 3], 10.0)), [0.0; 3]).unwrap_err();
        assert!(zero.to_string().contains("rotation axis"), "{zero}");
        let tiny = Key::new(0.0, Some(([1e-320, 0.0, 0.0], 10.0)), [0.0; 3]);
        assert!(matches!(
            tiny,
            Err(KeyProblem::Transform(TransformError::Axis(_)))
        ));
        let inf = Key::new(0.0, None, [f64::INFINITY, 0.0, 0.0]).unwrap_err();
        assert!(inf.to_string().contains("translate"), "{inf}");
        let nan = Key::new(0.0, Some(([0.0, 1.0, 0.0], f64::NAN)), [0.0; 3]).unwrap_err();
        assert!(nan.to_string().contains("angle"), "{nan}");
    }
}
