//! Run-time selection of indices by name (`bvh`, `grid:lambda=4`, ...): the list of every index
//! ([`list`]), the spec parser ([`spec`]) and the build of one ([`build`]).

mod build;
mod list;
mod spec;

pub use build::parse_params;
pub use list::{
    Kind, build_index, estimated_build_bytes, index_names, is_peer, kind_of, peer_names,
};
pub use spec::IndexSpec;
