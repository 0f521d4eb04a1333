//! `asperity report RESULTS_DIR`: writes one self-contained HTML page with trends, load curves
//! and maps (see docs/report.md).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};

use asperity::engine::output::Generation;
use asperity::report::{build_report, Report, ReportOptions};

/// Arguments of `asperity report`.
#[derive(Debug, clap::Args)]
pub struct ReportArgs {
    /// The results folder written by `asperity run` (holds scenarios.parquet).
    results: PathBuf,
    /// The HTML file to write [default: RESULTS_DIR/report.html].
    #[arg(long, value_name = "FILE.html")]
    out: Option<PathBuf>,
    #[command(flatten)]
    cache: super::CacheArg,
    /// Also plot this column of a node table (repeatable): `mean_contact_pressure`,
    /// `contacts.plastic_area_share`, `surfaces.sq_m`, …
    #[arg(long, value_name = "COLUMN")]
    metric: Vec<String>,
    /// A replicate axis (repeatable): points average over it. Default: parameters named seed,
    /// *_seed, seed_*, replicate, realisation, repetition.
    #[arg(long, value_name = "PARAMETER")]
    replicate: Vec<String>,
    /// Draw maps for this many scenarios, spread over the swept configurations.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 3,
        conflicts_with = "scenario"
    )]
    maps: usize,
    /// Draw maps for this scenario index (repeatable; the `scenario` column).
    #[arg(long, value_name = "INDEX")]
    scenario: Vec<usize>,
}

/// Runs `asperity report`.
pub fn report(args: ReportArgs) -> Result<ExitCode> {
    let cache = args.cache.open()?;
    let options = ReportOptions {
        results_dir: args.results.clone(),
        metrics: args.metric,
        replicates: (!args.replicate.is_empty()).then_some(args.replicate),
        map_count: args.maps,
        map_scenarios: args.scenario,
    };
    let out = args.out.unwrap_or_else(|| args.results.join("report.html"));
    let report = read_one_set(&options, &cache, &out)?;
    for s in &report.skipped {
        eprintln!("skipped: {s}");
    }
    println!(
        "wrote {} ({} figure(s), {} KiB)",
        out.display(),
        report.figures,
        report.html.len() / 1024
    );
    Ok(ExitCode::SUCCESS)
}

/// Writes the page as `<out>.tmp` and renames it into place. A Ctrl-C meanwhile is left until
/// the page is written or its temporary file deleted, then stops the command ([`Interrupted`]).
///
/// [`Interrupted`]: super::interrupt::Interrupted
fn write_page(out: &std::path::Path, html: &str) -> Result<()> {
    let _section = super::interrupt::cooperative();
    let tmp = out.with_extension("html.tmp");
    std::fs::write(&tmp, html).with_context(|| format!("cannot write {}", tmp.display()))?;
    if super::interrupt::requested() {
        let _ = std::fs::remove_file(&tmp);
        return Err(super::interrupt::Interrupted.into());
    }
    std::fs::rename(&tmp, out).with_context(|| format!("cannot write {}", out.display()))?;
    Ok(())
}

/// How often the report is rebuilt when runs keep publishing into the results folder.
const READ_ATTEMPTS: usize = 3;

/// Builds the report from one published set of tables and writes it to `out`. A run publishes
/// a new set by replacing the folder whole (a new [`Generation`]); a report whose folder changed
/// while it read the tables, or before its page was written into it, is built again.
fn read_one_set(
    options: &ReportOptions,
    cache: &asperity::engine::cache::Cache,
    out: &std::path::Path,
) -> Result<Report> {
    let generation = || {
        Generation::of(&options.results_dir)
            .with_context(|| format!("cannot read {}", options.results_dir.display()))
    };
    for _ in 0..READ_ATTEMPTS {
        let before = generation()?;
        let report = build_report(options, Some(cache))?;
        write_page(out, &report.html)?;
        if generation()? == before {
            return Ok(report);
        }
    }
    anyhow::bail!(
        "{} was replaced by {READ_ATTEMPTS} runs while the report read it; run the report again \
         when the runs writing into it are done",
        options.results_dir.display()
    )
}
