//! The engine: end-to-end runs, byte-reproducible tables, the cache policy, node keys and the schema, the architecture invariants.

mod architecture;
mod cache_policy;
mod cancellation;
mod code_shape;
mod column_literals;
mod engine_end_to_end;
mod flagged_status;
mod import_graph;
mod key_sensitivity;
mod reproducible_tables;
#[path = "../scale_out_common/mod.rs"]
mod scale_out_common;
mod schema_and_keys;
mod source_scan;
mod table_equality;
