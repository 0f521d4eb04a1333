//! Measured surfaces against their synthetic twins through the whole chain: for every measured
//! file surface and every twin made from that one file alone (the twin's only
//! `twin_of_0_blake3` equals the file's `file_blake3`), the summit radius of the surfaces, the
//! area fraction and stress ratio of the contacts solved on each (the contact whose `lower` is
//! the surface), and μ_s of each friction node downstream of them (through its `lower` surface
//! or its `contact`), paired by method and model. One figure per quantity: the twin's mean ±
//! sample standard deviation over the replicates (seeds) against the measured value, one point
//! per group of the other swept parameters (e.g. per file), with the line of equality.

use crate::engine::value::column_name;
use crate::units::Dimension;
use crate::vocabulary::surface_parameters::{twin_of_blake3, FILE_BLAKE3, SOURCE};
use crate::vocabulary::{kinds, metrics, roles};

use super::axis::format_number;
use super::figure::{Figure, Section, ValueTable};
use super::metrics::{Metric, NodeTable};
use super::quantity::{pretty_name, DisplayUnit};
use super::scenarios::{NodeLink, ScenarioSet};
use super::statistics::Summary;
use super::svg_plot::{LinePlot, PlotPoint, PlotSeries};

/// A measured node and the twin node that mirrors it, with the quantity compared.
struct Pair<'a> {
    table: &'a NodeTable,
    measured: &'a NodeLink,
    twin: &'a NodeLink,
    column: String,
}

/// The comparison section, or `None` when the results hold no file surface with a twin of it.
pub fn twin_comparison(scenarios: &ScenarioSet, tables: &[NodeTable]) -> Option<Section> {
    let of_kind = |kind: &str| tables.iter().find(|t| t.kind == kind);
    let surfaces = of_kind(kinds::SURFACE)?;
    let surface_pairs = twin_pairs(scenarios, surfaces);
    if surface_pairs.is_empty() {
        return None;
    }
    let mut pairs = Vec::new();
    for &(measured, twin) in &surface_pairs {
        pairs.push(Pair {
            table: surfaces,
            measured,
            twin,
            column: column_name(metrics::SUMMIT_MEAN_RADIUS, Dimension::Length),
        });
        let contacts = of_kind(kinds::CONTACT).and_then(|c| {
            let on = |surface| {
                downstream(scenarios, c, surface, &key_column(roles::LOWER))
                    .into_iter()
                    .next()
            };
            Some((c, on(measured)?, on(twin)?))
        });
        if let Some((table, measured, twin)) = contacts {
            for column in [metrics::AREA_FRACTION, metrics::STRESS_RATIO] {
                pairs.push(Pair {
                    table,
                    measured,
                    twin,
                    column: column.to_string(),
                });
            }
        }
        if let Some(friction) = of_kind(kinds::FRICTION) {
            let sides = [
                (measured, contacts.map(|c| c.1)),
                (twin, contacts.map(|c| c.2)),
            ];
            let [on_measured, on_twin] = sides
                .map(|(surface, contact)| friction_nodes(scenarios, friction, surface, contact));
            pairs.extend(same_method_and_model(friction, &on_measured, &on_twin));
        }
    }
    let figures: Vec<Figure> = pairs
        .iter()
        .filter_map(|p| comparison_figure(scenarios, p))
        .collect();
    Some(Section {
        title: String::from("Measured surfaces and their twins"),
        intro: format!(
            "Each measured surface against the synthetic twin made from it alone, through contact \
             and friction: the twin's mean ± sample standard deviation over {} against the \
             measured value, one point per group of the other parameters; on the equality line the \
             twin reproduces the measurement.",
            replicate_text(scenarios)
        ),
        figures,
    })
}

