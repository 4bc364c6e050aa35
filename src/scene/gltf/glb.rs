//! The container of a binary glTF (`.glb`) file: a 12-byte header (`glTF`, version 2, total
//! length), a JSON chunk, then optionally a BIN chunk, all little-endian. Split in place (the
//! `gltf` crate's reader copies the BIN chunk), with the byte offset of every error.

use crate::scene::error::Location;

/// The chunks of a `.glb` file: the JSON text, and the BIN chunk with its offset in the file.
pub struct Glb<'a> {
    pub json: &'a [u8],
    pub bin: Option<(&'a [u8], usize)>,
}

const JSON: u32 = 0x4E4F_534A;
const BIN: u32 = 0x004E_4942;

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    let four = b.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes(four.try_into().ok()?))
}

/// Splits `bytes` (the whole file, starting with `glTF`).
pub fn split(bytes: &[u8]) -> Result<Glb<'_>, (Location, String)> {
    let fail = |at: usize, m: String| Err((Location::Byte(at as u64), m));
    let (Some(version), Some(length)) = (u32_at(bytes, 4), u32_at(bytes, 8)) else {
        return fail(
            0,
            format!(
                "the file has {} bytes, fewer than a GLB header's 12; it is truncated",
                bytes.len()
            ),
        );
    };
    if version != 2 {
        return fail(
            4,
            format!("GLB version {version}; only glTF 2.0 (version 2) is supported"),
        );
    }
    if length as usize != bytes.len() {
        return fail(
            8,
            format!(
                "the header says the file has {length} bytes, it has {}; the file is truncated or padded",
                bytes.len()
            ),
        );
    }
    let chunk = |at: usize, want: u32, name: &str| -> Result<(&[u8], usize), (Location, String)> {
        let (Some(len), Some(ty)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err((
                Location::Byte(at as u64),
                format!("the file ends where the {name} chunk's header should be"),
            ));
        };
        if ty != want {
            return Err((
                Location::Byte(at as u64 + 4),
                format!("chunk type {ty:#010x} where the {name} chunk should be"),
            ));
        }
        let start = at + 8;
        match bytes.get(start..start + len as usize) {
            Some(data) => Ok((data, start)),
            None => Err((
                Location::Byte(at as u64),
                format!(
                    "the {name} chunk claims {len} bytes, but only {} follow; the file is truncated",
                    bytes.len() - start.min(bytes.len())
                ),
            )),
        }
    };
    let (json, at) = chunk(12, JSON, "JSON")?;
    // Chunks are padded to 4 bytes (the length already includes the padding).
    let next = at + json.len();
    let bin = if next < bytes.len() {
        Some(chunk(next, BIN, "BIN")?)
    } else {
        None
    };
    Ok(Glb { json, bin })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
        let mut v = b"glTF".to_vec();
        v.extend(2u32.to_le_bytes());
        v.extend(((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
        v.extend((json.len() as u32).to_le_bytes());
        v.extend(JSON.to_le_bytes());
        v.extend(json);
        v.extend((bin.len() as u32).to_le_bytes());
        v.extend(BIN.to_le_bytes());
        v.extend(bin);
        v
    }

    #[test]
    fn chunks_are_split_in_place_and_truncation_is_located() {
        let f = glb(b"{}  ", &[1, 2, 3, 4]);
        let g = split(&f).unwrap();
        assert_eq!(g.json, b"{}  ");
        assert_eq!(g.bin, Some((&[1u8, 2, 3, 4][..], 32)));
        let mut cut = f[..30].to_vec();
        cut[8..12].copy_from_slice(&30u32.to_le_bytes());
        assert_eq!(split(&cut).err().unwrap().0, Location::Byte(24));
        assert_eq!(split(&f[..10]).err().unwrap().0, Location::Byte(0));
    }
}
