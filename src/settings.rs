//! Settings (GUCs) and the memory budget they impose.

use pgrx::guc::{GucContext, GucFlags, GucRegistry, GucSetting};
use pgrx::pg_sys::panic::ErrorReport;
use pgrx::prelude::*;

/// `circletree.max_encode_memory`, in MB: the most memory one encode may be expected to take.
static MAX_ENCODE_MEMORY: GucSetting<i32> = GucSetting::<i32>::new(2048);

/// `circletree.encode_threads`: threads one encode may use (1 or 2).
static ENCODE_THREADS: GucSetting<i32> = GucSetting::<i32>::new(2);

pub fn init() {
    GucRegistry::define_int_guc(
        c"circletree.max_encode_memory",
        c"The most memory one ct_encode or ct_encode_within call may be expected to use.",
        c"Encoding allocates outside PostgreSQL's memory contexts, in proportion to the input's vertices (measured peaks in docs/RELIABILITY.md); an input whose estimate exceeds this is refused with an error instead of risking the out-of-memory killer. Only superusers may change it.",
        &MAX_ENCODE_MEMORY,
        1,
        i32::MAX,
        GucContext::Suset,
        GucFlags::UNIT_MB,
    );
    GucRegistry::define_int_guc(
        c"circletree.encode_threads",
        c"Threads one ct_encode or ct_encode_within call may use on a large geometry (1 or 2).",
        c"With 2, an encode of at least 5,000 vertices runs independent steps on a second thread, which never calls into PostgreSQL and stops when the statement is cancelled. Set 1 where the server's cores are better spent on other backends.",
        &ENCODE_THREADS,
        1,
        2,
        GucContext::Userset,
        GucFlags::default(),
    );
}

/// Tell the encoder how many threads this call may use (`circletree.encode_threads`).
pub fn apply_encode_threads() {
    circletree_core::set_threads(ENCODE_THREADS.get().clamp(1, 2) as usize);
}

/// Peak bytes a vertex of input costs, measured on a 1,000,000-vertex ring (VmHWM above a fresh
/// backend's: about 460 for `ct_encode`, 110 for `ct_encode_within`; the core's `scaling` example
/// peaks about 40 bytes a vertex higher since `map_runs` runs on two threads) and rounded up for rings
/// whose circles are denser.
pub const ENCODE_BYTES_PER_VERTEX: f64 = 600.0;
pub const ENCODE_WITHIN_BYTES_PER_VERTEX: f64 = 200.0;

/// Refuse an encode whose estimated peak (from the WKB size: 16 bytes a vertex) exceeds
/// `circletree.max_encode_memory`. Raises 54000 (program_limit_exceeded) with a hint.
pub fn check_encode_memory(wkb: &[u8], bytes_per_vertex: f64, function: &str) {
    apply_encode_threads();
    let vertices = wkb.len() as f64 / 16.0;
    let need_mb = (vertices * bytes_per_vertex / 1_048_576.0).ceil();
    let limit_mb = f64::from(MAX_ENCODE_MEMORY.get());
    if need_mb > limit_mb {
        ErrorReport::new(
            PgSqlErrorCode::ERRCODE_PROGRAM_LIMIT_EXCEEDED,
            format!(
                "{function} of a geometry of about {:.0} vertices would need about {need_mb:.0} MB, more than circletree.max_encode_memory ({limit_mb:.0} MB)",
                vertices.floor()
            ),
            "circletree",
        )
        .set_hint("A superuser can raise the limit (SET circletree.max_encode_memory = '8GB') if the server has the memory; or encode the parts separately (ST_Dump).")
        .report(PgLogLevel::ERROR);
    }
}
