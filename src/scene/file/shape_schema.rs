//! `[[shape]]` tables of the scene format: one primitive of the kinds in
//! [`crate::geometry::shapes`], chosen by `kind`, given in its own coordinates and placed by the
//! same `scale`, `rotate`, `translate` keys as `[[mesh]]`, with the same optional `material` key
//! as every other object. Unknown keys are rejected.
//!
//! ```toml
//! [[shape]]
//! kind = "box"                         # axis-aligned before the transform
//! center = [0, 0, 0]
//! half_extents = [0.5, 0.2, 0.1]
//! rotate = { axis = [0, 1, 0], degrees = 30 }
//!
//! [[shape]]
//! kind = "convex_polygon"              # or "concave_polygon"; planar, in order
//! vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
//!
//! [[shape]]
//! kind = "cylinder"                    # capped; uniform scale only
//! base = [0, 0, 0]
//! top = [0, 1, 0]
//! radius = 0.2
//!
//! [[shape]]
//! kind = "cone"                        # capped at the base; uniform scale only
//! base = [0, 0, 0]
//! apex = [0, 1, 0]
//! radius = 0.3
//!
//! [[shape]]
//! kind = "ellipsoid"                   # axis-aligned radii before the transform
//! center = [0, 0, 0]
//! radii = [0.3, 0.2, 0.1]
//! scale = 2
//! material = "red"                     # any kind: a [material.NAME] or an inline table
//! ```

use super::placed::{Placed, placed_entry};
use crate::geometry::shapes::{Cone, Cylinder, Ellipsoid, Obb, Polygon};
use crate::geometry::{Shape, ShapeError};
use glam::{Mat3A, Vec3A};
use serde::Deserialize;

/// `[[shape]]`: one primitive, by `kind`.
#[derive(Debug, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ShapeEntry {
    Box(BoxEntry),
    ConvexPolygon(PolygonEntry),
    ConcavePolygon(PolygonEntry),
    Cylinder(CylinderEntry),
    Cone(ConeEntry),
    Ellipsoid(EllipsoidEntry),
}

placed_entry! {
    BoxEntry {
        center: [f32; 3],
        half_extents: [f32; 3],
    }
}

placed_entry! {
    PolygonEntry {
        vertices: Vec<[f32; 3]>,
    }
}

placed_entry! {
    CylinderEntry {
        base: [f32; 3],
        top: [f32; 3],
        #[serde(deserialize_with = "super::schema::f32_in_range")]
        radius: f32,
    }
}

placed_entry! {
    ConeEntry {
        base: [f32; 3],
        apex: [f32; 3],
        #[serde(deserialize_with = "super::schema::f32_in_range")]
        radius: f32,
    }
}

placed_entry! {
    EllipsoidEntry {
        center: [f32; 3],
        radii: [f32; 3],
    }
}

