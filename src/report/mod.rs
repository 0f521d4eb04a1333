//! `asperity report`: one self-contained HTML page from a results folder and the cache.
//!
//! The page shows (a) trends of μ_s (`friction.mu_s`), A_t,rel (`contacts.area_fraction`), θ
//! (`contacts.stress_ratio`) and any requested metric against every swept parameter, as mean ±
//! sample standard deviation over the replicate axes ([`scenarios`] explains how they are
//! found), one series per combination of the other swept parameters, and with two or more
//! friction nodes one figure per swept parameter comparing their μ_s; (b) load curves from
//! `contacts_load_curve`; the material ratio curves of the surfaces from
//! `surfaces_material_ratio`; (c) height and contact-pressure maps of chosen scenarios from
//! verified cache entries. Missing tables, entries or fields are listed on the page, not
//! errors. This module knows the tribology table and column names but never prints.

mod axis;
mod colormap;
mod distributions;
mod error;
mod figure;
mod html;
mod map_figure;
mod maps;
mod material_ratio;
mod metrics;
mod quantity;
mod scenarios;
mod statistics;
mod svg_plot;
mod table;
mod trends;
mod twin_comparison;

use std::path::PathBuf;

use crate::engine::cache::Cache;
use crate::vocabulary::{kinds, metrics as names, tables as table_names};

pub use error::ReportError;

use figure::Section;
use html::PageHeader;
use metrics::{Metric, NodeTable, NODE_TABLES};
use scenarios::ScenarioSet;
use table::ResultTable;

/// What to put in the report.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportOptions {
    /// The folder `asperity run` wrote (`results/<study>/`).
    pub results_dir: PathBuf,
    /// Extra metrics to plot: `column`, `column` without unit suffix, or `table.column`.
    pub metrics: Vec<String>,
    /// The replicate axes; `None`: detected by name (`seed`, …).
    pub replicates: Option<Vec<String>>,
    /// How many scenarios get maps when `map_scenarios` is empty.
    pub map_count: usize,
    /// Scenario indices (0-based, the `scenario` column) to draw maps for.
    pub map_scenarios: Vec<usize>,
}

/// A finished report.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The page.
    pub html: String,
    /// Number of figures (plots, maps and table-only entries).
    pub figures: usize,
    /// What was skipped and why (also listed on the page).
    pub skipped: Vec<String>,
}

/// Builds the report page. `cache`: where maps come from (`None`: no maps).
pub fn build_report(options: &ReportOptions, cache: Option<&Cache>) -> Result<Report, ReportError> {
    let dir = &options.results_dir;
    let scenario_table = ResultTable::read(dir, table_names::SCENARIOS)?
        .ok_or_else(|| ReportError::NotAResultsDir(dir.clone()))?;
    let scenarios = ScenarioSet::from_table(&scenario_table, options.replicates.as_deref())?;
    let mut skipped = Vec::new();
    let tables = node_tables(dir, &scenarios, &mut skipped)?;
    let metrics = metrics::select_metrics(&tables, &scenarios, &options.metrics)?;
    let mut sections = Vec::new();

    sections.push(trend_section(&scenarios, &metrics, &mut skipped));
    sections.extend(twin_comparison::twin_comparison(&scenarios, &tables));

    let contacts = tables.iter().find(|t| t.kind == kinds::CONTACT);
    match (
        contacts,
        ResultTable::read(dir, table_names::CONTACTS_LOAD_CURVE)?,
    ) {
        (Some(contacts), Some(curve)) => sections.push(Section {
            title: String::from("Load curves"),
            intro: String::from(
                "True contact area fraction and stress ratio at each load step of the contacts.",
            ),
            figures: trends::load_curve_figures(&scenarios, contacts, &curve),
        }),
        _ => skipped.push(String::from(
            "load curves: they need contacts.parquet and contacts_load_curve.parquet",
        )),
    }

    let surfaces = tables.iter().find(|t| t.kind == kinds::SURFACE);
    match (
        surfaces,
        ResultTable::read(dir, table_names::SURFACES_MATERIAL_RATIO)?,
    ) {
        (Some(surfaces), Some(curve)) => sections.extend(material_ratio::material_ratio_section(
            &scenarios, surfaces, &curve,
        )),
        _ => skipped.push(String::from(
            "material ratio curves: they need surfaces.parquet and \
             surfaces_material_ratio.parquet",
        )),
    }

    sections.extend(map_section(
        options,
        cache,
        &scenarios,
        &tables,
        &mut skipped,
    )?);

    let study = scenario_table
        .study
        .clone()
        .unwrap_or_else(|| dir.display().to_string());
    let header = PageHeader {
        title: format!("asperity report: {study}"),
        facts: header_facts(options, &scenarios, &tables),
        skipped: skipped.clone(),
    };
    let figures = sections.iter().map(|s| s.figures.len()).sum();
    Ok(Report {
        html: html::page(&header, &sections),
        figures,
        skipped,
    })
}

/// The node tables of the results folder that scenarios use; the others are named in `skipped`
/// with the reason.
fn node_tables(
    dir: &std::path::Path,
    scenarios: &ScenarioSet,
    skipped: &mut Vec<String>,
) -> Result<Vec<NodeTable>, ReportError> {
    let mut tables = Vec::new();
    for (name, kind) in NODE_TABLES {
        match ResultTable::read(dir, name)? {
            None => skipped.push(format!("{name}.parquet: not in the results folder")),
            Some(table) if table.rows == 0 || table.texts("key").is_none() => {
                skipped.push(format!("{name}.parquet: no node instances"));
            }
            Some(table) => {
                let index = table.key_index()?;
                if scenarios.links_into(&index).next().is_none() {
                    skipped.push(format!("{name}.parquet: no scenario uses its rows"));
                    continue;
                }
                tables.push(NodeTable {
                    table,
                    kind: kind.to_string(),
                    index,
                });
            }
        }
    }
    Ok(tables)
}