/// The friction nodes downstream of `surface` (as their `lower`) or of `contact`, each once (a
/// statistical node may read both).
fn friction_nodes<'a>(
    scenarios: &'a ScenarioSet,
    friction: &'a NodeTable,
    surface: &NodeLink,
    contact: Option<&NodeLink>,
) -> Vec<&'a NodeLink> {
    let mut links = downstream(scenarios, friction, surface, &key_column(roles::LOWER));
    if let Some(c) = contact {
        links.extend(downstream(
            scenarios,
            friction,
            c,
            &key_column(roles::CONTACT),
        ));
    }
    let mut seen = std::collections::BTreeSet::new();
    links.retain(|l| seen.insert(l.node.as_str()));
    links
}

/// μ_s of each measured-side friction node against the twin-side node of the same method and
/// model.
fn same_method_and_model<'a>(
    friction: &'a NodeTable,
    on_measured: &[&'a NodeLink],
    on_twin: &[&'a NodeLink],
) -> Vec<Pair<'a>> {
    let detail = |link: &NodeLink| Metric::resolve(friction, link, metrics::MU_S).map(|m| m.detail);
    let twin_details: Vec<_> = on_twin.iter().map(|t| detail(t)).collect();
    on_measured
        .iter()
        .filter_map(|m| {
            let d = detail(m);
            let i = twin_details.iter().position(|t| *t == d)?;
            Some(Pair {
                table: friction,
                measured: m,
                twin: on_twin[i],
                column: metrics::MU_S.to_string(),
            })
        })
        .collect()
}

fn replicate_text(scenarios: &ScenarioSet) -> String {
    let names = scenarios.replicate_names();
    if names.is_empty() {
        String::from("its instances")
    } else {
        format!("the replicates ({})", names.join(", "))
    }
}

/// The first row of `link`'s instances in `table`.
fn first_row(table: &NodeTable, link: &NodeLink) -> Option<usize> {
    link.keys
        .iter()
        .flatten()
        .find_map(|k| table.index.get(k).copied())
}

/// (file surface, twin of that file alone) node pairs of the surfaces table.
fn twin_pairs<'a>(
    scenarios: &'a ScenarioSet,
    surfaces: &'a NodeTable,
) -> Vec<(&'a NodeLink, &'a NodeLink)> {
    let text = |column: &str, row: usize| {
        surfaces
            .table
            .texts(column)
            .and_then(|t| t.get(row).cloned().flatten())
    };
    let links: Vec<&NodeLink> = scenarios.links_into(&surfaces.index).collect();
    let mut pairs = Vec::new();
    for twin in &links {
        let Some(row) = first_row(surfaces, twin) else {
            continue;
        };
        if text(SOURCE, row).as_deref() != Some("twin") || text(&twin_of_blake3(1), row).is_some() {
            continue;
        }
        let Some(of) = text(&twin_of_blake3(0), row) else {
            continue;
        };
        let measured = links.iter().find(|m| {
            first_row(surfaces, m).is_some_and(|r| {
                text(SOURCE, r).as_deref() == Some("file")
                    && text(FILE_BLAKE3, r).as_deref() == Some(of.as_str())
            })
        });
        if let Some(m) = measured {
            pairs.push((*m, *twin));
        }
    }
    pairs
}

/// The column of a node table holding the key of its upstream input in `role` (`lower_key`).
fn key_column(role: &str) -> String {
    format!("{role}_key")
}

/// The nodes of `table` whose `upstream_column` holds the key of `upstream`'s instance in every
/// scenario where both exist (and in at least one).
fn downstream<'a>(
    scenarios: &'a ScenarioSet,
    table: &'a NodeTable,
    upstream: &NodeLink,
    upstream_column: &str,
) -> Vec<&'a NodeLink> {
    let Some(column) = table.table.texts(upstream_column) else {
        return Vec::new();
    };
    scenarios
        .links_into(&table.index)
        .filter(|link| {
            let mut linked = false;
            for (key, up) in link.keys.iter().zip(&upstream.keys) {
                let (Some(key), Some(up)) = (key, up) else {
                    continue;
                };
                let Some(&row) = table.index.get(key) else {
                    return false;
                };
                if column.get(row).cloned().flatten().as_deref() != Some(up.as_str()) {
                    return false;
                }
                linked = true;
            }
            linked
        })
        .collect()
}

