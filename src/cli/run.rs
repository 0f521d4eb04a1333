//! `asperity run`: plan, execute with a progress bar, write tables, summarise.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};

use asperity::engine::execute::{execute, execute_nodes, NodeOutcome, NodeStatus, RunReport};
use asperity::engine::output::check_target;
use asperity::engine::plan::Plan;
use asperity::engine::shard::{Shard, ShardPlan};
use asperity::study_run::{default_memory_budget, default_out, execute_options, write_results};

use super::progress::BarProgress;
use super::CacheArg;

/// Arguments of `asperity run`.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// The study file (YAML).
    study: PathBuf,
    #[command(flatten)]
    set: super::SetArg,
    /// Output folder for the Parquet tables [default: results/<study>]. It is replaced whole,
    /// in one step, when the run's tables are complete (files put into it, such as an earlier
    /// report.html, go with it); only an absent, empty or earlier results folder is replaced.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    #[command(flatten)]
    cache: CacheArg,
    /// Worker threads [default: all cores].
    #[arg(long, short = 'j', value_name = "N")]
    jobs: Option<usize>,
    /// Memory budget for nodes running at once, in MiB [default: 60 % of available memory]; a
    /// node whose estimate alone exceeds it fails, saying so, before it allocates.
    #[arg(long, value_name = "MIB")]
    memory_mib: Option<u64>,
    /// Compute only shard I of N (0 <= I < N) of the study's nodes, into the shared cache; no
    /// tables are written (a plain `run` afterwards assembles them from the cache).
    #[arg(long, value_name = "I/N")]
    shard: Option<Shard>,
    /// No progress bar.
    #[arg(long, short)]
    quiet: bool,
}

pub fn run(args: RunArgs) -> Result<ExitCode> {
    if let Some(jobs) = args.jobs {
        anyhow::ensure!(jobs >= 1, "--jobs must be at least 1");
        rayon::ThreadPoolBuilder::new()
            .num_threads(jobs)
            .build_global()
            .context("cannot start the worker threads")?;
    }
    let (study, plan) = super::load(&args.study, &args.set)?;
    super::warn_unused(&plan);
    let cache = args.cache.open()?;
    let out = args.out.clone().unwrap_or_else(|| default_out(&study));
    let options = execute_options(
        &study,
        args.memory_mib
            .map(|m| m.saturating_mul(1 << 20))
            .unwrap_or_else(default_memory_budget),
    );
    if args.shard.is_none() {
        check_target(&out)?;
    }
    let progress = BarProgress::new(args.quiet);
    if let Some(shard) = args.shard {
        let split = ShardPlan::split(&plan, &plan.needed_for(&study.outputs), shard.count);
        let report = execute_nodes(&plan, &cache, split.nodes(shard), &options, &progress)?;
        progress.finish();
        report_failures(&plan, &report);
        println!(
            "{} shard {shard}: {} computed, {} reused from cache, {} failed, {} skipped in {:.2} s \
             (no tables written: run the study without --shard to assemble them)",
            study.name(),
            report.computed,
            report.cached,
            report.failed,
            report.skipped,
            report.wall_seconds
        );
        return Ok(exit_code(&report));
    }
    let report = execute(&plan, &cache, &options, &progress)?;
    progress.finish();
    let files = write_results(&study, &plan, &report, &out)?;
    report_failures(&plan, &report);
    println!(
        "{}: {} computed, {} reused from cache, {} failed, {} skipped{} in {:.2} s",
        study.name(),
        report.computed,
        report.cached,
        report.failed,
        report.skipped,
        if report.discarded > 0 {
            format!(" ({} corrupt cache entries recomputed)", report.discarded)
        } else {
            String::new()
        },
        report.wall_seconds
    );
    println!("tables in {}:", out.display());
    for f in files {
        println!("  {}", f.display());
    }
    Ok(exit_code(&report))
}

fn exit_code(report: &RunReport) -> ExitCode {
    if report.all_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    }
}

/// One line on stderr per failed instance and one per flag of a flagged instance (flagged rows
/// keep exit code 0: their values are possible, but must be read with the sentence).
fn report_failures(plan: &Plan, report: &RunReport) {
    for (i, o) in report.outcomes.iter().enumerate() {
        let Some(outcome) = o else { continue };
        let node = &plan.nodes[i];
        let (kind, names, key) = (node.task.kind(), node.names.join(", "), node.key.short());
        if let NodeOutcome {
            status: NodeStatus::Failed(m),
            ..
        } = outcome
        {
            eprintln!("failed: {kind} node '{names}' ({key}): {m}");
        } else if outcome.is_flagged() {
            for flag in &outcome.flags {
                eprintln!("flagged: {kind} node '{names}' ({key}): {flag}");
            }
        }
    }
}
