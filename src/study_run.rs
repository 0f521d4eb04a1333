//! A study run from a file to a results folder, in the steps every front end shares (the
//! `asperity` command and the Python package): load and plan, execute, write the tables. Only
//! the front ends print or report progress; this module returns typed errors.

use std::path::{Path, PathBuf};

use crate::engine::execute::{ExecuteOptions, RunReport};
use crate::engine::output::{
    check_target, remove_stale_stagings, results_origin, OutputError, OutputMetadata, ResultSet,
};
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

/// Why a run may not write its results folder.
#[derive(Debug, thiserror::Error)]
pub enum ResultsFolderError {
    #[error(transparent)]
    Output(#[from] OutputError),
    #[error(
        "{} holds the results of another study file, {} (study '{}'), and this run reads {}; a \
         run replaces its results folder whole: give one of the two studies another `study:` \
         name, choose another results folder (--out), or replace those results (--force); \
         nothing was computed",
        folder.display(), other.display(), study, this.display()
    )]
    OtherStudyFile {
        folder: PathBuf,
        other: PathBuf,
        this: PathBuf,
        study: String,
    },
}

/// Checks, before anything is computed, that the run may write its results into `out`: the
/// folder's shape and permissions ([`check_target`]), and whose results it holds. Results of
/// the same study file (perhaps edited since) are replaced; results of another study file with
/// the same `study:` name are refused unless `force` (then replaced with a warning naming both
/// files). Stale staging folders of earlier runs are deleted. Returns the warnings.
pub fn check_results_folder(
    study: &Study<TribologyNode>,
    out: &Path,
    force: bool,
) -> Result<Vec<String>, ResultsFolderError> {
    check_target(out)?;
    let mut warnings: Vec<String> = remove_stale_stagings(out)?.into_iter().collect();
    let Some(origin) = results_origin(out) else {
        return Ok(warnings);
    };
    let this = std::fs::canonicalize(&study.path).unwrap_or_else(|_| study.path.clone());
    let same_contents = origin.study_file_hash.as_deref() == Some(study.file_hash.as_str());
    match origin.study_file {
        Some(other) if other != this && !same_contents => {
            if !force {
                return Err(ResultsFolderError::OtherStudyFile {
                    folder: out.to_path_buf(),
                    other,
                    this,
                    study: origin.study.unwrap_or_default(),
                });
            }
            warnings.push(format!(
                "replacing the results of another study file, {}, in {} with those of {} \
                 (--force)",
                other.display(),
                out.display(),
                this.display()
            ));
        }
        None if !same_contents => warnings.push(format!(
            "replacing {}, written by a study file with other contents (an asperity that did \
             not record which file; blake3 {})",
            out.display(),
            origin.study_file_hash.as_deref().unwrap_or("unknown")
        )),
        _ => {}
    }
    Ok(warnings)
}

/// The files a run published and what the user should know about its folder.
#[derive(Debug)]
pub struct Published {
    pub files: Vec<PathBuf>,
    /// Leftovers of earlier runs that could not be deleted, with the command that deletes them.
    pub warnings: Vec<String>,
}

/// Writes the run's tables, summaries and timings into `out`, replacing it in one step; returns
/// the files written.
pub fn write_results(
    study: &Study<TribologyNode>,
    plan: &Plan,
    report: &RunReport,
    out: &Path,
) -> Result<Vec<PathBuf>, OutputError> {
    Ok(write_results_unless(study, plan, report, out, &|| false)?
        .map_or_else(Vec::new, |p| p.files))
}

/// [`write_results`], giving up before each step and before publishing once `stop()` (a
/// Ctrl-C): the staging folder is then deleted, `out` is left as it was and `None` returned.
pub fn write_results_unless(
    study: &Study<TribologyNode>,
    plan: &Plan,
    report: &RunReport,
    out: &Path,
    stop: &dyn Fn() -> bool,
) -> Result<Option<Published>, OutputError> {
    let meta = OutputMetadata {
        study: study.name().to_string(),
        study_file_hash: study.file_hash.clone(),
        tool_version: crate::TOOL_VERSION.to_string(),
        overrides: study.overrides.clone(),
    };
    let mut set = ResultSet::stage(out)?.from_study_file(&study.path);
    if stop() {
        return Ok(None);
    }
    set.write_tables(plan, report, &study.outputs, &meta)?;
    if stop() {
        return Ok(None);
    }
    set.write_summaries(plan, report, &study.file.summaries, &meta)?;
    set.write_timings(plan, report, &meta)?;
    if stop() {
        return Ok(None);
    }
    let (files, warnings) = set.publish_with_warnings()?;
    Ok(Some(Published { files, warnings }))
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
