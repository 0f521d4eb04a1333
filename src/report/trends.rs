//! Trend and load-curve figures: replicate groups of scenarios reduced to mean ± standard
//! deviation and drawn as one series per value of the other swept parameters; the friction-model
//! comparison draws μ_s of every friction node in one figure per swept parameter.

use std::collections::BTreeMap;

use crate::engine::value::column_name;
use crate::units::Dimension;
use crate::vocabulary::metrics;

use super::figure::{Figure, ValueTable};
use super::metrics::{Metric, NodeTable};
use super::quantity::{pretty_name, short_name, DisplayUnit};
use super::scenarios::{Parameter, ScenarioSet};
use super::statistics::Summary;
use super::svg_plot::{LinePlot, PlotPoint, PlotSeries};

/// One series of replicate summaries, by x (SI).
struct SummarySeries {
    label: String,
    points: Vec<(f64, Summary)>,
}

/// Reduces each group of scenarios to summaries by x: `samples(s)` gives the `(x, y)` values of
/// scenario `s` (SI); values at equal x are replicates.
fn summarise(
    groups: Vec<(String, Vec<usize>)>,
    samples: impl Fn(usize) -> Vec<(f64, f64)>,
) -> Vec<SummarySeries> {
    groups
        .into_iter()
        .filter_map(|(label, scenarios)| {
            let mut by_x: BTreeMap<u64, (f64, Vec<f64>)> = BTreeMap::new();
            for s in scenarios {
                for (x, y) in samples(s) {
                    by_x.entry(x.to_bits()).or_insert((x, Vec::new())).1.push(y);
                }
            }
            let mut points: Vec<(f64, Summary)> = by_x
                .into_values()
                .filter_map(|(x, ys)| Summary::of(&ys).map(|s| (x, s)))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            (!points.is_empty()).then_some(SummarySeries { label, points })
        })
        .collect()
}

/// The plot and value table of summarised series.
fn figure(
    title: String,
    (x_name, x_unit): (&str, &DisplayUnit),
    (y_name, y_si): (&str, &str),
    series: &[SummarySeries],
    caption: String,
) -> Figure {
    let y_unit = DisplayUnit::for_slice(
        y_si,
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1.mean)),
    );
    let x_label = x_unit.axis_label(x_name);
    let y_label = y_unit.axis_label(y_name);
    let mut values = ValueTable {
        header: vec![
            String::from("series"),
            x_label.clone(),
            String::from("mean"),
            String::from("std"),
            String::from("n"),
        ],
        rows: Vec::new(),
    };
    let mut plot_series = Vec::new();
    for s in series {
        let mut points = Vec::new();
        for (x, summary) in &s.points {
            let y = summary.mean * y_unit.factor;
            let e = summary.std.map(|e| e * y_unit.factor);
            points.push(PlotPoint {
                x: x * x_unit.factor,
                y,
                y_error: e,
            });
            values.rows.push(vec![
                s.label.clone(),
                super::axis::format_number(x * x_unit.factor),
                super::axis::format_number(y),
                e.map_or(String::from("—"), super::axis::format_number),
                summary.n.to_string(),
            ]);
        }
        plot_series.push(PlotSeries {
            label: s.label.clone(),
            points,
            joined: true,
        });
    }
    let plot = LinePlot {
        title,
        x_log: LinePlot::spans_decades(
            plot_series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.x)),
        ),
        y_log: LinePlot::spans_decades(
            plot_series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.y)),
        ),
        x_label,
        y_label,
        series: plot_series,
    };
    Figure {
        svg: Some(plot.to_svg()),
        caption,
        values: Some(values),
    }
}

fn node_title(metric: &Metric) -> String {
    let kind = metric.table.trim_end_matches('s');
    if metric.detail.is_empty() {
        format!("{kind} '{}'", metric.node)
    } else {
        format!("{kind} '{}' ({})", metric.node, metric.detail)
    }
}

