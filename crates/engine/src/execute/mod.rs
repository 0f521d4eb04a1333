//! Execution: load what the cache has, compute the rest in parallel, upstream first.
//!
//! Only instances the requested tables need are touched. Instances run in parallel on the rayon
//! pool as soon as their upstream finished, deepest first (see `RunContext::pull`), each first
//! acquiring its memory estimate from a budget so large nodes do not run all at once. A failing
//! node fails only its dependants; a flagged one (computed, with sentences its row must be read
//! with, [`Artifact::flags`]) is used by them like any other.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use crate::artifact::Artifact;
use crate::cache::{Cache, CacheError, CachedEntry};
use crate::hash::NodeKey;
use crate::node::{ArrayStorage, NodeError};
use crate::plan::{Plan, PlannedNode};

mod cache_access;
mod derive;
mod memory_budget;
mod outcome;
mod store;
mod store_gate;

use memory_budget::MemoryBudget;
pub use outcome::{NodeOutcome, NodeStatus};
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
    /// Memory budget for concurrently running nodes, bytes.
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
    let budget = MemoryBudget::new(options.memory_budget);
    let shared = Mutex::new(Shared {
        artifacts: vec![None; n],
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

/// Which instances of `needed` must be loaded with their arrays (a dependant will be computed,
/// or derives its arrays from them) and how many dependants each has.
fn payload_needs(plan: &Plan, cache: &Cache, needed: &[usize]) -> (Vec<bool>, Vec<usize>) {
    let n = plan.nodes.len();
    let entries: Vec<(&str, &NodeKey)> = needed
        .iter()
        .map(|&i| (plan.nodes[i].task.kind(), &plan.nodes[i].key))
        .collect();
    let mut in_cache = vec![false; n];
    for (&i, present) in needed.iter().zip(cache.present(&entries)) {
        in_cache[i] = present;
    }
    let mut wants_payload = vec![false; n];
    let mut dependants = vec![0usize; n];
    for &i in needed {
        for (_, u) in &plan.nodes[i].upstream {
            dependants[*u] += 1;
            if !in_cache[i] {
                wants_payload[*u] = true;
            }
        }
    }
    for &i in needed.iter().rev() {
        if wants_payload[i] && matches!(plan.nodes[i].task.array_storage(), ArrayStorage::Derive(_))
        {
            for (_, u) in &plan.nodes[i].upstream {
                wants_payload[*u] = true;
            }
        }
    }
    (wants_payload, dependants)
}

/// The order instances run in: each as soon as its upstream finished, deepest first (see
/// [`RunContext::pull`]).
struct Schedule {
    /// Upstream instances not yet finished.
    waiting: Vec<usize>,
    /// The dependants of each instance.
    downstream: Vec<Vec<usize>>,
    /// Depth in the DAG (0: no upstream).
    level: Vec<usize>,
    /// The instances with nothing to wait for.
    ready: BinaryHeap<(usize, Reverse<usize>)>,
}

impl Schedule {
    fn of(plan: &Plan, needed: &[usize]) -> Schedule {
        let n = plan.nodes.len();
        let mut waiting = vec![0usize; n];
        let mut downstream: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut level = vec![0usize; n];
        for &i in needed {
            for (_, u) in &plan.nodes[i].upstream {
                waiting[i] += 1;
                downstream[*u].push(i);
                level[i] = level[i].max(level[*u] + 1);
            }
        }
        let ready = needed
            .iter()
            .filter(|&&i| waiting[i] == 0)
            .map(|&i| (level[i], Reverse(i)))
            .collect();
        Schedule {
            waiting,
            downstream,
            level,
            ready,
        }
    }
}

/// What the running instances share.
struct Shared {
    /// Artifacts that dependants yet to run still need.
    artifacts: Vec<Option<Arc<Artifact>>>,
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

struct RunContext<'a> {
    plan: &'a Plan,
    cache: &'a Cache,
    options: &'a ExecuteOptions,
    progress: &'a dyn Progress,
    budget: &'a MemoryBudget,
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
        let Some(i) = self.take_ready() else {
            return;
        };
        let (outcome, artifact) = self.run_node(i, self.wants_payload[i]);
        self.progress.finished(&self.plan.nodes[i], &outcome.status);
        self.finish(i, outcome, artifact);
        self.spawn_pulls(scope);
    }

    fn take_ready(&self) -> Option<usize> {
        if self.progress.cancelled() {
            return None;
        }
        let mut shared = self.lock();
        if shared.running >= self.slots {
            return None;
        }
        let (_, Reverse(i)) = shared.ready.pop()?;
        shared.running += 1;
        Some(i)
    }

    /// Records the result of instance `i`, releases the artifacts no dependant needs any more and
    /// queues the dependants that became ready.
    fn finish(&self, i: usize, outcome: NodeOutcome, artifact: Option<Arc<Artifact>>) {
        let mut shared = self.lock();
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
        if shared.dependants[i] > 0 {
            shared.artifacts[i] = artifact;
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

    /// Computes a node from its upstream artifacts (loading any that are not in memory), under
    /// the memory budget, turning a panic into a failure. Returns the result and its time.
    fn run_compute(&self, node: &PlannedNode) -> (Result<Artifact, NodeOutcome>, f64) {
        let inputs = match self.upstream_artifacts(node) {
            Ok(inputs) => inputs,
            Err(failed) => return (Err(failed), 0.0),
        };
        let input_refs: Vec<&Artifact> = inputs.iter().map(Arc::as_ref).collect();
        let estimate = node.task.memory_estimate();
        if estimate > self.budget.total() {
            return (
                Err(failed_outcome(over_budget(estimate, self.budget.total()))),
                0.0,
            );
        }
        let _permit = self.budget.acquire(estimate);
        let start = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| node.task.compute(&input_refs)))
            .unwrap_or_else(|panic| Err(internal_error(panic)));
        let seconds = start.elapsed().as_secs_f64();
        (
            result.map_err(|e| failed_outcome(NodeStatus::Failed(e.message))),
            seconds,
        )
    }

    /// The artifacts (with arrays) of `node`'s upstream instances, in its order. Present when
    /// loaded with arrays or computed in this run; otherwise (loaded metrics-only because its
    /// dependants were cached, then one turned out corrupt) an upstream entry is read again with
    /// its arrays (and its derived arrays derived), or recomputed if they are not stored or that
    /// read finds the entry gone or corrupt.
    fn upstream_artifacts(&self, node: &PlannedNode) -> Result<Vec<Arc<Artifact>>, NodeOutcome> {
        let mut inputs = Vec::with_capacity(node.upstream.len());
        for (role, u) in &node.upstream {
            let upstream = &self.plan.nodes[*u];
            let in_memory = self.lock().artifacts[*u].clone();
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
        Ok(inputs)
    }

    fn compute(&self, node: &PlannedNode) -> (NodeOutcome, Option<Arc<Artifact>>) {
        match self.run_compute(node) {
            (Ok(artifact), seconds) => self.store_computed(node, artifact, seconds),
            (Err(failed), _) => (failed, None),
        }
    }
}

/// The failure of a node whose memory estimate exceeds the whole budget: checked before its
/// inputs' arrays meet its own allocations, so `--memory-mib` bounds what a run may allocate.
fn over_budget(estimate: u64, budget: u64) -> NodeStatus {
    let mib = |bytes: u64| bytes.div_ceil(1 << 20);
    NodeStatus::Failed(format!(
        "needs about {} MiB of memory, more than the run's budget of {} MiB: raise \
         `--memory-mib` (default 60 % of the available memory) or make the node smaller (a \
         coarser grid, fewer fields)",
        mib(estimate),
        mib(budget)
    ))
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