/// Per group of the swept parameters: its label, the measured mean and the twin's summary
/// (groups where either has no value are left out).
fn comparison_rows(
    scenarios: &ScenarioSet,
    measured: &Metric,
    twin: &Metric,
) -> Vec<(String, f64, Summary)> {
    let mut rows = Vec::new();
    for (label, members) in scenarios.groups(&scenarios.swept()) {
        let values =
            |m: &Metric| -> Vec<f64> { members.iter().filter_map(|&s| m.values[s]).collect() };
        let (Some(x), Some(y)) = (Summary::of(&values(measured)), Summary::of(&values(twin)))
        else {
            continue;
        };
        rows.push((label, x.mean, y));
    }
    rows
}

/// The figure's values: measured, twin mean, std and count per group, and their ratio.
fn comparison_table(rows: &[(String, f64, Summary)], unit: &DisplayUnit) -> ValueTable {
    ValueTable {
        header: vec![
            String::from("group"),
            unit.axis_label("measured"),
            unit.axis_label("twin mean"),
            unit.axis_label("twin std"),
            String::from("n"),
            String::from("twin / measured"),
        ],
        rows: rows
            .iter()
            .map(|(label, x, y)| {
                vec![
                    label.clone(),
                    format_number(x * unit.factor),
                    format_number(y.mean * unit.factor),
                    y.std
                        .map_or(String::from("—"), |e| format_number(e * unit.factor)),
                    y.n.to_string(),
                    format_number(y.mean / x),
                ]
            })
            .collect(),
    }
}

/// Twin mean ± std against the measured value per group of the swept parameters.
fn comparison_figure(scenarios: &ScenarioSet, pair: &Pair<'_>) -> Option<Figure> {
    let measured = Metric::resolve(pair.table, pair.measured, &pair.column)?;
    let twin = Metric::resolve(pair.table, pair.twin, &pair.column)?;
    let rows = comparison_rows(scenarios, &measured, &twin);
    if rows.is_empty() {
        return None;
    }
    let unit = DisplayUnit::for_slice(&measured.unit, rows.iter().flat_map(|r| [r.1, r.2.mean]));
    let name = pretty_name(&measured.base);
    let detail = if measured.detail.is_empty() {
        String::new()
    } else {
        format!(" ({})", measured.detail)
    };
    let points: Vec<PlotPoint> = rows
        .iter()
        .map(|(_, x, y)| PlotPoint {
            x: x * unit.factor,
            y: y.mean * unit.factor,
            y_error: y.std.map(|e| e * unit.factor),
        })
        .collect();
    let (lo, hi) = points
        .iter()
        .flat_map(|p| [p.x, p.y])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    let plot = LinePlot {
        title: format!("{name}{detail}: twin against measured"),
        x_label: unit.axis_label(&format!("measured {name}")),
        y_label: unit.axis_label(&format!("twin {name}")),
        x_log: false,
        y_log: false,
        series: vec![
            PlotSeries {
                label: String::from("equality"),
                points: [lo, hi]
                    .map(|v| PlotPoint {
                        x: v,
                        y: v,
                        y_error: None,
                    })
                    .to_vec(),
                joined: true,
            },
            PlotSeries {
                label: format!("{} / {}", pair.twin.node, pair.measured.node),
                points,
                joined: false,
            },
        ],
    };
    let values = comparison_table(&rows, &unit);
    Some(Figure {
        svg: Some(plot.to_svg()),
        caption: format!(
            "{name}{detail}: node '{}' (twin) against node '{}' (measured).",
            pair.twin.node, pair.measured.node
        ),
        values: Some(values),
    })
}
