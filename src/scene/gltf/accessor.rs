//! Reading a glTF accessor's elements out of its buffer with every range checked first: the
//! `POSITION` accessor of a primitive (`FLOAT` `VEC3`) and its `indices` (unsigned 8-, 16- or
//! 32-bit scalars), in parallel. A problem in the document is located by its JSON path, one in
//! the data by the byte offset in the file that holds it.

use super::buffers::{Buffer, Buffers};
use crate::scene::SceneError;
use crate::scene::error::Location;
use glam::Vec3A;
use gltf::Accessor;
use gltf::accessor::{DataType, Dimensions};
use rayon::prelude::*;
use std::path::Path;

/// Elements below which a read stays on one thread.
const MIN_PARALLEL: usize = 1 << 14;

/// Where an accessor's elements lie in its buffer: element `k` starts at `start + k * stride`.
struct Span<'a> {
    buffer: Buffer<'a>,
    start: usize,
    stride: usize,
    count: usize,
}

impl Span<'_> {
    fn element(&self, k: usize) -> &[u8] {
        &self.buffer.bytes[self.start + k * self.stride..]
    }

    /// Every element through `read` (given the element's bytes onwards), in parallel.
    fn read_all<T: Send>(&self, read: impl Fn(&[u8]) -> T + Sync) -> Vec<T> {
        let mut out = Vec::new();
        (0..self.count)
            .into_par_iter()
            .with_min_len(MIN_PARALLEL)
            .map(|k| read(self.element(k)))
            .collect_into_vec(&mut out);
        out
    }

    /// The file offset of element `k`.
    fn at(&self, k: usize) -> Location {
        Location::Byte((self.buffer.base + self.start + k * self.stride) as u64)
    }
}

/// An error in the document `main` at accessor `a`.
fn bad(main: &Path, a: &Accessor, message: String) -> SceneError {
    SceneError::Mesh {
        path: main.to_owned(),
        format: "glTF",
        at: Location::Json(format!("accessors[{}]", a.index())),
        message,
    }
}

/// The span of accessor `a` of elements of `size` bytes, checked to lie inside its buffer view
/// and the view inside its buffer.
fn span<'a>(
    buffers: &'a Buffers,
    main: &Path,
    a: &Accessor,
    size: usize,
) -> Result<Span<'a>, SceneError> {
    if a.sparse().is_some() {
        return Err(bad(
            main,
            a,
            "sparse accessors are not supported; write the data out densely".into(),
        ));
    }
    let Some(view) = a.view() else {
        return Err(bad(main, a, "the accessor has no bufferView (all zeros), which is not supported for positions or indices".into()));
    };
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(bad(
            main,
            a,
            format!(
                "its bufferView's byteStride {stride} is smaller than an element ({size} bytes)"
            ),
        ));
    }
    let count = a.count();
    let need = match count.checked_sub(1) {
        None => Some(0),
        Some(last) => last
            .checked_mul(stride)
            .and_then(|n| n.checked_add(size + a.offset())),
    };
    match need {
        Some(need) if need <= view.length() => {}
        _ => {
            return Err(bad(
                main,
                a,
                format!(
                    "{count} elements of {size} bytes (stride {stride}) from byteOffset {} do not fit in bufferView {} of {} bytes; fix the accessor's count or byteOffset",
                    a.offset(),
                    view.index(),
                    view.length()
                ),
            ));
        }
    }
    let buffer = buffers.get(view.buffer().index());
    if view
        .offset()
        .checked_add(view.length())
        .is_none_or(|end| end > view.buffer().length())
    {
        return Err(SceneError::Mesh {
            path: main.to_owned(),
            format: "glTF",
            at: Location::Json(format!("bufferViews[{}]", view.index())),
            message: format!(
                "bytes {}..+{} lie outside buffer {} of {} bytes; fix the view's byteOffset or byteLength",
                view.offset(),
                view.length(),
                view.buffer().index(),
                view.buffer().length()
            ),
        });
    }
    Ok(Span {
        buffer,
        start: view.offset() + a.offset(),
        stride,
        count,
    })
}

/// The positions of accessor `a` (`FLOAT` `VEC3`). Errors: another type, a range outside the
/// buffer, a NaN or infinite coordinate (with its byte offset).
pub fn positions(buffers: &Buffers, main: &Path, a: &Accessor) -> Result<Vec<Vec3A>, SceneError> {
    if (a.data_type(), a.dimensions()) != (DataType::F32, Dimensions::Vec3) || a.normalized() {
        return Err(bad(
            main,
            a,
            format!(
                "POSITION is {:?} {:?}; positions must be FLOAT VEC3 (quantized positions, KHR_mesh_quantization, are not supported)",
                a.data_type(),
                a.dimensions()
            ),
        ));
    }
    let s = span(buffers, main, a, 12)?;
    let out = s.read_all(|e| {
        let f = |i: usize| f32::from_le_bytes(e[4 * i..4 * i + 4].try_into().expect("4 bytes"));
        Vec3A::new(f(0), f(1), f(2))
    });
    if let Some(k) = out.par_iter().position_first(|p| !p.is_finite()) {
        let p = out[k];
        return Err(SceneError::NonFiniteVertex {
            path: s.buffer.file.to_owned(),
            at: s.at(k),
            text: format!(
                "accessor {}, vertex {k}: {} {} {}",
                a.index(),
                p.x,
                p.y,
                p.z
            ),
        });
    }
    Ok(out)
}

/// The indices of accessor `a` (unsigned 8-, 16- or 32-bit scalars), each checked to be below
/// `vertices`.
pub fn indices(
    buffers: &Buffers,
    main: &Path,
    a: &Accessor,
    vertices: usize,
) -> Result<Vec<u32>, SceneError> {
    let size = match (a.data_type(), a.dimensions()) {
        (DataType::U8, Dimensions::Scalar) => 1,
        (DataType::U16, Dimensions::Scalar) => 2,
        (DataType::U32, Dimensions::Scalar) => 4,
        (t, d) => {
            return Err(bad(
                main,
                a,
                format!(
                    "indices are {t:?} {d:?}; they must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT scalars"
                ),
            ));
        }
    };
    let s = span(buffers, main, a, size)?;
    let out = s.read_all(|e| match size {
        1 => e[0] as u32,
        2 => u16::from_le_bytes([e[0], e[1]]) as u32,
        _ => u32::from_le_bytes([e[0], e[1], e[2], e[3]]),
    });
    if let Some(k) = out.par_iter().position_first(|&i| i as usize >= vertices) {
        return Err(SceneError::Mesh {
            path: s.buffer.file.to_owned(),
            format: "glTF",
            at: s.at(k),
            message: format!(
                "index {k} of accessor {} is {}, but the primitive's POSITION accessor has {vertices} vertices; fix the index or the positions",
                a.index(),
                out[k]
            ),
        });
    }
    Ok(out)
}
