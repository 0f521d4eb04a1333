//! The node-kind contract: the only thing the engine knows about what nodes compute.
//!
//! A study's node specs ([`NodeSpec`]) are resolved, once per distinct parameter combination, into
//! [`NodeTask`]s: concrete, SI-valued, hashable units of work. The engine plans, keys, caches,
//! schedules and tabulates tasks without knowing what they mean.

use std::sync::Arc;

use serde::de::DeserializeOwned;

use crate::engine::artifact::Artifact;
use crate::engine::study::{ResolveContext, SpannedName, SpecError};
use crate::engine::value::Field;

/// A reference from a node spec to an upstream node, under a role name ("lower", "surface").
#[derive(Debug, Clone, Copy)]
pub struct UpstreamRef<'a> {
    /// Role of the upstream node for this node; part of the key (roles are sorted).
    pub role: &'static str,
    /// Name of the upstream node in the study, with its location.
    pub node: &'a SpannedName,
}

/// A node as written in a study file (with `${param}` references still unresolved).
pub trait NodeSpec: DeserializeOwned + schemars::JsonSchema + Send + Sync {
    /// Every table the node kinds can produce (`surfaces`, `contacts`, …), for `outputs:`.
    fn all_tables() -> &'static [&'static str];
    /// The kind name, the key in the study file (`surface`, `contact`, `friction`).
    fn kind(&self) -> &'static str;
    /// The table the kind's rows go to (`surfaces`); also the output name users request.
    fn table(&self) -> &'static str;
    /// Upstream references, in a fixed order.
    fn upstream(&self) -> Vec<UpstreamRef<'_>>;
    /// Resolves the spec under one scenario's parameter values. The context gives the upstream
    /// tasks in the order of [`NodeSpec::upstream`].
    fn instantiate(&self, ctx: &ResolveContext<'_>) -> Result<Arc<dyn NodeTask>, SpecError>;
}

/// One node instance ready to compute.
pub trait NodeTask: Send + Sync + std::fmt::Debug {
    /// Kind name (`surface`).
    fn kind(&self) -> &'static str;
    /// Implementation version of the kind: bumped by hand whenever its numerics change, so stale
    /// cache entries are never reused.
    fn version(&self) -> u32;
    /// The table the kind's rows go to (`surfaces`).
    fn table(&self) -> &'static str;
    /// The resolved parameters (SI) this node consumes, and nothing else: they enter the key and
    /// the table row.
    fn params(&self) -> &[Field];
    /// Estimated peak memory of [`NodeTask::compute`] in bytes, for the memory-aware limit.
    fn memory_estimate(&self) -> u64;
    /// How the cache keeps this instance's arrays (metrics and tables are always stored).
    fn array_storage(&self) -> ArrayStorage {
        ArrayStorage::Store
    }
    /// Computes the node from its upstream artifacts (in [`NodeSpec::upstream`] order).
    fn compute(&self, inputs: &[&Artifact]) -> Result<Artifact, NodeError>;
}

/// The cache's storage policy for a node's arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ArrayStorage {
    /// Stored (losslessly compressed) and read back when a dependant needs them.
    Store,
    /// Not stored: cheaper to recompute than to read (e.g. a synthetic surface generated from
    /// its key in a second, where its heights take ~100 MB). A dependant that needs them gets them
    /// by recomputing the node, which must then be deterministic: the engine checks that the
    /// recomputed metrics equal the cached ones.
    Regenerate,
}

/// A node failed to compute; only its dependants fail with it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct NodeError {
    pub message: String,
}

impl NodeError {
    /// A failure with a message for the user.
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }
}
