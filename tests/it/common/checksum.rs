//! Checksums of ray sets, as the protocol states them.

use accelbench::geometry::Ray;
use accelbench::rays::ray_to_record;
use md5::{Digest, Md5};

/// MD5 of the rays' 32-byte little-endian records, as `accelbench rays` writes them.
pub fn md5_of_rays(rays: &[Ray]) -> String {
    let mut h = Md5::new();
    for r in rays {
        for x in ray_to_record(r) {
            h.update(x.to_le_bytes());
        }
    }
    format!("{:x}", h.finalize())
}
