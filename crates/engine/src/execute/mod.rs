//! Execution: load what the cache has, compute the rest in parallel, upstream first.
//!
//! Only instances the requested tables need are touched. Instances run in parallel on the rayon
//! pool as soon as their upstream finished, deepest first (see `RunContext::pull`), each admitted
//! only when its memory estimate fits the process's budget beside what is held already
//! (`memory_budget`), so large nodes do not run all at once. A failing
//! node fails only its dependants; a flagged one (computed, with sentences its row must be read
//! with, [`Artifact::flags`]) is used by them like any other.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use crate::artifact::Artifact;
use crate::cache::{Cache, CacheError, CachedEntry};
use crate::node::{ArrayStorage, NodeError};
use crate::plan::{Plan, PlannedNode};

mod cache_access;
mod derive;
mod memory_budget;
mod outcome;
pub mod process_memory;
mod schedule;
mod store;
mod store_gate;

use memory_budget::{artifact_bytes, table_bytes, Charge, Held, MemoryBudget};
pub use outcome::{NodeOutcome, NodeStatus};
use schedule::{payload_needs, Schedule};
use store::Storing;
pub use store_gate::StoreGate;

/// Receives progress events; the CLI draws a progress bar, tests ignore them.
pub trait Progress: Sync {
    /// Execution starts with `total` instances to load or compute.
    fn start(&self, total: usize);
    /// One instance finished (computed, loaded, failed or skipped).
    fn finished(&self, node: &PlannedNode, status: &NodeStatus);
    /// Something the user should know that is not a failure (a corrupt entry was discarded, …).
    fn warn(&self, message: &str);
    /// `true` once the caller wants the run to stop (Ctrl-C): no further instance is started,
    /// the running ones finish and are stored, so the cache holds only complete entries. The
    /// instances never started have no outcome and [`RunReport::cancelled`] is set.
    fn cancelled(&self) -> bool {
        false
    }
    /// The gate every cache write of the run passes (see [`StoreGate`]), for a front end that
    /// may end the process at once; `None`: writes are not counted.
    fn store_gate(&self) -> Option<&StoreGate> {
        None
    }
}

/// A [`Progress`] that ignores everything.
pub struct NoProgress;

impl Progress for NoProgress {
    fn start(&self, _: usize) {}
    fn finished(&self, _: &PlannedNode, _: &NodeStatus) {}
    fn warn(&self, _: &str) {}
}

/// Execution settings.
#[derive(Debug, Clone)]
pub struct ExecuteOptions {
    /// Tables to produce; instances are computed only if these need them.
    pub tables: Vec<String>,
    /// Memory budget of the process, bytes: its resident set when the run starts, the nodes
    /// running at once (their estimates), the artifacts held for dependants and the tables kept
    /// for the results together stay within it (see the `memory_budget` module).
    pub memory_budget: u64,
    /// Tool version recorded in manifests.
    pub tool_version: String,
}

/// The result of a run.
#[derive(Debug, Clone, Default)]
pub struct RunReport {
    /// `outcomes[i]` for instance `i`; `None` when the requested tables did not need it.
    pub outcomes: Vec<Option<NodeOutcome>>,
    pub computed: usize,
    pub cached: usize,
    pub failed: usize,
    pub skipped: usize,
    /// Computed or cached instances with flags (also counted in `computed` or `cached`).
    pub flagged: usize,
    /// Corrupt cache entries found, discarded and recomputed.
    pub discarded: usize,
    /// Computed results not stored in the cache (a read-only cache, a full disk, …): said once
    /// by a warning, counted here.
    pub not_stored: usize,
    /// The run stopped early on [`Progress::cancelled`]: some needed instances never ran.
    pub cancelled: bool,
    pub wall_seconds: f64,
    /// The process's peak resident set (`VmHWM`) when the run ended, bytes; `None` where the
    /// system does not say (not Linux).
    pub peak_resident_bytes: Option<u64>,
}

impl RunReport {
    /// `true` when every needed instance computed (flagged ones included).
    pub fn all_ok(&self) -> bool {
        self.failed == 0 && self.skipped == 0 && !self.cancelled
    }
}