/// The maps of the chosen scenarios (`--scenario`, else spread over the swept configurations),
/// from verified cache entries; `None` without a cache or without scenarios.
fn map_section(
    options: &ReportOptions,
    cache: Option<&Cache>,
    scenarios: &ScenarioSet,
    tables: &[NodeTable],
    skipped: &mut Vec<String>,
) -> Result<Option<Section>, ReportError> {
    let chosen = if options.map_scenarios.is_empty() {
        maps::default_scenarios(scenarios, options.map_count)
    } else {
        options.map_scenarios.clone()
    };
    Ok(match cache {
        Some(cache) if !chosen.is_empty() => Some(Section {
            title: String::from("Maps"),
            intro: format!(
                "Scenarios {}: heights of the surfaces and contact pressure of the final load step, \
                 from verified cache entries; y points up, the colour map is viridis.",
                chosen
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            figures: maps::map_figures(cache, scenarios, tables, &chosen, skipped)?,
        }),
        Some(_) => None,
        None => {
            skipped.push(String::from("maps: no cache given"));
            None
        }
    })
}

/// The trends of every metric; after the μ_s trends, the comparison of the friction nodes
/// when there are two or more.
fn trend_section(
    scenarios: &ScenarioSet,
    metrics: &[Metric],
    skipped: &mut Vec<String>,
) -> Section {
    let is_mu_s = |m: &Metric| m.table == table_names::FRICTION && m.column == names::MU_S;
    let mu_s: Vec<&Metric> = metrics.iter().filter(|m| is_mu_s(m)).collect();
    let last_mu_s = metrics.iter().rposition(is_mu_s);
    let mut figures = Vec::new();
    for (i, metric) in metrics.iter().enumerate() {
        let trends = trends::trend_figures(scenarios, metric);
        if trends.is_empty() {
            skipped.push(format!(
                "trend of {}.{} of node '{}': no values (failed or not computed)",
                metric.table, metric.column, metric.node
            ));
        }
        figures.extend(trends);
        if Some(i) == last_mu_s {
            figures.extend(trends::friction_model_figures(scenarios, &mu_s));
        }
    }
    figures.extend(distributions::distribution_figures(
        scenarios,
        &distribution_families(metrics, mu_s),
    ));
    let mut intro = trend_intro(scenarios);
    if metrics.is_empty() {
        intro.push_str(
            " No metric to plot: there is no contacts or friction table; name a column with \
             --metric (e.g. --metric surfaces.sq_m).",
        );
    }
    Section {
        title: String::from("Trends"),
        intro,
        figures,
    }
}

/// What the distribution figures draw side by side: θ and A_t,rel of each contact node, and μ_s
/// of every friction node together.
fn distribution_families<'a>(metrics: &'a [Metric], mu_s: Vec<&'a Metric>) -> Vec<Vec<&'a Metric>> {
    let mut families: Vec<Vec<&Metric>> = [names::STRESS_RATIO, names::AREA_FRACTION]
        .iter()
        .map(|column| {
            metrics
                .iter()
                .filter(|m| m.table == table_names::CONTACTS && m.base == *column)
                .collect()
        })
        .collect();
    families.push(mu_s);
    families
}

fn trend_intro(scenarios: &ScenarioSet) -> String {
    let replicates = scenarios.replicate_names();
    let how = if scenarios.replicates_named {
        "named with --replicate"
    } else {
        "detected by name: seed, *_seed, seed_*, replicate, realisation, repetition; override with --replicate"
    };
    if replicates.is_empty() {
        format!("No replicate axis varies ({how}); each point is one scenario.")
    } else {
        format!(
            "Each point is the mean over the replicate axes {} ({how}); error bars are ± one sample \
             standard deviation (n − 1). One series per combination of the other swept parameters; \
             expand “values” for the numbers.",
            replicates.join(", ")
        )
    }
}

fn header_facts(
    options: &ReportOptions,
    scenarios: &ScenarioSet,
    tables: &[NodeTable],
) -> Vec<(String, String)> {
    let mut facts = vec![
        (
            String::from("results"),
            options.results_dir.display().to_string(),
        ),
        (String::from("scenarios"), scenarios.count.to_string()),
    ];
    for (label, replicate) in [("swept parameters", false), ("replicate axes", true)] {
        let text: Vec<String> = scenarios
            .parameters
            .iter()
            .filter(|p| p.replicate == replicate && p.distinct() > 1)
            .map(|p| {
                let mut values: Vec<f64> = p.values.iter().flatten().copied().collect();
                values.sort_by(f64::total_cmp);
                values.dedup();
                let shown: Vec<String> = values
                    .iter()
                    .map(|&v| p.describe(Some(v)))
                    .map(|d| {
                        d.split_once(" = ")
                            .map_or(d.clone(), |(_, v)| v.to_string())
                    })
                    .collect();
                format!("{}: {}", p.name, shown.join(", "))
            })
            .collect();
        let text = if text.is_empty() {
            String::from("none")
        } else {
            text.join("; ")
        };
        facts.push((label.to_string(), text));
    }
    let read: Vec<String> = tables
        .iter()
        .map(|t| format!("{} ({} rows)", t.table.name, t.table.rows))
        .collect();
    facts.push((String::from("node tables"), read.join(", ")));
    facts
}
