//! A resolved node instance as the engine runs it: [`NodeTask`] (kind, version, SI parameters,
//! memory estimate, `compute`, array storage policy and the derivation of arrays it does not
//! store) and [`NodeError`]. Specs resolve into tasks
//! in [`crate::node`].

use crate::artifact::Artifact;
use crate::value::Field;

/// One node instance ready to compute.
pub trait NodeTask: Send + Sync + std::fmt::Debug {
    /// Kind name (`surface`).
    fn kind(&self) -> &'static str;
    /// Implementation version of the kind: bumped by hand whenever its numerics change, so stale
    /// cache entries are never reused.
    fn version(&self) -> u32;
    /// The table the kind's rows go to (`surfaces`).
    fn table(&self) -> &'static str;
    /// The name of the kind's own long table that holds one row per load step, if the kind has
    /// load steps: a `step` column (0, 1, …) and every metric of the kind table's row at that
    /// step (its last row equals the row). The tidy view `<table>_by_scenario` gives one row per
    /// step from it. No kind's own table is called `by_scenario` (that name is the view's).
    fn step_table(&self) -> Option<&'static str> {
        None
    }
    /// The resolved parameters (SI) this node consumes, and nothing else: they enter the key and
    /// the table row. Derived from the task's own typed fields by one function per kind (the
    /// task keeps no second, hand-built copy), so what the node computes with and what its key
    /// says cannot drift apart.
    fn params(&self) -> Vec<Field>;
    /// Estimated peak memory of [`NodeTask::compute`] in bytes, for the memory-aware limit.
    fn memory_estimate(&self) -> u64;
    /// How the cache keeps this instance's arrays (metrics and tables are always stored).
    fn array_storage(&self) -> ArrayStorage {
        ArrayStorage::Store
    }
    /// Under [`ArrayStorage::Derive`]: adds the arrays the policy names to `artifact` (this
    /// instance's cached metrics, tables and stored arrays), from the upstream artifacts `inputs`
    /// (with their arrays, in the order of [`NodeTask::compute`]'s). The arrays must equal those
    /// `compute` returns (to round-off, as the kind documents). Kinds that derive nothing keep
    /// this default, which refuses.
    fn derive_arrays(
        &self,
        inputs: &[&Artifact],
        artifact: &mut Artifact,
    ) -> Result<(), NodeError> {
        let _ = (inputs, artifact);
        Err(NodeError::new(format!(
            "the {} kind derives no arrays",
            self.kind()
        )))
    }
    /// The task as `Any`, so that the application's node kinds can read an upstream task of a
    /// kind they know as its own type (the engine never does).
    fn as_any(&self) -> &dyn std::any::Any;
    /// Computes the node from its upstream artifacts (in the order of the spec's `upstream`).
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
    /// The arrays named here are not stored, the others are: the named ones follow from the
    /// stored ones and the upstream arrays at a fraction of the node's cost (e.g. a contact's gap
    /// and deformations from its pressure field by one convolution, where the solve takes
    /// hundreds). A dependant that needs them gets them from [`NodeTask::derive_arrays`], run on
    /// the cached entry and the upstream artifacts (loaded, regenerated or derived in turn).
    Derive(&'static [&'static str]),
}

impl ArrayStorage {
    /// Whether the cache stores the array called `name` under this policy.
    pub fn stores(&self, name: &str) -> bool {
        match self {
            ArrayStorage::Store => true,
            ArrayStorage::Regenerate => false,
            ArrayStorage::Derive(derived) => !derived.contains(&name),
        }
    }
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
