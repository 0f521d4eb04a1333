//! A study run from a file to a results folder, in the steps every front end shares (the
//! `asperity` command and the Python package): load and plan, execute, write the tables. Only
//! the front ends print or report progress; this module returns typed errors.

use std::path::{Path, PathBuf};

use crate::engine::execute::{ExecuteOptions, RunReport};
use crate::engine::output::{OutputError, OutputMetadata, ResultSet};
use crate::engine::plan::Plan;
use crate::engine::study::{ParameterOverride, Study, StudyError};
use crate::nodes::TribologyNode;

/// Reads the study at `path`, applies the `--set` overrides and builds its plan.
pub fn load_study(
    path: &Path,
    overrides: &[ParameterOverride],
) -> Result<(Study<TribologyNode>, Plan), StudyError> {
    let mut study = Study::<TribologyNode>::load(path)?;
    study.apply_overrides(overrides)?;
    let plan = Plan::build(&study)?;
    Ok((study, plan))
}

/// The execution settings of a whole-study run: the study's tables, `memory_budget` bytes for
/// the nodes running at once and this tool's version in the manifests.
pub fn execute_options(study: &Study<TribologyNode>, memory_budget: u64) -> ExecuteOptions {
    ExecuteOptions {
        tables: study.outputs.clone(),
        memory_budget,
        tool_version: crate::TOOL_VERSION.to_string(),
    }
}

/// The cache folder: `explicit`, else `$ASPERITY_CACHE`, else `./cache`.
pub fn cache_dir(explicit: Option<PathBuf>) -> PathBuf {
    explicit
        .or_else(|| std::env::var_os("ASPERITY_CACHE").map(PathBuf::from))
        .unwrap_or_else(|| PathBuf::from("cache"))
}

/// The default results folder of a study: `results/<study name>`.
pub fn default_out(study: &Study<TribologyNode>) -> PathBuf {
    PathBuf::from("results").join(study.name())
}

/// Writes the run's tables, summaries and timings into `out`, replacing it in one step; returns
/// the files written.
pub fn write_results(
    study: &Study<TribologyNode>,
    plan: &Plan,
    report: &RunReport,
    out: &Path,
) -> Result<Vec<PathBuf>, OutputError> {
    let meta = OutputMetadata {
        study: study.name().to_string(),
        study_file_hash: study.file_hash.clone(),
        tool_version: crate::TOOL_VERSION.to_string(),
        overrides: study.overrides.clone(),
    };
    let mut set = ResultSet::stage(out)?;
    set.write_tables(plan, report, &study.outputs, &meta)?;
    set.write_summaries(plan, report, &study.file.summaries, &meta)?;
    set.write_timings(plan, report, &meta)?;
    set.publish()
}

/// 60 % of MemAvailable from /proc/meminfo, or 4 GiB when it cannot be read.
pub fn default_memory_budget() -> u64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("MemAvailable:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<u64>().ok())
        })
        .map_or(4 << 30, |kb| kb * 1024 / 10 * 6)
}
