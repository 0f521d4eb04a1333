//! Trend and load-curve figures: replicate groups of scenarios reduced to mean ± standard
//! deviation and drawn as one series per value of the other swept parameters.

use std::collections::BTreeMap;

use super::figure::{Figure, ValueTable};
use super::metrics::{Metric, NodeTable};
use super::quantity::{pretty_name, short_name, DisplayUnit};
use super::scenarios::ScenarioSet;
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

/// One figure per swept parameter: the metric against it, one series per combination of the
/// other swept parameters, error bars over the replicate axes. Without a swept parameter, one
/// table-only entry with the overall mean ± standard deviation.
pub fn trend_figures(scenarios: &ScenarioSet, metric: &Metric) -> Vec<Figure> {
    let swept = scenarios.swept();
    let replicates = scenarios.replicate_names();
    let over = if replicates.is_empty() {
        String::from("no replicate axis: each point is one scenario")
    } else {
        format!(
            "error bars: ± one sample standard deviation over {}",
            replicates.join(", ")
        )
    };
    let value = |s: usize| metric.values.get(s).copied().flatten();
    if swept.is_empty() {
        let all: Vec<f64> = (0..scenarios.count).filter_map(value).collect();
        let Some(summary) = Summary::of(&all) else {
            return Vec::new();
        };
        let unit = DisplayUnit::for_values(&metric.unit, summary.mean.abs());
        let std = summary.std.map_or(String::from("—"), |s| unit.format(s));
        return vec![Figure {
            svg: None,
            caption: format!(
                "{} of {} over all {} scenario(s): {} ± {std}",
                pretty_name(&metric.base),
                node_title(metric),
                summary.n,
                unit.format(summary.mean)
            ),
            values: None,
        }];
    }
    let mut figures = Vec::new();
    for &x in &swept {
        let Some(param) = scenarios.parameters.get(x) else {
            continue;
        };
        if !param.categories.is_empty() {
            continue;
        }
        let others: Vec<usize> = swept.iter().copied().filter(|&p| p != x).collect();
        let series = summarise(scenarios.groups(&others), |s| {
            scenarios.value(x, s).zip(value(s)).into_iter().collect()
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
            over.clone(),
        ));
    }
    figures
}

/// Load curves of every contact node: area fraction and stress ratio against the nominal
/// pressure of each load step, one series per combination of the swept parameters.
pub fn load_curve_figures(
    scenarios: &ScenarioSet,
    contacts: &NodeTable,
    curve: &super::table::ResultTable,
) -> Vec<Figure> {
    let (Some(keys), Some(pressure)) = (curve.texts("key"), curve.numbers("nominal_pressure_Pa"))
    else {
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
        for column in ["area_fraction", "stress_ratio"] {
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
                (&pretty_name("nominal_pressure"), &pressure_unit),
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