/// The caption of a trend: what the error bars are.
fn error_bar_caption(scenarios: &ScenarioSet) -> String {
    let replicates = scenarios.replicate_names();
    if replicates.is_empty() {
        String::from("no replicate axis: each point is one scenario")
    } else {
        format!(
            "error bars: ± one sample standard deviation over {}",
            replicates.join(", ")
        )
    }
}

/// The numeric swept parameters, each with its index and the other swept parameters.
pub(super) fn numeric_axes(scenarios: &ScenarioSet) -> Vec<(usize, &Parameter, Vec<usize>)> {
    let swept = scenarios.swept();
    swept
        .iter()
        .filter_map(|&x| {
            let param = scenarios
                .parameters
                .get(x)
                .filter(|p| p.categories.is_empty())?;
            let others = swept.iter().copied().filter(|&p| p != x).collect();
            Some((x, param, others))
        })
        .collect()
}

/// The `(x, metric)` sample of scenario `s` against parameter `x`, if both are known.
pub(super) fn sample(
    scenarios: &ScenarioSet,
    x: usize,
    metric: &Metric,
    s: usize,
) -> Vec<(f64, f64)> {
    let value = metric.values.get(s).copied().flatten();
    scenarios.value(x, s).zip(value).into_iter().collect()
}

/// One figure per swept parameter: the metric against it, one series per combination of the
/// other swept parameters, error bars over the replicate axes. Without a swept parameter, one
/// table-only entry with the overall mean ± standard deviation.
pub fn trend_figures(scenarios: &ScenarioSet, metric: &Metric) -> Vec<Figure> {
    if scenarios.swept().is_empty() {
        return overall_summary(scenarios, metric).into_iter().collect();
    }
    let mut figures = Vec::new();
    for (x, param, others) in numeric_axes(scenarios) {
        let series = summarise(scenarios.groups(&others), |s| {
            sample(scenarios, x, metric, s)
        });
        if series.is_empty() {
            continue;
        }
        let y_name = short_name(&metric.base);
        figures.push(figure(
            format!(
                "{y_name} vs {} — {}",
                short_name(&param.name),
                node_title(metric)
            ),
            (&pretty_name(&param.name), &param.display),
            (&pretty_name(&metric.base), &metric.unit),
            &series,
            error_bar_caption(scenarios),
        ));
    }
    figures
}

/// The table-only entry of a metric without swept parameters: mean ± standard deviation over
/// all scenarios.
fn overall_summary(scenarios: &ScenarioSet, metric: &Metric) -> Option<Figure> {
    let all: Vec<f64> = (0..scenarios.count)
        .filter_map(|s| metric.values.get(s).copied().flatten())
        .collect();
    let summary = Summary::of(&all)?;
    let unit = DisplayUnit::for_values(&metric.unit, summary.mean.abs());
    let std = summary.std.map_or(String::from("—"), |s| unit.format(s));
    Some(Figure {
        svg: None,
        caption: format!(
            "{} of {} over all {} scenario(s): {} ± {std}",
            pretty_name(&metric.base),
            node_title(metric),
            summary.n,
            unit.format(summary.mean)
        ),
        values: None,
    })
}

/// A node's series label: `stick_per_spot (per_spot, full_stick)`.
pub(super) fn node_label(metric: &Metric) -> String {
    if metric.detail.is_empty() {
        metric.node.clone()
    } else {
        format!("{} ({})", metric.node, metric.detail)
    }
}

