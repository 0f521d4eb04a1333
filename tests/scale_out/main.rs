//! Scale-out: shards, cache commands, concurrent processes and crash safety.

mod cache_damage;
mod concurrency;
mod crash_safety;
#[path = "../scale_out_common/mod.rs"]
mod scale_out_common;
mod scale_out_shards;
