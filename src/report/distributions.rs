//! Distributions per group: for every numeric swept parameter with replicates (a grade of
//! surface with its specimen pairs), every replicate's value drawn as a point, one column of
//! points per node side by side at each parameter value — the strip plot of the reference
//! workflow's per-grade comparison (θ, A_t,rel and μ_s of every model). Means hide what the
//! spread over pairs says; these figures show it.

use super::figure::{Figure, ValueTable};
use super::metrics::Metric;
use super::quantity::{pretty_name, short_name, DisplayUnit};
use super::scenarios::ScenarioSet;
use super::svg_plot::{LinePlot, PlotPoint, PlotSeries};
use super::trends::{node_label, numeric_axes, sample};

/// Largest number of distinct parameter values drawn as groups (beyond it, a trend reads better).
const MAX_GROUPS: usize = 12;

/// Share of the smallest gap between parameter values that the nodes' columns of points span.
const SPREAD: f64 = 0.5;

/// One strip figure per numeric swept parameter and per family of metrics (`families`: each a
/// list of metrics drawn side by side, e.g. μ_s of every friction node). Empty without replicate
/// axes or with more than [`MAX_GROUPS`] values.
pub fn distribution_figures(scenarios: &ScenarioSet, families: &[Vec<&Metric>]) -> Vec<Figure> {
    if scenarios.replicate_names().is_empty() {
        return Vec::new();
    }
    let mut figures = Vec::new();
    for (x, param, _) in numeric_axes(scenarios) {
        let mut xs: Vec<f64> = (0..scenarios.count)
            .filter_map(|s| scenarios.value(x, s))
            .collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        if xs.len() < 2 || xs.len() > MAX_GROUPS {
            continue;
        }
        let gap = xs
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        for family in families.iter().filter(|f| !f.is_empty()) {
            let axis = (pretty_name(&param.name), &param.display);
            if let Some(f) = strip_figure(scenarios, x, axis, family, gap) {
                figures.push(f);
            }
        }
    }
    figures
}

/// The strip plot of `metrics` against parameter `x`: node k of n at x + (k − (n − 1)/2)·δ with
/// δ = [`SPREAD`]·gap/n, one point per scenario.
fn strip_figure(
    scenarios: &ScenarioSet,
    x: usize,
    (x_name, x_unit): (String, &DisplayUnit),
    metrics: &[&Metric],
    gap: f64,
) -> Option<Figure> {
    let first = metrics.first()?;
    let y_unit = DisplayUnit::for_slice(
        &first.unit,
        metrics
            .iter()
            .flat_map(|m| m.values.iter().flatten().copied()),
    );
    let n = metrics.len() as f64;
    let step = SPREAD * gap / n;
    let x_label = x_unit.axis_label(&x_name);
    let y_label = y_unit.axis_label(&pretty_name(&first.base));
    let mut values = ValueTable {
        header: vec![
            String::from("series"),
            x_label.clone(),
            String::from("value"),
        ],
        rows: Vec::new(),
    };
    let mut series = Vec::new();
    for (k, metric) in metrics.iter().enumerate() {
        let offset = (k as f64 - (n - 1.0) / 2.0) * step;
        let label = node_label(metric);
        let points: Vec<PlotPoint> = (0..scenarios.count)
            .flat_map(|s| sample(scenarios, x, metric, s))
            .filter(|(_, y)| y.is_finite())
            .map(|(px, y)| {
                values.rows.push(vec![
                    label.clone(),
                    super::axis::format_number(px * x_unit.factor),
                    super::axis::format_number(y * y_unit.factor),
                ]);
                PlotPoint {
                    x: (px + offset) * x_unit.factor,
                    y: y * y_unit.factor,
                    y_error: None,
                }
            })
            .collect();
        if !points.is_empty() {
            series.push(PlotSeries {
                label,
                points,
                joined: false,
            });
        }
    }
    if series.is_empty() {
        return None;
    }
    let plot = LinePlot {
        title: format!(
            "{} per {}: every replicate",
            short_name(&first.base),
            short_name(&scenarios.parameters[x].name)
        ),
        x_label,
        y_label,
        x_log: false,
        y_log: false,
        series,
    };
    Some(Figure {
        svg: Some(plot.to_svg()),
        caption: format!(
            "one point per scenario ({} over {}); the nodes' columns are set side by side around \
             each value of the parameter",
            scenarios.replicate_names().join(", "),
            short_name(&scenarios.parameters[x].name)
        ),
        values: Some(values),
    })
}