/// The comparison of the friction nodes: for every numeric swept parameter one figure "μ_s by
/// friction model", μ_s against the parameter with one series per node (per node and
/// combination of the other swept parameters when several are swept), mean ± sample standard
/// deviation over the replicate axes. `metrics`: μ_s of each friction node. Empty unless at
/// least two nodes have values.
pub fn friction_model_figures(scenarios: &ScenarioSet, metrics: &[&Metric]) -> Vec<Figure> {
    let mut figures = Vec::new();
    for (x, param, others) in numeric_axes(scenarios) {
        let mut series = Vec::new();
        let mut nodes = 0;
        for &metric in metrics {
            let groups = scenarios
                .groups(&others)
                .into_iter()
                .map(|(label, members)| match label.as_str() {
                    "" => (node_label(metric), members),
                    _ => (format!("{}, {label}", node_label(metric)), members),
                })
                .collect();
            let found = summarise(groups, |s| sample(scenarios, x, metric, s));
            nodes += usize::from(!found.is_empty());
            series.extend(found);
        }
        let Some(first) = metrics.first().filter(|_| nodes >= 2) else {
            continue;
        };
        figures.push(figure(
            format!(
                "{} by friction model vs {}",
                short_name(&first.base),
                short_name(&param.name)
            ),
            (&pretty_name(&param.name), &param.display),
            (&pretty_name(&first.base), &first.unit),
            &series,
            left_out_caption(scenarios, x, metrics),
        ));
    }
    figures
}

/// The error-bar caption plus how many values of the scenarios with a value of parameter `x`
/// are left out: missing (failed or not computed) and non-finite ones.
fn left_out_caption(scenarios: &ScenarioSet, x: usize, metrics: &[&Metric]) -> String {
    let (mut missing, mut non_finite) = (0, 0);
    for metric in metrics {
        for s in (0..scenarios.count).filter(|&s| scenarios.value(x, s).is_some()) {
            match metric.values.get(s).copied().flatten() {
                None => missing += 1,
                Some(v) if !v.is_finite() => non_finite += 1,
                Some(_) => {}
            }
        }
    }
    let mut caption = error_bar_caption(scenarios);
    if missing > 0 {
        caption.push_str(&format!(
            "; {missing} missing value(s) (failed or not computed) left out"
        ));
    }
    if non_finite > 0 {
        caption.push_str(&format!(
            "; {non_finite} non-finite value(s) cannot be drawn and are left out"
        ));
    }
    caption
}

