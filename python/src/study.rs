//! Studies from Python: `run_study`, `plan_study`, `validate_study`, and `StudyError`.
//!
//! A run executes on its own thread with the GIL released while the calling thread waits for
//! the engine's progress events; between events (at least every 100 ms) it takes the GIL, hands
//! the events to the Python callback and checks for signals. A `KeyboardInterrupt` raises the
//! engine's cancellation flag ([`Progress::cancelled`]): no further node starts, the running ones
//! finish and are stored, so the cache holds only complete entries, no results folder is
//! written, and the interrupt is raised once the run thread is done.

use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError, Sender};
use std::sync::Mutex;
use std::time::Duration;

use asperity::engine::cache::Cache;
use asperity::engine::execute::{execute, NodeStatus, Progress, RunReport};
use asperity::engine::plan::{Plan, PlannedNode};
use asperity::engine::study::{ParameterOverride, Study, StudyError as EngineStudyError};
use asperity::nodes::TribologyNode;
use asperity::study_run;
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyRuntimeError, PyUserWarning};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::guard::{compute, panic_error, value_error};

create_exception!(
    asperity,
    StudyError,
    PyException,
    "A broken study file: `file`, `line`, `column` (None when unknown), `context` and \
     `message`; str() is the text the command line prints after `error:`."
);

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run_study, m)?)?;
    m.add_function(wrap_pyfunction!(plan_study, m)?)?;
    m.add_function(wrap_pyfunction!(validate_study, m)?)?;
    Ok(())
}

/// The Python `StudyError` of an engine study error, with its location as attributes.
fn study_error(py: Python<'_>, e: &EngineStudyError) -> PyErr {
    let err = StudyError::new_err(e.to_string());
    let value = err.value(py);
    let known = e.location.is_known();
    let _ = value.setattr("file", e.path.display().to_string());
    let _ = value.setattr("context", e.context.as_str());
    let _ = value.setattr("message", e.message.as_str());
    let _ = value.setattr("line", known.then_some(e.location.line));
    let _ = value.setattr("column", known.then_some(e.location.column));
    err
}

fn overrides(set: &[String]) -> PyResult<Vec<ParameterOverride>> {
    set.iter()
        .map(|s| ParameterOverride::from_str(s).map_err(|e| value_error("set", e)))
        .collect()
}

/// Loads and plans a study with the GIL released.
fn load(py: Python<'_>, study: &Path, set: &[String]) -> PyResult<(Study<TribologyNode>, Plan)> {
    let set = overrides(set)?;
    let loaded = compute(py, || Ok(study_run::load_study(study, &set)))?;
    loaded.map_err(|e| study_error(py, &e))
}

fn open_cache(cache: Option<PathBuf>) -> PyResult<Cache> {
    let dir = study_run::cache_dir(cache);
    Cache::open(&dir).map_err(|e| {
        PyRuntimeError::new_err(format!("cannot open the cache at {}: {e}", dir.display()))
    })
}

/// `validate(study, set)`: the study's counts, or `StudyError`.
#[pyfunction]
#[pyo3(signature = (study, set=Vec::new()))]
fn validate_study<'py>(
    py: Python<'py>,
    study: PathBuf,
    set: Vec<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let (loaded, plan) = load(py, &study, &set)?;
    let d = PyDict::new(py);
    d.set_item("study", loaded.name())?;
    d.set_item("scenarios", plan.scenarios.rows.len())?;
    d.set_item("nodes", plan.node_names.len())?;
    d.set_item("instances", plan.nodes.len())?;
    d.set_item("unused_parameters", plan.unused_parameters.clone())?;
    Ok(d)
}

