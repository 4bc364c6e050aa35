//! The header of a PLY file (Turk's format as Stanford's tools write it): the encoding, the
//! elements in file order with their properties, and the role each element plays for the
//! loader (vertices, faces, triangle strips, or skipped).

use crate::scene::error::Location;

/// The most bytes a header may take (up to and including its `end_header` line).
pub const MAX_HEADER: usize = 1 << 20;

/// What is wrong where: a malformed file, or a vertex coordinate that is NaN or infinite.
#[derive(Debug)]
pub enum Problem {
    Malformed(String),
    NonFinite(String),
}

/// A problem at a location of the file.
pub type Fail = (Location, Problem);

/// `Err` of a malformed file at `at`.
pub fn malformed<T>(at: Location, message: String) -> Result<T, Fail> {
    Err((at, Problem::Malformed(message)))
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

/// A scalar property type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// Both spellings of the format (`uchar` and `uint8`, ...).
    fn named(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Bytes in binary encodings.
    pub fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The value at the start of `b` (at least [`Scalar::size`] bytes), big- or little-endian.
    /// Every integer type is exact in `f64`; a `float` widens exactly.
    #[inline]
    pub fn read(self, b: &[u8], big: bool) -> f64 {
        macro_rules! get {
            ($t:ty, $n:literal) => {{
                let a: [u8; $n] = b[..$n].try_into().expect("checked length");
                (if big {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }) as f64
            }};
        }
        match self {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => get!(i16, 2),
            Scalar::U16 => get!(u16, 2),
            Scalar::I32 => get!(i32, 4),
            Scalar::U32 => get!(u32, 4),
            Scalar::F32 => get!(f32, 4),
            Scalar::F64 => get!(f64, 8),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Scalar(Scalar),
    /// A list: its length as `count`, then that many `item`s.
    List {
        count: Scalar,
        item: Scalar,
    },
}

#[derive(Debug, Clone)]
pub struct Property {
    pub name: String,
    pub kind: Kind,
}

/// What the loader does with an element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// `vertex`: the indices of its `x`, `y`, `z` properties.
    Vertex([usize; 3]),
    /// `face`: the index of its `vertex_indices` (or `vertex_index`) list.
    Faces(usize),
    /// `tristrips`: the index of its `vertex_indices` list (runs ended by -1).
    Strips(usize),
    Skipped,
}

#[derive(Debug, Clone)]
pub struct Element {
    pub name: String,
    /// Records the header declares.
    pub count: u64,
    pub properties: Vec<Property>,
    pub role: Role,
    /// The header line of its `element` statement.
    pub line: usize,
}

impl Element {
    /// Bytes of one record in a binary encoding when every property is a scalar.
    pub fn fixed_size(&self) -> Option<usize> {
        self.properties
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(s) => Some(s.size()),
                Kind::List { .. } => None,
            })
            .sum()
    }
}

#[derive(Debug, Clone)]
pub struct Header {
    pub encoding: Encoding,
    pub elements: Vec<Element>,
    /// Byte offset of the body (just after the `end_header` line).
    pub body: usize,
    /// Lines of the header (the body's first line is `lines + 1`).
    pub lines: usize,
    /// Vertices the header declares.
    pub vertices: u64,
}

/// Parses the header at the start of `bytes`. Errors name the header line and what to fix.
pub fn parse(bytes: &[u8]) -> Result<Header, Fail> {
    let head = &bytes[..bytes.len().min(MAX_HEADER)];
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut pos = 0;
    let mut n = 0;
    loop {
        n += 1;
        let at = Location::Line(n);
        let Some(len) = head[pos..].iter().position(|&b| b == b'\n') else {
            let message = if n == 1 {
                "this is not a PLY file: it does not start with a line 'ply'".to_owned()
            } else {
                format!(
                    "the header has no 'end_header' line within its first {} bytes; complete the header (or the file is truncated)",
                    head.len()
                )
            };
            return malformed(at, message);
        };
        let line = String::from_utf8_lossy(&head[pos..pos + len]);
        pos += len + 1;
        let words: Vec<&str> = line.split_ascii_whitespace().collect();
        if n == 1 {
            if words != ["ply"] {
                return malformed(
                    at,
                    "this is not a PLY file: it does not start with a line 'ply'".into(),
                );
            }
            continue;
        }
        match words.as_slice() {
            ["format", f, version] => {
                if !version.starts_with('1') {
                    return malformed(
                        at,
                        format!("PLY version {version} is not supported; 1.0 is"),
                    );
                }
                encoding = Some(match *f {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::LittleEndian,
                    "binary_big_endian" => Encoding::BigEndian,
                    _ => {
                        return malformed(
                            at,
                            format!(
                                "unknown format '{f}': give ascii, binary_little_endian or binary_big_endian"
                            ),
                        );
                    }
                });
            }
            ["comment", ..] | ["obj_info", ..] | [] => {}
            ["element", name, count] => {
                let count = count.parse::<u64>().map_err(|_| {
                    let m = format!(
                        "element '{name}' has count '{count}', which is not a number of records"
                    );
                    (at.clone(), Problem::Malformed(m))
                })?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                    role: Role::Skipped,
                    line: n,
                });
            }
            ["property", rest @ ..] => {
                let Some(e) = elements.last_mut() else {
                    return malformed(
                        at,
                        "a property before any element; put an 'element' line first".into(),
                    );
                };
                e.properties
                    .push(property(rest).map_err(|m| (at.clone(), Problem::Malformed(m)))?);
            }
            ["end_header"] => break,
            _ => {
                return malformed(
                    at,
                    format!(
                        "'{}' is not a header statement (format, comment, obj_info, element, property, end_header)",
                        line.trim()
                    ),
                );
            }
        }
    }
    let Some(encoding) = encoding else {
        return malformed(
            Location::Line(2),
            "no 'format' line: add 'format binary_little_endian 1.0' (or ascii) after 'ply'".into(),
        );
    };
    let mut vertices = None;
    for e in &mut elements {
        e.role = role(e)?;
        if matches!(e.role, Role::Vertex(_)) {
            if vertices.is_some() {
                return malformed(
                    Location::Line(e.line),
                    "a second 'vertex' element; merge them into one".into(),
                );
            }
            vertices = Some(e.count);
        }
    }
    let Some(vertices) = vertices else {
        return malformed(
            Location::Line(n),
            "the header declares no 'vertex' element".into(),
        );
    };
    Ok(Header {
        encoding,
        elements,
        body: pos,
        lines: n,
        vertices,
    })
}