/// Load curves of every contact node: area fraction and stress ratio against the nominal
/// pressure of each load step, one series per combination of the swept parameters.
pub fn load_curve_figures(
    scenarios: &ScenarioSet,
    contacts: &NodeTable,
    curve: &super::table::ResultTable,
) -> Vec<Figure> {
    let pressure_column = column_name(metrics::NOMINAL_PRESSURE, Dimension::Pressure);
    let (Some(keys), Some(pressure)) = (curve.texts("key"), curve.numbers(&pressure_column)) else {
        return Vec::new();
    };
    let mut rows_of: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for (row, key) in keys.iter().enumerate() {
        if let Some(k) = key {
            rows_of.entry(k.as_str()).or_default().push(row);
        }
    }
    let swept = scenarios.swept();
    let replicates = scenarios.replicate_names();
    let pressure_unit = DisplayUnit::for_slice("Pa", pressure.iter().flatten().copied());
    let mut figures = Vec::new();
    for link in scenarios.links_into(&contacts.index) {
        for column in [metrics::AREA_FRACTION, metrics::STRESS_RATIO] {
            let Some(values) = curve.numbers(column) else {
                continue;
            };
            let series = summarise(scenarios.groups(&swept), |s| {
                let key = link.keys.get(s).and_then(|k| k.as_deref());
                key.and_then(|k| rows_of.get(k))
                    .map(|rows| {
                        rows.iter()
                            .filter_map(|&r| {
                                pressure
                                    .get(r)
                                    .copied()
                                    .flatten()
                                    .zip(values.get(r).copied().flatten())
                            })
                            .collect()
                    })
                    .unwrap_or_default()
            });
            if series.is_empty() {
                continue;
            }
            let caption = if replicates.is_empty() {
                String::from("one load-stepped contact computation per point")
            } else {
                format!(
                    "mean over {}; error bars: ± one sample standard deviation",
                    replicates.join(", ")
                )
            };
            figures.push(figure(
                format!(
                    "Load curve: {} — contact '{}'",
                    short_name(column),
                    link.node
                ),
                (&pretty_name(metrics::NOMINAL_PRESSURE), &pressure_unit),
                (&pretty_name(column), ""),
                &series,
                caption,
            ));
        }
    }
    figures
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The SVG of a one-series figure with the means `ys` at x = 1, 2, …
    fn svg_of(ys: &[f64]) -> String {
        let series = vec![SummarySeries {
            label: String::from("s"),
            points: (ys.iter().enumerate())
                .map(|(i, &y)| ((i + 1) as f64, Summary::of(&[y]).expect("one value")))
                .collect(),
        }];
        let figure = figure(
            String::from("t"),
            ("x", &DisplayUnit::none()),
            ("y", ""),
            &series,
            String::new(),
        );
        figure.svg.expect("a plot")
    }

    /// Scenarios 0–3: `load` 1, 1, 2, 2 (swept), `seed` 1, 2, 1, 2 (replicate axis).
    fn two_loads_two_seeds() -> ScenarioSet {
        let parameter = |name: &str, values: [f64; 4], replicate| Parameter {
            name: name.to_string(),
            unit: String::new(),
            values: values.iter().map(|&v| Some(v)).collect(),
            categories: Vec::new(),
            replicate,
            display: DisplayUnit::none(),
        };
        ScenarioSet {
            count: 4,
            parameters: vec![
                parameter("load", [1.0, 1.0, 2.0, 2.0], false),
                parameter("seed", [1.0, 2.0, 1.0, 2.0], true),
            ],
            nodes: Vec::new(),
            replicates_named: false,
        }
    }

    fn mu_s(node: &str, detail: &str, values: [Option<f64>; 4]) -> Metric {
        Metric {
            table: String::from("friction"),
            node: node.to_string(),
            column: String::from("mu_s"),
            base: String::from("mu_s"),
            unit: String::new(),
            detail: detail.to_string(),
            values: values.to_vec(),
        }
    }

    #[test]
    fn friction_nodes_share_one_figure_and_undrawable_values_are_counted() {
        let set = two_loads_two_seeds();
        let ke = mu_s("ke", "statistical, kogut_etsion", [Some(0.3); 4]);
        // Means 0 and 0.02 with ke at 0.3: not all positive, so the y axis stays linear and
        // the zero is drawn; the failed row and the infinite value are left out and counted.
        let stick = mu_s("stick", "", [Some(0.0), Some(0.0), None, Some(0.02)]);
        let odd = mu_s(
            "odd",
            "",
            [Some(f64::INFINITY), Some(0.5), Some(0.4), Some(0.4)],
        );
        let figures = friction_model_figures(&set, &[&ke, &stick, &odd]);
        assert_eq!(figures.len(), 1);
        let figure = figures.first().expect("one figure");
        let svg = figure.svg.as_deref().expect("a plot");
        assert!(svg.contains("μ_s by friction model vs load"), "{svg}");
        for label in ["ke (statistical, kogut_etsion)", "stick", "odd"] {
            assert!(svg.contains(&format!(">{label}</text>")), "{label}: {svg}");
        }
        // Three series of two points, plus three legend markers; linear ticks.
        assert_eq!(svg.matches("<circle").count(), 9);
        assert!(svg.contains(">0.1<") && !svg.contains(">0.001<"), "{svg}");
        assert!(
            figure.caption.contains("1 missing value(s)"),
            "{}",
            figure.caption
        );
        assert!(
            figure.caption.contains("1 non-finite value(s)"),
            "{}",
            figure.caption
        );
        // One node with values is no comparison.
        let empty = mu_s("empty", "", [None; 4]);
        assert!(friction_model_figures(&set, &[&ke, &empty]).is_empty());
    }

    #[test]
    fn the_y_axis_is_logarithmic_when_the_means_span_two_decades() {
        // Decade ticks only on a log axis over 1e-4 … 1; a linear axis has 0.2, 0.4, …
        let log = svg_of(&[1e-4, 1e-2, 1.0]);
        assert!(log.contains(">0.001<") && !log.contains(">0.2<"), "{log}");
        let linear = svg_of(&[0.2, 0.5, 1.0]);
        assert!(
            linear.contains(">0.2<") && !linear.contains(">0.001<"),
            "{linear}"
        );
    }
}
