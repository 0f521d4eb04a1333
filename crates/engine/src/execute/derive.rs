//! Arrays a node kind does not store ([`ArrayStorage::Derive`]), derived again for a dependant
//! from the node's cached entry and its upstream arrays.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Arc;

use super::{internal_error, NodeOutcome, NodeStatus, RunContext};
use crate::artifact::Artifact;
use crate::cache::CachedEntry;
use crate::node::ArrayStorage;
use crate::plan::PlannedNode;

impl RunContext<'_> {
    /// A cached node that derives arrays, for its dependants: its entry completed with the
    /// derived arrays (the node counts as cached). When they cannot be derived (an upstream
    /// node that cannot be loaded or regenerated, a failing derivation), a warning says why and
    /// the node is recomputed.
    pub(super) fn derive(
        &self,
        node: &PlannedNode,
        entry: CachedEntry,
    ) -> (NodeOutcome, Option<Arc<Artifact>>) {
        let outcome = NodeOutcome {
            status: NodeStatus::Cached,
            metrics: entry.artifact.metrics.clone(),
            tables: entry.artifact.tables.clone(),
            flags: entry.artifact.flags.clone(),
            compute_seconds: entry.manifest.compute_seconds,
        };
        match self.complete(node, entry) {
            Ok(artifact) => (outcome, Some(Arc::new(artifact))),
            Err(reason) => {
                self.progress.warn(&format!(
                    "{} node '{}' ({}): its arrays could not be derived from the cache ({reason}); \
                     recomputing it",
                    node.task.kind(),
                    node.names.join(", "),
                    node.key.short()
                ));
                self.compute(node)
            }
        }
    }

    /// The artifact of `entry` (a cached entry of `node` read with its stored arrays) with the
    /// arrays its kind derives, under the memory budget; the artifact as it is for a kind that
    /// derives none. An error says why they could not be derived.
    pub(super) fn complete(
        &self,
        node: &PlannedNode,
        entry: CachedEntry,
    ) -> Result<Artifact, String> {
        let mut artifact = entry.artifact;
        if !matches!(node.task.array_storage(), ArrayStorage::Derive(_)) {
            return Ok(artifact);
        }
        if let Some(failed) = self.over_budget(node) {
            return Err(failed.message().to_string());
        }
        let (inputs, _charges) = self
            .upstream_artifacts(node)
            .map_err(|failed| failed.status.message().to_string())?;
        let input_refs: Vec<&Artifact> = inputs.iter().map(Arc::as_ref).collect();
        catch_unwind(AssertUnwindSafe(|| {
            node.task.derive_arrays(&input_refs, &mut artifact)
        }))
        .unwrap_or_else(|panic| Err(internal_error(panic)))
        .map_err(|e| e.message)?;
        Ok(artifact)
    }
}