impl ShapeEntry {
    /// The `kind` as written in the file.
    pub fn kind(&self) -> &'static str {
        match self {
            ShapeEntry::Box(_) => "box",
            ShapeEntry::ConvexPolygon(_) => "convex_polygon",
            ShapeEntry::ConcavePolygon(_) => "concave_polygon",
            ShapeEntry::Cylinder(_) => "cylinder",
            ShapeEntry::Cone(_) => "cone",
            ShapeEntry::Ellipsoid(_) => "ellipsoid",
        }
    }

    /// The shape in its own coordinates (before the transform), validated.
    pub fn local_shape(&self) -> Result<Shape, ShapeError> {
        let v = |a: [f32; 3]| Vec3A::from(a);
        Ok(match self {
            ShapeEntry::Box(b) => {
                Shape::Box(Obb::new(v(b.center), v(b.half_extents), Mat3A::IDENTITY)?)
            }
            ShapeEntry::ConvexPolygon(p) => {
                Shape::ConvexPolygon(Polygon::convex(p.vertices.iter().map(|&a| v(a)).collect())?)
            }
            ShapeEntry::ConcavePolygon(p) => {
                Shape::ConcavePolygon(Polygon::new(p.vertices.iter().map(|&a| v(a)).collect())?)
            }
            ShapeEntry::Cylinder(c) => {
                Shape::Cylinder(Cylinder::new(v(c.base), v(c.top), c.radius)?)
            }
            ShapeEntry::Cone(c) => Shape::Cone(Cone::new(v(c.base), v(c.apex), c.radius)?),
            ShapeEntry::Ellipsoid(e) => {
                Shape::Ellipsoid(Ellipsoid::new(v(e.center), v(e.radii), Mat3A::IDENTITY)?)
            }
        })
    }

    /// The entry's shared keys (transform and material).
    pub fn placed(&self) -> &dyn Placed {
        match self {
            ShapeEntry::Box(e) => e,
            ShapeEntry::ConvexPolygon(e) | ShapeEntry::ConcavePolygon(e) => e,
            ShapeEntry::Cylinder(e) => e,
            ShapeEntry::Cone(e) => e,
            ShapeEntry::Ellipsoid(e) => e,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::geometry::{Ray, Shape};
    use crate::scene::Material;
    use crate::scene::file::tests::load;
    use glam::{Vec3, Vec3A};

    /// One shape of every kind (the box by the material name, the cone with its own), a sphere
    /// and the shapes generator (by name).
    const ALL_KINDS: &str = r#"
[material.gold]
color = [1, 0.8, 0.1]
specular = 0.9
[[shape]]
kind = "box"
center = [1, 0, 0]
half_extents = [1, 1, 1]
scale = [2, 3, 4]
rotate = { axis = [0, 0, 1], degrees = 90 }
translate = [0, 0, 1]
material = "gold"
[[sphere]]
center = [0, 0, 9]
radius = 1
[[shape]]
kind = "convex_polygon"
vertices = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
translate = [0, 0, -5]
[[shape]]
kind = "concave_polygon"
vertices = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]]
[[shape]]
kind = "cylinder"
base = [0, 0, 0]
top = [0, 1, 0]
radius = 0.5
scale = 2
[[shape]]
kind = "cone"
base = [0, 0, 0]
apex = [0, 1, 0]
radius = 0.5
material = { color = [0, 0, 1], emission = [0.2, 0.2, 0.2] }
[[shape]]
kind = "ellipsoid"
center = [0, 0, 0]
radii = [1, 2, 3]
scale = [1, 1, 2]
[[generator]]
name = "shapes"
n = 16
translate = [10, 0, 0]
material = "gold"
"#;

    #[test]
    fn every_kind_in_file_order_with_transforms() {
        let s = load(ALL_KINDS).unwrap();
        let kinds: Vec<_> = s.shapes.iter().map(Shape::kind).collect();
        assert_eq!(
            kinds[..6],
            [
                "box",
                "convex_polygon",
                "concave_polygon",
                "cylinder",
                "cone",
                "ellipsoid"
            ]
        );
        // The generator's shapes follow, moved by its transform.
        let g = crate::scene::generators::generate("shapes", 16, 1).unwrap();
        assert_eq!(s.shapes.len(), 6 + g.shapes.len());
        assert_eq!(s.spheres.len(), 1 + g.spheres.len());
        assert!(
            (s.shapes[6].bounds().center()
                - g.shapes[0].bounds().center()
                - Vec3A::new(10.0, 0.0, 0.0))
            .length()
                < 1e-5
        );
        // The box: scaled to half-extents (2, 3, 4), turned, centred at (0, 2, 1).
        let down = Ray::infinite(Vec3::new(0.0, 2.0, 9.0), Vec3::NEG_Z).unwrap();
        let t = s.shapes[0].intersect(&down, f32::INFINITY).unwrap();
        assert!((t - 4.0).abs() < 1e-5, "{t}");
        // The cylinder is twice as tall: a ray along +x at y = 1.9 hits its side at x = -1.
        let across = Ray::infinite(Vec3::new(-5.0, 1.9, 0.0), Vec3::X).unwrap();
        assert!((s.shapes[3].intersect(&across, f32::INFINITY).unwrap() - 4.0).abs() < 1e-5);
        // The ellipsoid's z radius is 6 after the scale.
        let bz = s.shapes[5].bounds();
        assert!((bz.max.z - 6.0).abs() < 1e-4, "{bz:?}");
    }

    #[test]
    fn shapes_take_materials_by_name_or_inline() {
        let s = load(ALL_KINDS).unwrap();
        let gold = Material {
            color: glam::Vec3::new(1.0, 0.8, 0.1),
            specular: 0.9,
            ..Material::DEFAULT
        };
        // Ids: the generator's triangles, the sphere, the generator's spheres, then the shapes
        // in file order (box, polygons, cylinder, cone, ellipsoid) and the generator's.
        let first_shape = (s.triangles.len() + s.spheres.len()) as u32;
        let sphere = s.triangles.len() as u32;
        assert_eq!(
            *s.material(sphere),
            Material::DEFAULT,
            "the sphere has none"
        );
        assert_eq!(*s.material(0), gold, "the generator's triangles");
        assert_eq!(*s.material(first_shape), gold);
        assert_eq!(*s.material(first_shape + 1), Material::DEFAULT);
        let cone = s.material(first_shape + 4);
        assert_eq!(cone.color, glam::Vec3::Z);
        assert_eq!(cone.emission, glam::Vec3::splat(0.2));
        // The generator's shapes (after the six of the file) take its material.
        assert!(s.shapes.len() > 6);
        assert_eq!(*s.material(s.len() as u32 - 1), gold);
        // An undefined name is an error naming the table.
        let e = load("[[shape]]\nkind = \"box\"\ncenter = [0,0,0]\nhalf_extents = [1,1,1]\nmaterial = \"tin\"\n")
            .expect_err("undefined material");
        assert!(e.to_string().contains("[material.tin]"), "{e}");
    }

    #[test]
    fn bad_shapes_name_what_to_fix() {
        for (toml, expect) in [
            ("[[shape]]\nkind = \"torus\"\n", "unknown variant `torus`"),
            (
                "[[shape]]\nkind = \"cone\"\nbase = [0,0,0]\napex = [0,1,0]\nradius = 1\ncolour = 2\n",
                "unknown field `colour`",
            ),
            (
                "[[shape]]\nkind = \"cone\"\nbase = [0,0,0]\napex = [0,0,0]\nradius = 1\n",
                "distinct end points",
            ),
            (
                "[[shape]]\nkind = \"cylinder\"\nbase = [0,0,0]\ntop = [0,1,0]\nradius = 1\nscale = [1,2,1]\n",
                "not uniform",
            ),
            (
                "[[shape]]\nkind = \"box\"\ncenter = [0,0,0]\nhalf_extents = [1,0,1]\n",
                "half-extent",
            ),
            (
                "[[shape]]\nkind = \"convex_polygon\"\nvertices = [[0,0,0],[2,0,0],[2,1,0],[1,1,0],[1,2,0],[0,2,0]]\n",
                "not convex",
            ),
            (
                "\n[[shape]]\nkind = \"concave_polygon\"\nvertices = [[0,0,0],[1,0,0],[1,1,1],[0,1,0]]\n",
                "line 2, [[shape]] kind = \"concave_polygon\"",
            ),
            (
                "[[shape]]\nkind = \"ellipsoid\"\ncenter = [0,0,0]\nradii = [1,1,1]\nscale = 0\n",
                "non-zero",
            ),
        ] {
            let e = load(toml).expect_err(toml);
            let msg = e.to_string();
            assert!(msg.contains(expect), "expected '{expect}' in: {msg}");
        }
    }
}
