//! `asperity run`: plan, execute with a progress bar, write tables, summarise.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};

use asperity::engine::cache::Cache;
use asperity::engine::execute::{
    execute, execute_nodes, process_memory, ExecuteOptions, NodeOutcome, NodeStatus, RunReport,
};
use asperity::engine::plan::Plan;
use asperity::engine::shard::{Shard, ShardPlan};
use asperity::engine::study::Study;
use asperity::nodes::TribologyNode;
use asperity::study_run::{
    check_results_folder, default_memory_budget, default_out, execute_options, write_results_unless,
};

use super::interrupt;
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
    /// Replace a results folder written by another study file (one with the same `study:`
    /// name); without it such a folder is refused before anything is computed.
    #[arg(long)]
    force: bool,
    #[command(flatten)]
    cache: CacheArg,
    /// Worker threads [default: all cores].
    #[arg(long, short = 'j', value_name = "N")]
    jobs: Option<usize>,
    /// Memory budget of the process, in MiB [default: 60 % of available memory]: its own base,
    /// the nodes running at once (their estimates), the arrays held for dependants and the tables
    /// kept for the results stay within it (nodes wait their turn); a node that cannot fit even
    /// alone fails, saying so, before it allocates. Linux counts the resident set; the run prints
    /// its peak.
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
    let folder_warnings = match args.shard {
        Some(_) => Vec::new(),
        None => check_results_folder(&study, &out, args.force)?,
    };
    for warning in &folder_warnings {
        eprintln!("warning: {warning}");
    }
    // From here on a first Ctrl-C lets the running nodes finish and be cached (interrupt.rs).
    let _section = interrupt::cooperative();
    let progress = BarProgress::new(args.quiet);
    if let Some(shard) = args.shard {
        return run_shard(&study, &plan, &cache, shard, &options, &progress);
    }
    let report = execute(&plan, &cache, &options, &progress)?;
    progress.finish();
    report_failures(&plan, &report);
    if interrupt::requested() {
        return Ok(interrupted(&report, "no tables written"));
    }
    let Some(published) =
        write_results_unless(&study, &plan, &report, &out, &interrupt::requested)?
    else {
        return Ok(interrupted(&report, "no tables written"));
    };
    for warning in published
        .warnings
        .iter()
        .filter(|w| !folder_warnings.contains(w))
    {
        eprintln!("warning: {warning}");
    }
    println!(
        "{}",
        run_summary(study.name(), &report, options.memory_budget)
    );
    println!("tables in {}:", out.display());
    for f in published.files {
        println!("  {}", f.display());
    }
    if interrupt::requested() {
        eprintln!("interrupted once the tables were complete: they are written");
        return Ok(ExitCode::from(interrupt::EXIT_CODE));
    }
    Ok(exit_code(&report))
}

/// One shard of a study (`--shard i/n`): its nodes computed and cached, no tables written.
fn run_shard(
    study: &Study<TribologyNode>,
    plan: &Plan,
    cache: &Cache,
    shard: Shard,
    options: &ExecuteOptions,
    progress: &BarProgress,
) -> Result<ExitCode> {
    let split = ShardPlan::split(plan, &plan.needed_for(&study.outputs), shard.count);
    let report = execute_nodes(plan, cache, split.nodes(shard), options, progress)?;
    progress.finish();
    report_failures(plan, &report);
    if interrupt::requested() {
        return Ok(interrupted(&report, "no tables are written by a shard"));
    }
    println!(
        "{} shard {shard}: {} computed, {} reused from cache, {} failed, {} skipped in {:.2} s{} \
         (no tables written: run the study without --shard to assemble them)",
        study.name(),
        report.computed,
        report.cached,
        report.failed,
        report.skipped,
        report.wall_seconds,
        peak_memory(options.memory_budget)
    );
    Ok(exit_code(&report))
}

/// The line a finished run prints: its counts, wall time and peak memory.
fn run_summary(name: &str, report: &RunReport, memory_budget: u64) -> String {
    let discarded = if report.discarded > 0 {
        format!(" ({} corrupt cache entries recomputed)", report.discarded)
    } else {
        String::new()
    };
    let not_stored = if report.not_stored > 0 {
        format!(" ({} not stored in the cache)", report.not_stored)
    } else {
        String::new()
    };
    format!(
        "{name}: {} computed, {} reused from cache, {} failed, {} skipped{discarded}{not_stored} \
         in {:.2} s{}",
        report.computed,
        report.cached,
        report.failed,
        report.skipped,
        report.wall_seconds,
        peak_memory(memory_budget)
    )
}

/// `, peak memory P MiB of a B MiB budget`: the process's peak resident set so far (tables
/// written included) beside `--memory-mib`; empty where the system does not say (not Linux).
fn peak_memory(budget: u64) -> String {
    let mib = |bytes: u64| bytes.div_ceil(1 << 20);
    process_memory::peak_resident_bytes().map_or(String::new(), |peak| {
        format!(
            ", peak memory {} MiB of a {} MiB budget",
            mib(peak),
            mib(budget)
        )
    })
}

/// Says what an interrupted run did (everything computed is cached, so a rerun continues
/// from there) and returns exit code 130.
fn interrupted(report: &RunReport, tables: &str) -> ExitCode {
    eprintln!(
        "interrupted: {} node(s) computed{}, {} reused from the cache; {tables} (run the study \
         again to continue from the cache)",
        report.computed,
        if report.not_stored > 0 {
            format!(" ({} not stored in the cache)", report.not_stored)
        } else {
            String::from(" and cached")
        },
        report.cached,
    );
    ExitCode::from(interrupt::EXIT_CODE)
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
