//! Command-line arguments and dispatch.

mod cache;
mod inspect;
pub mod interrupt;
mod progress;
mod report;
mod run;
mod slurm;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};

use asperity::engine::cache::Cache;
use asperity::engine::plan::Plan;
use asperity::engine::study::{ParameterOverride, Study};
use asperity::nodes::TribologyNode;

/// Reproducible rough-surface contact and static-friction studies.
#[derive(Debug, Parser)]
#[command(name = "asperity", version, about, long_about = None)]
pub struct Cli {
    /// More log output (-v: info, -vv: debug); RUST_LOG overrides.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a study: compute what is not cached, write Parquet tables.
    Run(run::RunArgs),
    /// Show what a run would do: each node instance, cached or to compute.
    Plan {
        /// The study file (YAML).
        study: PathBuf,
        #[command(flatten)]
        set: SetArg,
        #[command(flatten)]
        cache: CacheArg,
        /// Print the node DAG as Graphviz DOT instead.
        #[arg(long, conflicts_with = "mermaid")]
        dot: bool,
        /// Print the node DAG as a Mermaid flowchart instead.
        #[arg(long)]
        mermaid: bool,
    },
    /// Check a study file without running it.
    Validate {
        /// The study file (YAML).
        study: PathBuf,
        #[command(flatten)]
        set: SetArg,
    },
    /// Print the JSON Schema of study files (for editors with the YAML language server).
    Schema,
    /// Describe a topography file: format, grid, spacing, missing points, statistics.
    Inspect(inspect::InspectArgs),
    /// Write a self-contained HTML report (trends, load curves, maps) of a results folder.
    Report(report::ReportArgs),
    /// Inspect and maintain the cache: ls, du, verify, gc.
    Cache(cache::CacheArgs),
    /// Write (and submit) a Slurm job array running the study's shards, then a collect job.
    Slurm(slurm::SlurmArgs),
}

/// Parameter overrides for this invocation.
#[derive(Debug, Default, clap::Args)]
struct SetArg {
    /// Replace a parameter's axis for this run: `--set n=64`, `--set "sq=[0.38 um, 1.19 um]"`,
    /// `--set "seed={range: [1, 2]}"` (repeatable; recorded in the tables' metadata).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    overrides: Vec<ParameterOverride>,
}

/// Where the cache lives.
#[derive(Debug, clap::Args)]
struct CacheArg {
    /// Cache directory [default: $ASPERITY_CACHE or ./cache].
    #[arg(long, value_name = "DIR")]
    cache: Option<PathBuf>,
}

impl CacheArg {
    fn dir(&self) -> PathBuf {
        asperity::study_run::cache_dir(self.cache.clone())
    }

    fn open(&self) -> Result<Cache> {
        let dir = self.dir();
        Cache::open(&dir).with_context(|| format!("cannot open the cache at {}", dir.display()))
    }
}

/// Sets up tracing logs on stderr: warnings by default, more with -v; RUST_LOG overrides.
pub fn init_tracing(verbose: u8) {
    let default = match verbose {
        0 => "warn",
        1 => "asperity=info,warn",
        _ => "asperity=debug,info",
    };
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new(default));
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_target(false)
        .init();
}

/// Runs the command.
pub fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Run(args) => run::run(args),
        Command::Plan {
            study,
            set,
            cache,
            dot,
            mermaid,
        } => plan(&study, &set, &cache, dot, mermaid),
        Command::Validate { study, set } => validate(&study, &set),
        Command::Inspect(args) => inspect::inspect(args),
        Command::Report(args) => report::report(args),
        Command::Cache(args) => cache::cache(args),
        Command::Slurm(args) => slurm::slurm(args),
        Command::Schema => {
            print!("{}", asperity::nodes::study_schema_json());
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn load(study: &std::path::Path, set: &SetArg) -> Result<(Study<TribologyNode>, Plan)> {
    Ok(asperity::study_run::load_study(study, &set.overrides)?)
}

fn warn_unused(plan: &Plan) {
    for p in &plan.unused_parameters {
        eprintln!("warning: parameter '{p}' is not used by any node");
    }
}

fn validate(path: &std::path::Path, set: &SetArg) -> Result<ExitCode> {
    let (study, plan) = load(path, set)?;
    warn_unused(&plan);
    println!(
        "{}: ok — study '{}', {} scenario(s), {} node(s), {} unique node instance(s)",
        path.display(),
        study.name(),
        plan.scenarios.rows.len(),
        plan.node_names.len(),
        plan.nodes.len()
    );
    Ok(ExitCode::SUCCESS)
}

fn plan(
    path: &std::path::Path,
    set: &SetArg,
    cache: &CacheArg,
    dot: bool,
    mermaid: bool,
) -> Result<ExitCode> {
    let (study, plan) = load(path, set)?;
    let cache = cache.open()?;
    let cached: Vec<bool> = plan
        .nodes
        .iter()
        .map(|n| cache.contains(n.task.kind(), &n.key))
        .collect();
    if dot {
        print!("{}", plan.to_dot(|i| cached[i]));
        return Ok(ExitCode::SUCCESS);
    }
    if mermaid {
        print!("{}", plan.to_mermaid(|i| cached[i]));
        return Ok(ExitCode::SUCCESS);
    }
    warn_unused(&plan);
    let needed = plan.needed_for(&study.outputs);
    println!(
        "study '{}': {} scenario(s), {} unique node instance(s), outputs: {}",
        study.name(),
        plan.scenarios.rows.len(),
        plan.nodes.len(),
        study.outputs.join(", ")
    );
    println!(
        "{:<8} {:<12} {:<10} {:<8} nodes",
        "status", "key", "kind", "version"
    );
    let mut to_compute = 0;
    for &i in &needed {
        let n = &plan.nodes[i];
        let status = if cached[i] { "cached" } else { "compute" };
        to_compute += usize::from(!cached[i]);
        println!(
            "{status:<8} {:<12} {:<10} {:<8} {}",
            n.key.short(),
            n.task.kind(),
            n.task.version(),
            n.names.join(", ")
        );
    }
    println!(
        "total: {} needed, {} cached, {} to compute{}",
        needed.len(),
        needed.len() - to_compute,
        to_compute,
        if needed.len() < plan.nodes.len() {
            format!(
                " ({} not needed by the requested outputs)",
                plan.nodes.len() - needed.len()
            )
        } else {
            String::new()
        }
    );
    Ok(ExitCode::SUCCESS)
}

/// The text of an error and its causes, joined by ": " (as anyhow's `{:#}`), leaving out a
/// cause whose text the message already holds: a library error that writes its cause into its
/// own message and also returns it as `source()` would otherwise say it twice.
pub fn error_text(error: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in error.chain() {
        let part = cause.to_string();
        if text.contains(&part) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&part);
    }
    text
}

#[cfg(test)]
mod error_text_tests {
    use super::error_text;

    #[derive(Debug, thiserror::Error)]
    #[error("form removal failed: {0}")]
    struct Wrapper(#[from] std::io::Error);

    #[test]
    fn a_cause_already_in_the_message_is_said_once() {
        let io = std::io::Error::other("missing magic");
        let error = anyhow::Error::from(Wrapper(io)).context("cannot read scan.al3d");
        assert_eq!(
            error_text(&error),
            "cannot read scan.al3d: form removal failed: missing magic"
        );
    }
}