/// `plan(study, set, cache)`: each needed instance with its key, kind, version, node names and
/// whether the cache holds it.
#[pyfunction]
#[pyo3(signature = (study, set=Vec::new(), cache=None))]
fn plan_study<'py>(
    py: Python<'py>,
    study: PathBuf,
    set: Vec<String>,
    cache: Option<PathBuf>,
) -> PyResult<Bound<'py, PyList>> {
    let (loaded, plan) = load(py, &study, &set)?;
    let cache = open_cache(cache)?;
    let rows = PyList::empty(py);
    for i in plan.needed_for(&loaded.outputs) {
        let n = &plan.nodes[i];
        let d = PyDict::new(py);
        d.set_item("key", n.key.to_string())?;
        d.set_item("kind", n.task.kind())?;
        d.set_item("version", n.task.version())?;
        d.set_item("nodes", n.names.clone())?;
        d.set_item("cached", cache.contains(n.task.kind(), &n.key))?;
        rows.append(d)?;
    }
    Ok(rows)
}

/// What the run thread tells the calling thread.
enum Event {
    Start(usize),
    Finished { node: String, status: &'static str },
    Warn(String),
}

/// The engine's progress, forwarded as events; cancelled once the caller raises the flag.
struct ChannelProgress<'a> {
    events: Mutex<Sender<Event>>,
    cancel: &'a AtomicBool,
}

impl ChannelProgress<'_> {
    fn send(&self, event: Event) {
        if let Ok(sender) = self.events.lock() {
            let _ = sender.send(event);
        }
    }
}

impl Progress for ChannelProgress<'_> {
    fn start(&self, total: usize) {
        self.send(Event::Start(total));
    }

    fn finished(&self, node: &PlannedNode, status: &NodeStatus) {
        let status = match status {
            NodeStatus::Computed => "computed",
            NodeStatus::Cached => "cached",
            NodeStatus::Failed(_) => "failed",
            NodeStatus::Skipped(_) => "skipped",
        };
        let node = format!("{} {}", node.task.kind(), node.names.join(","));
        self.send(Event::Finished { node, status });
    }

    fn warn(&self, message: &str) {
        self.send(Event::Warn(message.to_string()));
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }
}

/// Settings of one run.
struct RunSettings {
    out: PathBuf,
    cache: Cache,
    jobs: Option<usize>,
    memory_budget: u64,
}

/// The CLI's checks of the results folder (another study's results are refused unless
/// `force`); its warnings as Python `UserWarning`s.
fn check_results_folder(
    py: Python<'_>,
    loaded: &Study<TribologyNode>,
    out: &Path,
    force: bool,
) -> PyResult<()> {
    for warning in
        study_run::check_results_folder(loaded, out, force).map_err(|e| value_error("out", e))?
    {
        PyErr::warn(
            py,
            &py.get_type::<PyUserWarning>(),
            &CString::new(warning)?,
            1,
        )?;
    }
    Ok(())
}

/// `run(study, set, out, cache, jobs, memory_mib, progress)`: runs the study and, unless
/// interrupted, writes its tables; returns `(folder, files, report)` where `report` counts the instances and lists the
/// failures and flags. `progress(event, a, b)` is called with `("start", total, "")`,
/// `("node", status, "kind names")` and `("warning", message, "")`.
#[pyfunction]
#[pyo3(signature = (study, set=Vec::new(), out=None, cache=None, jobs=None, memory_mib=None, progress=None, force=false))]
#[allow(clippy::too_many_arguments)]
fn run_study<'py>(
    py: Python<'py>,
    study: PathBuf,
    set: Vec<String>,
    out: Option<PathBuf>,
    cache: Option<PathBuf>,
    jobs: Option<usize>,
    memory_mib: Option<u64>,
    progress: Option<Bound<'py, PyAny>>,
    force: bool,
) -> PyResult<Bound<'py, PyAny>> {
    if jobs == Some(0) {
        return Err(value_error("jobs", "must be at least 1 (worker threads)"));
    }
    let (loaded, plan) = load(py, &study, &set)?;
    let out = out.unwrap_or_else(|| study_run::default_out(&loaded));
    check_results_folder(py, &loaded, &out, force)?;
    let settings = RunSettings {
        out,
        cache: open_cache(cache)?,
        jobs,
        memory_budget: memory_mib
            .map(|m| m.saturating_mul(1 << 20))
            .unwrap_or_else(study_run::default_memory_budget),
    };
    let cancel = AtomicBool::new(false);
    let (sender, receiver) = channel();
    let receiver = Mutex::new(receiver);
    let reporter = ChannelProgress {
        events: Mutex::new(sender),
        cancel: &cancel,
    };
    let mut interrupt: Option<PyErr> = None;
    let outcome = std::thread::scope(|scope| {
        let worker = scope.spawn(|| {
            let reporter = reporter;
            catch_run(&loaded, &plan, &settings, &reporter)
        });
        loop {
            let next = py.detach(|| match receiver.lock() {
                Ok(r) => r.recv_timeout(Duration::from_millis(100)),
                Err(_) => Err(RecvTimeoutError::Disconnected),
            });
            match next {
                Ok(event) => deliver(progress.as_ref(), event, &mut interrupt),
                Err(RecvTimeoutError::Timeout) => {}
                Err(RecvTimeoutError::Disconnected) => break,
            }
            if interrupt.is_none() {
                if let Err(e) = py.check_signals() {
                    interrupt = Some(e);
                }
            }
            if interrupt.is_some() {
                cancel.store(true, Ordering::Relaxed);
            }
        }
        py.detach(|| worker.join())
    });
    if let Some(e) = interrupt {
        return Err(e);
    }
    let report = match outcome {
        Ok(result) => result?,
        Err(payload) => return Err(panic_error(payload.as_ref())),
    };
    let files = compute(py, || {
        study_run::write_results(&loaded, &plan, &report, &settings.out)
            .map_err(|e| PyRuntimeError::new_err(format!("writing the tables: {e}")))
    })?;
    let report = report_dict(py, &plan, &report)?;
    (settings.out, files, report)
        .into_pyobject(py)
        .map(|t| t.into_any())
}