/// Runs the instances of `plan` that `options.tables` need.
pub fn execute(
    plan: &Plan,
    cache: &Cache,
    options: &ExecuteOptions,
    progress: &dyn Progress,
) -> Result<RunReport, CacheError> {
    let needed = plan.needed_for(&options.tables);
    execute_nodes(plan, cache, &needed, options, progress)
}

/// Runs the given instances (a shard's share) and everything upstream of them;
/// `options.tables` is not consulted.
pub fn execute_nodes(
    plan: &Plan,
    cache: &Cache,
    nodes: &[usize],
    options: &ExecuteOptions,
    progress: &dyn Progress,
) -> Result<RunReport, CacheError> {
    let start = Instant::now();
    let storing = prepare_cache(cache, progress)?;
    let needed = plan.upstream_closure(nodes, None);
    let n = plan.nodes.len();
    let (wants_payload, dependants) = payload_needs(plan, cache, &needed);
    let Schedule {
        waiting,
        downstream,
        level,
        ready,
    } = Schedule::of(plan, &needed);
    progress.start(needed.len());
    let budget = MemoryBudget::for_process(options.memory_budget);
    let shared = Mutex::new(Shared {
        artifacts: (0..n).map(|_| None).collect(),
        outcomes: vec![None; n],
        dependants,
        waiting,
        ready,
        running: 0,
        storing,
        report: RunReport::default(),
    });
    let ctx = RunContext {
        plan,
        cache,
        options,
        progress,
        budget: &budget,
        shared: &shared,
        wants_payload: &wants_payload,
        downstream: &downstream,
        level: &level,
        slots: rayon::current_num_threads().max(1),
    };
    rayon::scope(|scope| ctx.spawn_pulls(scope));
    let Shared {
        outcomes,
        mut report,
        ..
    } = shared.into_inner().unwrap_or_else(|p| p.into_inner());
    report.cancelled = progress.cancelled() && needed.iter().any(|&i| outcomes[i].is_none());
    report.outcomes = outcomes;
    report.wall_seconds = start.elapsed().as_secs_f64();
    report.peak_resident_bytes = process_memory::peak_resident_bytes();
    Ok(report)
}

/// Removes temporary folders of interrupted runs (with a warning) and says whether this run can
/// store its results (a read-only cache is one warning, not one per node).
fn prepare_cache(cache: &Cache, progress: &dyn Progress) -> Result<Storing, CacheError> {
    let stale = cache.clean_stale_tmp()?;
    if stale > 0 {
        progress.warn(&format!(
            "removed {stale} temporary cache folder(s) left by interrupted runs"
        ));
    }
    Ok(match cache_access::probe(cache) {
        Ok(()) => Storing::Yes,
        Err(e) => {
            progress.warn(&cache_access::read_only_warning(cache, &e));
            Storing::No
        }
    })
}

/// What the running instances share.
struct Shared {
    /// Artifacts that dependants yet to run still need, each charged its size.
    artifacts: Vec<Option<Held>>,
    outcomes: Vec<Option<NodeOutcome>>,
    /// Per instance, its needed dependants that have not finished: its artifact is released at 0.
    dependants: Vec<usize>,
    /// Per instance, its upstream instances that have not finished: it is ready at 0.
    waiting: Vec<usize>,
    /// Ready instances by priority: the deepest (longest upstream chain) first, then the first
    /// in plan order.
    ready: BinaryHeap<(usize, Reverse<usize>)>,
    /// Instances being loaded or computed.
    running: usize,
    /// Whether computed results are stored in the cache.
    storing: Storing,
    report: RunReport,
}

/// A node's upstream artifacts, and the charges of those read or computed for it alone.
type Inputs = (Vec<Arc<Artifact>>, Vec<Charge>);

struct RunContext<'a> {
    plan: &'a Plan,
    cache: &'a Cache,
    options: &'a ExecuteOptions,
    progress: &'a dyn Progress,
    budget: &'a Arc<MemoryBudget>,
    shared: &'a Mutex<Shared>,
    /// Per instance, whether its arrays are loaded from the cache (a dependant will be computed).
    wants_payload: &'a [bool],
    /// Per instance, its needed dependants.
    downstream: &'a [Vec<usize>],
    /// Per instance, the length of its longest upstream chain (0 for a surface).
    level: &'a [usize],
    /// Instances that may run at once: the pool's thread count.
    slots: usize,
}