/// A `property` statement's words after `property`.
fn property(words: &[&str]) -> Result<Property, String> {
    let ty = |t: &str| {
        Scalar::named(t).ok_or_else(|| {
            format!("unknown property type '{t}': give char, uchar, short, ushort, int, uint, float or double")
        })
    };
    match words {
        ["list", count, item, name] => {
            let count = ty(count)?;
            if !count.is_integer() {
                return Err(format!(
                    "list '{name}' has a count of type {count:?}; a count is an integer type (uchar, int, ...)"
                ));
            }
            Ok(Property {
                name: name.to_string(),
                kind: Kind::List {
                    count,
                    item: ty(item)?,
                },
            })
        }
        [t, name] => Ok(Property {
            name: name.to_string(),
            kind: Kind::Scalar(ty(t)?),
        }),
        _ => Err(
            "a property is 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'"
                .into(),
        ),
    }
}

/// The role of element `e`, checking the properties the loader reads.
fn role(e: &Element) -> Result<Role, Fail> {
    let at = || Location::Line(e.line);
    let find = |names: &[&str]| {
        e.properties
            .iter()
            .position(|p| names.contains(&p.name.as_str()))
    };
    let list = |names: &[&str]| -> Result<usize, Fail> {
        let Some(i) = find(names) else {
            return malformed(
                at(),
                format!("element '{}' has no '{}' list property", e.name, names[0]),
            );
        };
        match e.properties[i].kind {
            Kind::List { item, .. } if item.is_integer() => Ok(i),
            _ => malformed(
                at(),
                format!(
                    "'{}' of element '{}' must be a list of integers, like 'property list uchar int {}'",
                    e.properties[i].name, e.name, e.properties[i].name
                ),
            ),
        }
    };
    Ok(match e.name.as_str() {
        "vertex" => {
            let mut xyz = [0; 3];
            for (slot, axis) in xyz.iter_mut().zip(["x", "y", "z"]) {
                *slot = match find(&[axis]) {
                    Some(i) if matches!(e.properties[i].kind, Kind::Scalar(_)) => i,
                    Some(_) => {
                        return malformed(
                            at(),
                            format!("vertex property '{axis}' is a list; it must be a number"),
                        );
                    }
                    None => {
                        return malformed(
                            at(),
                            format!(
                                "element 'vertex' has no property '{axis}'; add 'property float {axis}'"
                            ),
                        );
                    }
                };
            }
            Role::Vertex(xyz)
        }
        "face" => Role::Faces(list(&["vertex_indices", "vertex_index"])?),
        "tristrips" => Role::Strips(list(&["vertex_indices", "vertex_index"])?),
        _ => Role::Skipped,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_header_gives_elements_roles_and_the_body_offset() {
        let text = b"ply\r\nformat binary_big_endian 1.0\ncomment x\nelement vertex 3\nproperty float x\nproperty float y\nproperty double z\nproperty uchar red\nelement face 1\nproperty list uchar uint vertex_index\nend_header\nBODY";
        let h = parse(text).unwrap();
        assert_eq!(h.encoding, Encoding::BigEndian);
        assert_eq!(h.elements[0].role, Role::Vertex([0, 1, 2]));
        assert_eq!(h.elements[0].fixed_size(), Some(17));
        assert_eq!(h.elements[1].role, Role::Faces(0));
        assert_eq!(&text[h.body..], b"BODY");
        assert_eq!((h.lines, h.vertices), (11, 3));
    }

    fn fails(text: &str) -> (Location, String) {
        match parse(text.as_bytes()) {
            Err((at, Problem::Malformed(m))) => (at, m),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn header_errors_name_their_line() {
        assert_eq!(fails("PLY\n").0, Location::Line(1));
        let (at, m) = fails(
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty half y\nend_header\n",
        );
        assert_eq!(at, Location::Line(5));
        assert!(m.contains("unknown property type 'half'"), "{m}");
        let (at, m) =
            fails("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n");
        assert_eq!(at, Location::Line(3));
        assert!(m.contains("no property 'y'"), "{m}");
        assert!(
            fails("ply\nformat ascii 1.0\nelement vertex 1\n")
                .1
                .contains("no 'end_header'")
        );
        let (at, _) = fails("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n");
        assert_eq!(at, Location::Line(3));
    }
}
