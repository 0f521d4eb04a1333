//! Scale-out: shards, cache commands, concurrent processes, crash safety, Ctrl-C, folder
//! trouble (permissions, leftovers, another study's results) and the memory budget.

mod cache_damage;
mod concurrency;
mod crash_safety;
#[cfg(target_os = "linux")]
mod folders;
#[cfg(target_os = "linux")]
mod interrupt;
#[cfg(target_os = "linux")]
mod memory;
#[path = "../scale_out_common/mod.rs"]
mod scale_out_common;
mod scale_out_shards;
