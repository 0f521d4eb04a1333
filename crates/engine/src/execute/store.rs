//! Storing what a run computes: through the front end's [`StoreGate`], once per run when the
//! cache cannot be written ([`Storing`]), and the arrays of regenerated entries.

use std::sync::Arc;
use std::time::{SystemTime, UNIX_EPOCH};

use crate::artifact::Artifact;
use crate::cache::{CachedEntry, Manifest, ENTRY_FORMAT};
use crate::plan::PlannedNode;

use super::{NodeOutcome, NodeStatus, RunContext};

/// Whether a run stores what it computes: not in a cache found read-only when it started, nor
/// after the first store failed (said once: one warning, not one per node).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Storing {
    Yes,
    No,
}

impl RunContext<'_> {
    /// Runs one cache write through the front end's [`StoreGate`]; `None` when the gate is
    /// closed (the process is about to end, so the write is not begun).
    pub(super) fn write<T>(&self, write: impl FnOnce() -> T) -> Option<T> {
        match self.progress.store_gate() {
            Some(gate) => gate.enter().map(|_pass| write()),
            None => Some(write()),
        }
    }

    /// Stores a computed artifact (without the arrays its [`ArrayStorage`](crate::node::ArrayStorage) does not keep; not at
    /// all once the run stores nothing, [`Storing`]) and makes its outcome.
    pub(super) fn store_computed(
        &self,
        node: &PlannedNode,
        artifact: Artifact,
        seconds: f64,
    ) -> (NodeOutcome, Option<Arc<Artifact>>) {
        {
            let mut shared = self.lock();
            if shared.storing == Storing::No {
                shared.report.not_stored += 1;
                drop(shared);
                return self.computed_outcome(artifact, seconds);
            }
        }
        let manifest = Manifest {
            format: ENTRY_FORMAT,
            key: node.key.to_hex(),
            kind: node.task.kind().to_string(),
            version: node.task.version(),
            params: node.task.params(),
            upstream: node
                .upstream
                .iter()
                .map(|(r, u)| (r.to_string(), self.plan.nodes[*u].key.to_hex()))
                .collect(),
            payloads: Vec::new(),
            compute_seconds: seconds,
            tool_version: self.options.tool_version.clone(),
            created_unix: SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_secs()),
        };
        let storage = node.task.array_storage();
        let stored = self.write(|| {
            self.cache
                .store(manifest, &artifact, &|name| storage.stores(name))
        });
        if let Some(Err(e)) = stored {
            let first = {
                let mut shared = self.lock();
                shared.report.not_stored += 1;
                std::mem::replace(&mut shared.storing, Storing::No) == Storing::Yes
            };
            if first {
                self.progress.warn(&format!(
                    "a result could not be stored in the cache ({e}); this run stores no \
                     further results and uses them as computed"
                ));
            }
        }
        self.computed_outcome(artifact, seconds)
    }

    /// The outcome of a computed artifact, and the artifact for dependants.
    fn computed_outcome(
        &self,
        artifact: Artifact,
        seconds: f64,
    ) -> (NodeOutcome, Option<Arc<Artifact>>) {
        let outcome = NodeOutcome {
            status: NodeStatus::Computed,
            metrics: artifact.metrics.clone(),
            tables: artifact.tables.clone(),
            flags: artifact.flags.clone(),
            compute_seconds: seconds,
        };
        (outcome, Some(Arc::new(artifact)))
    }

    /// The arrays of a cached [`ArrayStorage::Regenerate`](crate::node::ArrayStorage::Regenerate) entry, recomputed. The recomputed
    /// metrics and flags must equal the cached ones; if they do not, the entry is replaced (and counted
    /// as discarded) and the node counts as computed.
    pub(super) fn regenerate(
        &self,
        node: &PlannedNode,
        entry: CachedEntry,
    ) -> (NodeOutcome, Option<Arc<Artifact>>) {
        match self.run_compute(node) {
            (Ok(artifact), _)
                if artifact.metrics == entry.artifact.metrics
                    && artifact.flags == entry.artifact.flags =>
            {
                let outcome = NodeOutcome {
                    status: NodeStatus::Cached,
                    metrics: entry.artifact.metrics,
                    tables: entry.artifact.tables,
                    flags: entry.artifact.flags,
                    compute_seconds: entry.manifest.compute_seconds,
                };
                (outcome, Some(Arc::new(artifact)))
            }
            (Ok(artifact), seconds) => {
                self.progress.warn(&format!(
                    "{} node '{}' ({}): recomputing its arrays did not reproduce its cached \
                     metrics or flags; the cache entry is replaced",
                    node.task.kind(),
                    node.names.join(", "),
                    node.key.short()
                ));
                if let Some(Err(e)) = self.write(|| self.cache.discard(node.task.kind(), &node.key))
                {
                    self.progress.warn(&e.to_string());
                }
                self.lock().report.discarded += 1;
                self.store_computed(node, artifact, seconds)
            }
            (Err(failed), _) => (failed, None),
        }
    }
}
