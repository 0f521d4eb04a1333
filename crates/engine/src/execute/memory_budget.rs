//! The memory budget of a run (`--memory-mib`): what the process holds, counted in bytes.
//!
//! The budget is for the whole process, not per node. Charged against it:
//! * the process's own base ([`MemoryBudget::for_process`]): its resident set when the run starts
//!   (the program, its libraries, the plan) and what running nodes adds whatever they are
//!   ([`RUN_OVERHEAD_BYTES`]);
//! * each running instance, its [`NodeTask::memory_estimate`](crate::task::NodeTask::memory_estimate),
//!   from the moment the scheduler admits it until it is computed, stored and handed over
//!   (a [`Charge`]): an instance is admitted only when its estimate fits beside what is charged
//!   already, so under a small budget instances run one after another;
//! * each artifact held in memory for dependants that have not yet run, its measured size
//!   ([`artifact_bytes`]), until its last dependant finished;
//! * the tables every instance contributes to the results, kept until they are written.
//!
//! Writing the results comes after the nodes, when only the base and those tables are charged;
//! it needs more than the base ([`RESULTS_OVERHEAD_BYTES`]), so a budget below that is refused
//! whatever the nodes ([`MemoryBudget::results`]).
//!
//! The allocator must give freed memory back for the count to bound the resident set: the
//! binary fixes the system allocator's mmap threshold and keeps one arena for that
//! (`src/huge_pages.rs`).

use std::sync::{Arc, Mutex, PoisonError};

use crate::artifact::{Artifact, ColumnData, Table};

/// What the process's resident set grows by while nodes run, whatever they are: the worker
/// threads, the allocator's arena, the FFT plans and the cache's compression (an upper bound of a
/// `--shard` run of one 16² surface, which writes no result tables; figures: docs/robustness.md,
/// "Memory").
pub(super) const RUN_OVERHEAD_BYTES: u64 = 12 << 20;

/// What the process's resident set grows by when the result tables are written after the nodes
/// (the Parquet writer's buffers), beside the tables themselves (an upper bound of a run of one
/// 16² surface; figures: docs/robustness.md, "Memory").
pub(super) const RESULTS_OVERHEAD_BYTES: u64 = 32 << 20;

/// A counter of bytes against a total; charges are taken by [`MemoryBudget::try_charge`] (only
/// if they fit) or [`MemoryBudget::force`] (memory that exists already) and returned when the
/// [`Charge`] is dropped.
#[derive(Debug)]
pub(super) struct MemoryBudget {
    total: u64,
    /// The process's resident set when the run started with what running nodes add, charged for
    /// the whole run.
    base: u64,
    /// What the process holds while it writes the results, the tables kept for them aside.
    results: u64,
    used: Mutex<u64>,
}

/// Bytes charged against a [`MemoryBudget`] until dropped.
#[derive(Debug)]
pub(super) struct Charge {
    budget: Arc<MemoryBudget>,
    bytes: u64,
}

impl MemoryBudget {
    /// A budget of `total` bytes with `base` of them charged for the whole run and `results`
    /// needed to write the results.
    pub(super) fn new(total: u64, base: u64, results: u64) -> Arc<Self> {
        Arc::new(Self {
            total: total.max(1),
            base,
            results,
            used: Mutex::new(base),
        })
    }

    /// A budget of `total` bytes for this process: its base is its resident set now (none where
    /// the system does not say) and [`RUN_OVERHEAD_BYTES`]; writing the results needs that
    /// resident set and [`RESULTS_OVERHEAD_BYTES`].
    pub(super) fn for_process(total: u64) -> Arc<Self> {
        let resident = super::process_memory::resident_bytes().unwrap_or(0);
        Self::new(
            total,
            resident + RUN_OVERHEAD_BYTES,
            resident + RESULTS_OVERHEAD_BYTES,
        )
    }

    /// The whole budget, bytes.
    pub(super) fn total(&self) -> u64 {
        self.total
    }

    /// The process's base charged for the whole run, bytes.
    pub(super) fn base(&self) -> u64 {
        self.base
    }

    /// What the process holds while it writes the results (the tables kept for them aside),
    /// bytes: a budget below it cannot be kept whatever the nodes.
    pub(super) fn results(&self) -> u64 {
        self.results
    }

