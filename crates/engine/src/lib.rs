//! asperity-engine: the study engine of asperity. YAML study → scenarios → DAG of node instances
//! → content-hashed cache → parallel execution → Parquet tables.
//!
//! The engine knows nothing of tribology: node kinds plug in through [`node::NodeSpec`] and
//! [`node::NodeTask`]. It never prints; progress goes through [`execute::Progress`]. Quantities
//! with units at the study boundary: [`units`].

#![deny(unsafe_code)]

pub mod artifact;
pub mod cache;
pub mod cache_admin;
pub mod columns;
mod encoding;
pub mod execute;
pub mod hash;
pub mod node;
pub mod npy;
pub mod output;
pub mod plan;
pub mod regular_file;
pub mod resolve;
pub mod shard;
pub mod study;
pub mod summary;
pub mod syntax;
pub mod task;
pub mod units;
pub mod value;
