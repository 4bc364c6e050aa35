//! Surface materials for shading (Phong coefficients, colour, emission) and the per-primitive
//! lookup by object ranges.

use glam::Vec3;
use serde::{Deserialize, Serialize};

/// A Phong material. Colours are linear RGB; `color` and the coefficients are usually in
/// `[0, 1]`, `emission` is added as is (it may exceed 1 for a bright surface).
///
/// Shading of a hit (see `render::shade`): `emission + ambient * color + sum over light samples
/// of visible * intensity * (diffuse * color * max(n.l, 0) + specular * max(r.v, 0)^shininess)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Material {
    /// Albedo (diffuse and ambient colour).
    pub color: Vec3,
    /// Ambient coefficient (the ambient light is white, intensity 1).
    pub ambient: f32,
    /// Diffuse (Lambert) coefficient.
    pub diffuse: f32,
    /// Specular coefficient (white highlights).
    pub specular: f32,
    /// Phong exponent.
    pub shininess: f32,
    /// Emitted radiance, added whatever the lights.
    pub emission: Vec3,
}

impl Material {
    /// The material of primitives that have none: light grey, slightly glossy.
    pub const DEFAULT: Material = Material {
        color: Vec3::new(0.8, 0.8, 0.8),
        ambient: 0.1,
        diffuse: 0.7,
        specular: 0.2,
        shininess: 32.0,
        emission: Vec3::ZERO,
    };

    /// Largest accepted Phong exponent.
    pub const MAX_SHININESS: f32 = 100_000.0;

    /// Checks that every value is finite and non-negative, and the exponent at most
    /// [`Material::MAX_SHININESS`]; the message says what to fix.
    pub fn validate(&self) -> Result<(), String> {
        let coefficients = [self.ambient, self.diffuse, self.specular, self.shininess];
        let ok = self.color.is_finite()
            && self.emission.is_finite()
            && self.color.min_element() >= 0.0
            && self.emission.min_element() >= 0.0
            && coefficients.iter().all(|c| c.is_finite() && *c >= 0.0)
            && self.shininess <= Material::MAX_SHININESS;
        if ok {
            Ok(())
        } else {
            Err(format!(
                "material {self:?} is invalid: color, emission, ambient, diffuse and specular must be finite and >= 0, shininess from 0 to {}",
                Material::MAX_SHININESS
            ))
        }
    }
}

impl Default for Material {
    fn default() -> Material {
        Material::DEFAULT
    }
}

/// A run of primitives of one kind, from `first` up to the next run, sharing a material
/// (`None`: [`Material::DEFAULT`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Run {
    first: u32,
    material: Option<u32>,
}

/// Materials per primitive, stored as one entry per object (a run of consecutive ids), so a
/// million-triangle mesh costs one entry and a lookup is a binary search over the objects.
///
/// Ids are per kind: triangle `i` is primitive `i`, sphere `i` is primitive `n_triangles + i`,
/// shape `i` is primitive `n_triangles + n_spheres + i`.
/// Primitives before the first run, and an empty map, use [`Material::DEFAULT`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MaterialMap {
    materials: Vec<Material>,
    triangle_runs: Vec<Run>,
    sphere_runs: Vec<Run>,
    shape_runs: Vec<Run>,
}

impl MaterialMap {
    /// Triangles from `first` on (until the next call) use `material`. Calls must come in
    /// increasing `first` order; a later call with the same `first` replaces the earlier one.
    pub fn start_triangles(&mut self, first: usize, material: Option<Material>) {
        let run = self.run(first, material);
        push_run(&mut self.triangle_runs, run);
    }

    /// Spheres from `first` on (until the next call) use `material`; as
    /// [`MaterialMap::start_triangles`].
    pub fn start_spheres(&mut self, first: usize, material: Option<Material>) {
        let run = self.run(first, material);
        push_run(&mut self.sphere_runs, run);
    }

    /// Shapes (boxes, polygons, cylinders, cones, ellipsoids) from `first` on (until the next
    /// call) use `material`; as [`MaterialMap::start_triangles`].
    pub fn start_shapes(&mut self, first: usize, material: Option<Material>) {
        let run = self.run(first, material);
        push_run(&mut self.shape_runs, run);
    }

    /// The material of triangle `i`.
    #[inline]
    pub fn triangle(&self, i: usize) -> &Material {
        self.lookup(&self.triangle_runs, i)
    }

    /// The material of sphere `i` (counted among spheres).
    #[inline]
    pub fn sphere(&self, i: usize) -> &Material {
        self.lookup(&self.sphere_runs, i)
    }

    /// The material of shape `i` (counted among shapes).
    #[inline]
    pub fn shape(&self, i: usize) -> &Material {
        self.lookup(&self.shape_runs, i)
    }

    /// The distinct materials given (the default not included).
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    fn run(&mut self, first: usize, material: Option<Material>) -> Run {
        let material = material.map(|m| match self.materials.iter().position(|x| *x == m) {
            Some(k) => k as u32,
            None => {
                self.materials.push(m);
                (self.materials.len() - 1) as u32
            }
        });
        Run {
            first: u32::try_from(first).unwrap_or(u32::MAX),
            material,
        }
    }

    fn lookup(&self, runs: &[Run], i: usize) -> &Material {
        let k = runs.partition_point(|r| r.first as usize <= i);
        match k.checked_sub(1).and_then(|k| runs[k].material) {
            Some(m) => &self.materials[m as usize],
            None => &Material::DEFAULT,
        }
    }
}

fn push_run(runs: &mut Vec<Run>, run: Run) {
    if let Some(last) = runs.last_mut()
        && last.first == run.first
    {
        *last = run;
        return;
    }
    debug_assert!(runs.last().is_none_or(|l| l.first < run.first));
    runs.push(run);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_map_ids_to_materials() {
        let red = Material {
            color: Vec3::X,
            ..Material::DEFAULT
        };
        let blue = Material {
            color: Vec3::Z,
            ..Material::DEFAULT
        };
        let mut m = MaterialMap::default();
        assert_eq!(*m.triangle(5), Material::DEFAULT);
        m.start_triangles(0, Some(red));
        m.start_triangles(10, None);
        m.start_triangles(20, Some(blue));
        m.start_triangles(20, Some(red)); // an empty object is replaced
        m.start_spheres(3, Some(blue));
        m.start_shapes(1, Some(red));
        assert_eq!(*m.triangle(0), red);
        assert_eq!(*m.triangle(9), red);
        assert_eq!(*m.triangle(10), Material::DEFAULT);
        assert_eq!(*m.triangle(1_000_000), red);
        assert_eq!(*m.sphere(2), Material::DEFAULT);
        assert_eq!(*m.sphere(3), blue);
        assert_eq!(*m.shape(0), Material::DEFAULT);
        assert_eq!(*m.shape(1), red);
        assert_eq!(*m.shape(7), red);
        assert_eq!(m.materials().len(), 2, "equal materials are stored once");
    }

    #[test]
    fn validation_rejects_negative_and_nan() {
        assert!(Material::DEFAULT.validate().is_ok());
        let bad = [
            Material {
                diffuse: -0.1,
                ..Material::DEFAULT
            },
            Material {
                color: Vec3::new(f32::NAN, 0.0, 0.0),
                ..Material::DEFAULT
            },
            Material {
                shininess: 1e9,
                ..Material::DEFAULT
            },
        ];
        for m in bad {
            assert!(m.validate().is_err(), "{m:?}");
        }
    }
}
