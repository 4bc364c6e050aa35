//! The integration tests, gathered into one binary so that the crate is linked once (thirty
//! binaries each linking the whole crate made the test build several times slower). Each module
//! is one former `tests/NAME.rs`; run one with `cargo test --release --test it NAME::`.

mod common;
mod partition_kit;

mod accuracy;
mod agreement;
mod animate;
mod beams;
mod bounded_reads;
mod bsp;
mod bvh;
mod cameras;
mod cli;
mod compare;
mod full_disk;
mod fuzz;
mod gpu;
mod grid;
mod grid2;
mod instances;
mod kdtree;
mod last_hit;
mod layout;
mod leak;
mod memory_checks;
mod mesh_formats;
mod messages;
mod obvhs_peer;
mod octree;
mod packets;
mod peers;
mod proptest_indices;
mod protocol;
mod reliability;
mod render;
mod reorder;
mod report_folder;
mod report_html;
mod results_page;
mod shapes;
mod shard;
mod stress;
mod suite;
mod surprises;
mod verdict;
mod wbvh;