impl<'a> RunContext<'a> {
    /// Spawns one [`Self::pull`] per slot.
    fn spawn_pulls<'s>(&'s self, scope: &rayon::Scope<'s>)
    where
        'a: 's,
    {
        for _ in 0..self.slots {
            scope.spawn(move |scope| self.pull(scope));
        }
    }

    /// Runs the ready instance of highest priority, if a slot is free, then spawns new pulls.
    ///
    /// At most one instance per pool thread runs at once (a pull taken by a thread that waits
    /// inside a running node's parallel loop finds no free slot and returns), and the deepest
    /// ready instance goes first: a chain once started (surfaces, their contact, its friction)
    /// is finished before the next one is begun, and each artifact is released after its last
    /// dependant, so only a few chains' arrays are in memory at once, however many scenarios
    /// the study has. A node's own parallel loops still use every thread of the pool.
    fn pull<'s>(&'s self, scope: &rayon::Scope<'s>)
    where
        'a: 's,
    {
        let Some((i, charge)) = self.take_ready() else {
            return;
        };
        let (outcome, artifact) = self.run_node(i, self.wants_payload[i]);
        self.progress.finished(&self.plan.nodes[i], &outcome.status);
        self.finish(i, outcome, artifact, charge);
        self.spawn_pulls(scope);
    }

    /// The ready instance of highest priority, with the charge of its memory estimate, if a slot
    /// is free and the estimate fits the budget beside what is charged already. When it does not
    /// fit, it waits for a running instance to finish (nothing of lower priority overtakes it);
    /// when nothing runs, the artifacts held for other instances are let go (their dependants
    /// read them again from the cache) and it is admitted: a node larger than the whole budget
    /// then fails in [`Self::over_budget`], a cached one is loaded.
    fn take_ready(&self) -> Option<(usize, Charge)> {
        if self.progress.cancelled() {
            return None;
        }
        let mut shared = self.lock();
        if shared.running >= self.slots {
            return None;
        }
        let &(_, Reverse(i)) = shared.ready.peek()?;
        let estimate = self.plan.nodes[i].task.memory_estimate();
        let charge = match self.budget.try_charge(estimate) {
            Some(charge) => charge,
            None if shared.running > 0 => return None,
            None => {
                let upstream = &self.plan.nodes[i].upstream;
                for (u, held) in shared.artifacts.iter_mut().enumerate() {
                    if !upstream.iter().any(|(_, v)| *v == u) {
                        *held = None;
                    }
                }
                self.budget.force(estimate)
            }
        };
        shared.ready.pop();
        shared.running += 1;
        Some((i, charge))
    }

