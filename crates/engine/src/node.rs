//! The node-kind contract: the only thing the engine knows about what nodes compute.
//!
//! A study's node specs ([`NodeSpec`]) are resolved, once per distinct parameter combination, into
//! [`NodeTask`]s: concrete, SI-valued, hashable units of work. The engine plans, keys, caches,
//! schedules and tabulates tasks without knowing what they mean.

use std::sync::Arc;

use serde::de::DeserializeOwned;

use crate::resolve::ResolveContext;
use crate::syntax::{SpannedName, SpecError};

pub use crate::task::{ArrayStorage, NodeError, NodeTask};

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
