//! The names of the columns the engine itself writes (the node kinds' own names are the
//! application's vocabulary, which re-exports these): each defined once here, below every other
//! module of the engine.

/// The scenario number (`scenarios`, the tidy views).
pub const SCENARIO: &str = "scenario";
/// The number of scenarios in a group (`summary_<name>`).
pub const SCENARIOS: &str = "scenarios";
/// A node instance's content key (hex).
pub const KEY: &str = "key";
/// The study node names that resolve to an instance, a list (`List(String)`; kind tables,
/// timings).
pub const NODES: &str = "nodes";
/// The study node name of a row (the tidy views).
pub const NODE: &str = "node";
/// A node instance's kind (timings).
pub const KIND: &str = "kind";
/// The kind version that computed an instance.
pub const KIND_VERSION: &str = "kind_version";
/// `ok`, `flagged`, `failed`, `skipped` (rows), or a scenario's status.
pub const STATUS: &str = "status";
/// Why a row is flagged or failed.
pub const MESSAGE: &str = "message";
/// The load step of a row (a kind's step table, the tidy views).
pub const STEP: &str = "step";
/// Whether an instance was read from the cache (timings).
pub const FROM_CACHE: &str = "from_cache";
/// The compute time of an instance, s (timings only: it is no result).
pub const COMPUTE_SECONDS: &str = "compute_seconds";
/// The suffix of a column holding a node's key: `<node>_key` in `scenarios`, `<role>_key` in a
/// kind table.
pub const KEY_SUFFIX: &str = "_key";
/// The statistics of a summary metric: `<node>_<metric>_n`, `_mean`, `_std`.
pub const SUMMARY_STATISTICS: [&str; 3] = ["n", "mean", "std"];

/// The key column of node or role `name` (`lower_key`).
pub fn key_column(name: &str) -> String {
    format!("{name}{KEY_SUFFIX}")
}
