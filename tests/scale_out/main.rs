//! Scale-out: shards, cache commands, concurrent processes, crash safety, Ctrl-C and folder
//! trouble (permissions, leftovers, another study's results).

mod cache_damage;
mod concurrency;
mod crash_safety;
#[cfg(target_os = "linux")]
mod folders;
#[cfg(target_os = "linux")]
mod interrupt;
#[path = "../scale_out_common/mod.rs"]
mod scale_out_common;
mod scale_out_shards;
