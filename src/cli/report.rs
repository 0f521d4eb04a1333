//! `asperity report RESULTS_DIR`: writes one self-contained HTML page with trends, load curves
//! and maps (see docs/report.md).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};

use asperity::report::{build_report, ReportOptions};

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
    let report = build_report(&options, Some(&cache))?;
    let out = args.out.unwrap_or_else(|| args.results.join("report.html"));
    let tmp = out.with_extension("html.tmp");
    std::fs::write(&tmp, &report.html)
        .with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, &out).with_context(|| format!("cannot write {}", out.display()))?;
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