    /// Records the result of instance `i`, holds its artifact for its dependants (charged its
    /// size) and returns its admission `charge`, releases the artifacts no dependant needs any
    /// more and queues the dependants that became ready.
    fn finish(
        &self,
        i: usize,
        outcome: NodeOutcome,
        artifact: Option<Arc<Artifact>>,
        charge: Charge,
    ) {
        let mut shared = self.lock();
        if shared.dependants[i] > 0 {
            shared.artifacts[i] = artifact.map(|a| Held::new(a, self.budget));
        }
        drop(charge);
        self.budget
            .keep(outcome.tables.values().map(table_bytes).sum());
        shared.running -= 1;
        let report = &mut shared.report;
        match &outcome.status {
            NodeStatus::Computed => report.computed += 1,
            NodeStatus::Cached => report.cached += 1,
            NodeStatus::Failed(_) => report.failed += 1,
            NodeStatus::Skipped(_) => report.skipped += 1,
        }
        if outcome.is_flagged() {
            report.flagged += 1;
        }
        shared.outcomes[i] = Some(outcome);
        for (_, u) in &self.plan.nodes[i].upstream {
            shared.dependants[*u] -= 1;
            if shared.dependants[*u] == 0 {
                shared.artifacts[*u] = None;
            }
        }
        for &d in &self.downstream[i] {
            shared.waiting[d] -= 1;
            if shared.waiting[d] == 0 {
                shared.ready.push((self.level[d], Reverse(d)));
            }
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Shared> {
        self.shared.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Loads or computes instance `i`. Returns the outcome and the artifact (for dependants).
    fn run_node(&self, i: usize, with_payload: bool) -> (NodeOutcome, Option<Arc<Artifact>>) {
        let node = &self.plan.nodes[i];
        for (role, u) in &node.upstream {
            let upstream_ok = self.lock().outcomes[*u]
                .as_ref()
                .map(|o| matches!(o.status, NodeStatus::Computed | NodeStatus::Cached));
            if upstream_ok == Some(false) {
                let names = self.plan.nodes[*u].names.join(", ");
                let status =
                    NodeStatus::Skipped(format!("upstream {role} node '{names}' did not compute"));
                return (failed_outcome(status), None);
            }
        }
        match self.load(node, with_payload) {
            Some(entry)
                if with_payload && node.task.array_storage() == ArrayStorage::Regenerate =>
            {
                self.regenerate(node, entry)
            }
            Some(entry)
                if with_payload && matches!(node.task.array_storage(), ArrayStorage::Derive(_)) =>
            {
                self.derive(node, entry)
            }
            Some(CachedEntry { manifest, artifact }) => {
                let outcome = |metrics, tables, flags| NodeOutcome {
                    status: NodeStatus::Cached,
                    metrics,
                    tables,
                    flags,
                    compute_seconds: manifest.compute_seconds,
                };
                if with_payload {
                    let row = outcome(
                        artifact.metrics.clone(),
                        artifact.tables.clone(),
                        artifact.flags.clone(),
                    );
                    (row, Some(Arc::new(artifact)))
                } else {
                    (
                        outcome(artifact.metrics, artifact.tables, artifact.flags),
                        None,
                    )
                }
            }
            None => self.compute(node),
        }
    }

    /// The verified cache entry of `node`, or `None` to compute it: not cached, unreadable (a
    /// warning), or corrupt (a warning; the entry is discarded and counted).
    fn load(&self, node: &PlannedNode, with_arrays: bool) -> Option<CachedEntry> {
        let kind = node.task.kind();
        match self.cache.load(kind, &node.key, with_arrays) {
            Ok(entry) => entry,
            Err(CacheError::Corrupt { path, reason }) => {
                self.progress.warn(&format!(
                    "discarding corrupt cache entry {} ({reason}); recomputing",
                    path.display()
                ));
                if let Some(Err(e)) = self.write(|| self.cache.discard(kind, &node.key)) {
                    self.progress.warn(&e.to_string());
                }
                self.lock().report.discarded += 1;
                None
            }
            Err(e) => {
                self.progress
                    .warn(&format!("cache read failed: {e}; recomputing"));
                None
            }
        }
    }

    /// Computes a node from its upstream artifacts (loading any that are not in memory; the
    /// caller holds the charge of its own estimate), turning a panic into a failure. Returns the
    /// result and its time.
    fn run_compute(&self, node: &PlannedNode) -> (Result<Artifact, NodeOutcome>, f64) {
        if let Some(failed) = self.over_budget(node) {
            return (Err(failed_outcome(failed)), 0.0);
        }
        let (inputs, _charges) = match self.upstream_artifacts(node) {
            Ok(inputs) => inputs,
            Err(failed) => return (Err(failed), 0.0),
        };
        let input_refs: Vec<&Artifact> = inputs.iter().map(Arc::as_ref).collect();
        let start = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| node.task.compute(&input_refs)))
            .unwrap_or_else(|panic| Err(internal_error(panic)));
        let seconds = start.elapsed().as_secs_f64();
        (
            result.map_err(|e| failed_outcome(NodeStatus::Failed(e.message))),
            seconds,
        )
    }

    /// The artifacts (with arrays) of `node`'s upstream instances, in its order, and the charges
    /// of those not held in memory. Present when loaded with arrays or computed in this run;
    /// otherwise (loaded metrics-only because its dependants were cached, then one turned out
    /// corrupt, or let go to admit another instance) an upstream entry is read again with its
    /// arrays (and its derived arrays derived), or recomputed if they are not stored or that read
    /// finds the entry gone or corrupt, charged its memory estimate until `node` is done.
    fn upstream_artifacts(&self, node: &PlannedNode) -> Result<Inputs, NodeOutcome> {
        let mut inputs = Vec::with_capacity(node.upstream.len());
        let mut charges = Vec::new();
        for (role, u) in &node.upstream {
            let upstream = &self.plan.nodes[*u];
            let in_memory = self.lock().artifacts[*u]
                .as_ref()
                .map(|held| Arc::clone(&held.artifact));
            if in_memory.is_none() {
                charges.push(self.budget.force(upstream.task.memory_estimate()));
            }
            let fail = |what: &str, failed: NodeOutcome| {
                let message = format!("{what} upstream {role} node: {}", failed.status.message());
                failed_outcome(NodeStatus::Failed(message))
            };
            let artifact = match in_memory {
                Some(a) => a,
                None if upstream.task.array_storage() == ArrayStorage::Regenerate => {
                    match self.run_compute(upstream) {
                        (Ok(artifact), _) => Arc::new(artifact),
                        (Err(failed), _) => return Err(fail("cannot regenerate", failed)),
                    }
                }
                None => match self
                    .load(upstream, true)
                    .map(|e| self.complete(upstream, e))
                {
                    Some(Ok(artifact)) => Arc::new(artifact),
                    _ => match self.compute(upstream) {
                        (_, Some(artifact)) => artifact,
                        (failed, None) => return Err(fail("cannot load or recompute", failed)),
                    },
                },
            };
            inputs.push(artifact);
        }
        Ok((inputs, charges))
    }

    /// The failure of a node whose memory estimate, its inputs held in memory and the process's
    /// base together exceed the whole budget (an input read again for it is charged when read),
    /// or of every node when the budget cannot hold the writing of the results: checked before it
    /// reads its inputs and allocates, so `--memory-mib` bounds what a run may allocate.
    fn over_budget(&self, node: &PlannedNode) -> Option<NodeStatus> {
        let estimate = node.task.memory_estimate();
        let inputs: u64 = {
            let shared = self.lock();
            node.upstream
                .iter()
                .filter_map(|(_, u)| shared.artifacts[*u].as_ref())
                .map(|held| artifact_bytes(&held.artifact))
                .sum()
        };
        let (base, total) = (self.budget.base(), self.budget.total());
        let needed = estimate.saturating_add(inputs).saturating_add(base);
        let results = self.budget.results();
        let mib = |bytes: u64| bytes.div_ceil(1 << 20);
        if needed <= total && results > total {
            return Some(NodeStatus::Failed(format!(
                "the run's budget of {} MiB is below the {} MiB the process needs to write the \
                 results: raise `--memory-mib` to at least {} (default 60 % of the available \
                 memory)",
                mib(total),
                mib(results),
                mib(results.max(needed))
            )));
        }
        if needed <= total {
            return None;
        }
        let inputs = match inputs {
            0 => String::new(),
            bytes => format!(" its inputs' {} MiB and", mib(bytes)),
        };
        Some(NodeStatus::Failed(format!(
            "needs about {} MiB of memory, which with{inputs} the process's own {} MiB exceeds \
             the run's budget of {} MiB: raise `--memory-mib` to at least {} (default 60 % of \
             the available memory) or make the node smaller (a coarser grid, fewer fields)",
            mib(estimate),
            mib(base),
            mib(total),
            mib(needed)
        )))
    }

    fn compute(&self, node: &PlannedNode) -> (NodeOutcome, Option<Arc<Artifact>>) {
        match self.run_compute(node) {
            (Ok(artifact), seconds) => self.store_computed(node, artifact, seconds),
            (Err(failed), _) => (failed, None),
        }
    }
}

/// The failure of a node kind's code that panicked (with the panic's text).
fn internal_error(panic: Box<dyn std::any::Any + Send>) -> NodeError {
    let what = panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_default();
    NodeError::new(format!(
        "internal error (panic: {what}); please report it with the study file"
    ))
}

fn failed_outcome(status: NodeStatus) -> NodeOutcome {
    NodeOutcome {
        status,
        metrics: Vec::new(),
        tables: BTreeMap::new(),
        flags: Vec::new(),
        compute_seconds: 0.0,
    }
}
