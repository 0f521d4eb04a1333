//! Topography readers: every format against its reference values, robustness against broken and hostile files, synthetic round trips.

#[path = "../common/mod.rs"]
mod common;
mod damage;
mod damaged_files;
mod every_shared_file;
mod header_checks;
mod lying_headers;
mod mnt_mask;
mod readers_a;
#[path = "../readers_a_common/mod.rs"]
mod readers_a_common;
mod readers_a_synthetic;
mod readers_b;
mod readers_b_fixtures;
mod readers_bounded;
mod readers_instruments;
mod readers_mnt;
mod readers_more;
mod registry;