/// Hands one event to the callback; an exception in it stops the run like an interrupt.
fn deliver(callback: Option<&Bound<'_, PyAny>>, event: Event, interrupt: &mut Option<PyErr>) {
    let Some(callback) = callback else { return };
    let result = match event {
        Event::Start(total) => callback.call1(("start", total, "")),
        Event::Finished { node, status } => callback.call1(("node", status, node)),
        Event::Warn(message) => callback.call1(("warning", message, "")),
    };
    if let Err(e) = result {
        if interrupt.is_none() {
            *interrupt = Some(e);
        }
    }
}

/// Executes the plan on the settings' thread pool.
fn catch_run(
    study: &Study<TribologyNode>,
    plan: &Plan,
    settings: &RunSettings,
    progress: &ChannelProgress<'_>,
) -> PyResult<RunReport> {
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(jobs) = settings.jobs {
        pool = pool.num_threads(jobs);
    }
    let pool = pool
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the worker threads: {e}")))?;
    let options = study_run::execute_options(study, settings.memory_budget);
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        pool.install(|| execute(plan, &settings.cache, &options, progress))
    }))
    .map_err(|payload| panic_error(payload.as_ref()))?
    .map_err(|e| PyRuntimeError::new_err(format!("cache: {e}")))
}

/// The counts of a run, and one `(kind, nodes, message)` per failure and per flag.
fn report_dict<'py>(
    py: Python<'py>,
    plan: &Plan,
    report: &RunReport,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("computed", report.computed)?;
    d.set_item("cached", report.cached)?;
    d.set_item("failed", report.failed)?;
    d.set_item("skipped", report.skipped)?;
    d.set_item("flagged", report.flagged)?;
    d.set_item("discarded", report.discarded)?;
    d.set_item("wall_seconds", report.wall_seconds)?;
    let (mut failures, mut flags) = (Vec::new(), Vec::new());
    for (i, outcome) in report.outcomes.iter().enumerate() {
        let Some(outcome) = outcome else { continue };
        let node = &plan.nodes[i];
        let who = (node.task.kind(), node.names.join(", "));
        match &outcome.status {
            NodeStatus::Failed(m) | NodeStatus::Skipped(m) => {
                failures.push((who.0, who.1.clone(), m.clone()))
            }
            _ => {}
        }
        for flag in &outcome.flags {
            flags.push((who.0, who.1.clone(), flag.clone()));
        }
    }
    d.set_item("failures", failures)?;
    d.set_item("flags", flags)?;
    Ok(d)
}
