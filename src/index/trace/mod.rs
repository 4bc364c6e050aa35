//! The tracing machinery: how a batch of rays is traced through any index. The trace modes
//! ([`mode`]), the batch techniques an index may have ([`batch`]), the query kinds ([`query`]),
//! the last-hit cache ([`last_hit`]), a batch in an index's own ray form ([`own_rays`]), one
//! worker's chunk ([`chunk`]), packets from screen tiles ([`tiles`]), the parallel driver
//! ([`parallel`]), the coherence order it can trace a batch in ([`reorder`]) and the
//! object-safe [`TraceIndex`] of a built index ([`bound`]).

pub mod batch;
pub mod bound;
pub mod chunk;
pub mod last_hit;
pub mod mode;
pub mod own_rays;
pub mod parallel;
pub mod query;
pub mod reorder;
pub mod tiles;
pub mod trace_index;

pub use batch::BatchIndex;
pub use bound::{BoundIndex, build_index_on};
pub use mode::{MAX_PACKET, ModeFamily, TraceMode};
pub use own_rays::{Answers, OwnRays};
pub use trace_index::TraceIndex;
