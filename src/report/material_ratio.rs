//! The areal material ratio (Abbott–Firestone) curves of the surfaces, from the
//! `surfaces_material_ratio` table: one figure per surface node, one line per distinct surface
//! instance (at most [`MAX_CURVES`], in scenario order), height against material ratio, with the
//! functional parameters of each instance (`sk_m`, `spk_m`, `svk_m`, `smr1_percent`,
//! `smr2_percent`) in the figure's table.

use std::collections::BTreeMap;

use super::axis::format_number;
use super::figure::{Figure, Section, ValueTable};
use super::metrics::NodeTable;
use super::quantity::DisplayUnit;
use super::scenarios::ScenarioSet;
use super::svg_plot::{LinePlot, PlotPoint, PlotSeries};
use super::table::ResultTable;

/// Curves drawn in one figure (the palette's colours); the others are named in the caption.
pub const MAX_CURVES: usize = 7;

/// The surfaces table's columns quoted under each figure.
const QUOTED: [&str; 5] = ["sk_m", "spk_m", "svk_m", "smr1_percent", "smr2_percent"];

/// The section, or `None` without the table or without a surface node whose rows it holds.
pub fn material_ratio_section(
    scenarios: &ScenarioSet,
    surfaces: &NodeTable,
    curve: &ResultTable,
) -> Option<Section> {
    let (keys, ratio, height) = (
        curve.texts("key")?,
        curve.numbers("material_ratio_percent")?,
        curve.numbers("height_m")?,
    );
    let mut rows_of: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (row, key) in keys.iter().enumerate() {
        if let Some(k) = key {
            rows_of.entry(k.as_str()).or_default().push(row);
        }
    }
    let mut figures = Vec::new();
    for link in scenarios.links_into(&surfaces.index) {
        let mut instances: Vec<(usize, &str)> = Vec::new();
        for (scenario, key) in link.keys.iter().enumerate() {
            if let Some(k) = key.as_deref() {
                if rows_of.contains_key(k) && !instances.iter().any(|(_, seen)| *seen == k) {
                    instances.push((scenario, k));
                }
            }
        }
        if instances.is_empty() {
            continue;
        }
        let left_out = instances.len().saturating_sub(MAX_CURVES);
        instances.truncate(MAX_CURVES);
        let curve_of = |key: &str| -> Vec<(f64, f64)> {
            rows_of[key]
                .iter()
                .filter_map(|&r| ratio[r].zip(height[r]))
                .collect()
        };
        let plot = curves_plot(&link.node, &instances, curve_of);
        let mut caption = String::from(
            "Height against the share of the valid points at or above it (ISO 25178-2), \
             every 1 %; one line per surface instance, labelled by its first scenario.",
        );
        if left_out > 0 {
            caption.push_str(&format!(" {left_out} further instances are not drawn."));
        }
        figures.push(Figure {
            svg: Some(plot.to_svg()),
            caption,
            values: Some(quoted_values(surfaces, &instances)),
        });
    }
    (!figures.is_empty()).then(|| Section {
        title: String::from("Material ratio curves"),
        intro: String::from(
            "The areal material ratio curve of each surface and its functional parameters: the \
             core height Sk, the reduced peak height Spk and dale depth Svk, and the material \
             ratios Smr1, Smr2 that bound the core (docs/study-format.md, the `surfaces` table).",
        ),
        figures,
    })
}

/// One line per instance (labelled by its first scenario): height from the mean, in a display
/// unit, against the material ratio.
fn curves_plot(
    node: &str,
    instances: &[(usize, &str)],
    curve_of: impl Fn(&str) -> Vec<(f64, f64)>,
) -> LinePlot {
    let unit = DisplayUnit::for_slice(
        "m",
        instances
            .iter()
            .flat_map(|(_, k)| curve_of(k).into_iter().map(|p| p.1)),
    );
    let series = instances
        .iter()
        .map(|&(scenario, key)| PlotSeries {
            label: format!("scenario {scenario}"),
            points: curve_of(key)
                .into_iter()
                .map(|(x, y)| PlotPoint {
                    x,
                    y: y * unit.factor,
                    y_error: None,
                })
                .collect(),
            joined: true,
        })
        .collect();
    LinePlot {
        title: format!("Material ratio curve — surface '{node}'"),
        x_label: String::from("material ratio Smr (%)"),
        y_label: unit.axis_label("height from the mean"),
        x_log: false,
        y_log: false,
        series,
    }
}

/// The functional parameters of each drawn instance, from the surfaces table.
fn quoted_values(surfaces: &NodeTable, instances: &[(usize, &str)]) -> ValueTable {
    let mut header = vec![String::from("series")];
    header.extend(QUOTED.iter().map(|c| c.to_string()));
    let rows = instances
        .iter()
        .map(|&(scenario, key)| {
            let mut row = vec![format!("scenario {scenario}")];
            let at = surfaces.index.get(key).copied();
            row.extend(QUOTED.iter().map(|column| {
                at.and_then(|r| surfaces.table.numbers(column)?.get(r).copied().flatten())
                    .map_or(String::from("—"), format_number)
            }));
            row
        })
        .collect();
    ValueTable { header, rows }
}