    /// Charges `bytes` if they fit beside what is charged already.
    pub(super) fn try_charge(self: &Arc<Self>, bytes: u64) -> Option<Charge> {
        let mut used = self.lock();
        if *used + bytes > self.total {
            return None;
        }
        *used += bytes;
        Some(self.charge(bytes))
    }

    /// Charges `bytes` whether or not they fit: memory the process holds already (an artifact
    /// just computed) or an instance admitted when nothing else runs. While the budget is
    /// overdrawn, no further instance is admitted.
    pub(super) fn force(self: &Arc<Self>, bytes: u64) -> Charge {
        *self.lock() += bytes;
        self.charge(bytes)
    }

    /// Charges `bytes` for the rest of the run (the tables kept for the results).
    pub(super) fn keep(&self, bytes: u64) {
        *self.lock() += bytes;
    }

    fn charge(self: &Arc<Self>, bytes: u64) -> Charge {
        Charge {
            budget: Arc::clone(self),
            bytes,
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, u64> {
        self.used.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl Drop for Charge {
    fn drop(&mut self) {
        *self.budget.lock() -= self.bytes;
    }
}

/// An artifact held for dependants, with the charge of its size.
#[derive(Debug)]
pub(super) struct Held {
    pub(super) artifact: Arc<Artifact>,
    _charge: Charge,
}

impl Held {
    /// `artifact`, charged its measured size ([`artifact_bytes`]) until dropped.
    pub(super) fn new(artifact: Arc<Artifact>, budget: &Arc<MemoryBudget>) -> Self {
        let charge = budget.force(artifact_bytes(&artifact));
        Self {
            artifact,
            _charge: charge,
        }
    }
}

/// The bytes an artifact holds: its arrays (8 per value) and its tables ([`table_bytes`]).
pub(super) fn artifact_bytes(artifact: &Artifact) -> u64 {
    let arrays: u64 = artifact.arrays.values().map(|a| a.len() as u64 * 8).sum();
    arrays + artifact.tables.values().map(table_bytes).sum::<u64>()
}

/// The bytes a table holds: 8 per number, 1 per flag, and each text's length plus its 24-byte
/// header.
pub(super) fn table_bytes(table: &Table) -> u64 {
    table
        .columns
        .iter()
        .map(|c| match &c.data {
            ColumnData::Float(v) => v.len() as u64 * 8,
            ColumnData::Int(v) => v.len() as u64 * 8,
            ColumnData::Bool(v) => v.len() as u64,
            ColumnData::Text(v) => v.iter().map(|s| s.len() as u64 + 24).sum(),
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::units::Dimension;
    use ndarray::ArrayD;

    #[test]
    fn charges_fit_beside_the_base_and_are_returned_when_dropped() {
        let budget = MemoryBudget::new(100, 30, 40);
        let a = budget.try_charge(60).expect("30 + 60 fit in 100");
        assert!(budget.try_charge(20).is_none(), "30 + 60 + 20 exceed 100");
        let forced = budget.force(20);
        assert_eq!(*budget.lock(), 110);
        drop((a, forced));
        assert_eq!(*budget.lock(), 30);
        budget.keep(5);
        assert!(budget.try_charge(66).is_none());
        assert!(budget.try_charge(65).is_some());
    }

    #[test]
    fn an_artifact_is_charged_its_arrays_and_tables() {
        let mut artifact = Artifact::default();
        artifact
            .arrays
            .insert("pressure".into(), ArrayD::zeros(vec![4, 8]));
        let mut table = Table::default();
        table.push_float("load", Dimension::Dimensionless, vec![1.0; 3]);
        table.push_text("status", vec!["ok".into(), "flagged".into()]);
        artifact.tables.insert("steps".into(), table);
        assert_eq!(
            artifact_bytes(&artifact),
            32 * 8 + 3 * 8 + (2 + 24) + (7 + 24)
        );
        let budget = MemoryBudget::new(1 << 20, 0, 0);
        let held = Held::new(Arc::new(artifact), &budget);
        assert_eq!(*budget.lock(), 337);
        drop(held);
        assert_eq!(*budget.lock(), 0);
    }
}
