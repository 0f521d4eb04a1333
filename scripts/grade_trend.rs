//! Whether each metric of a grouped summary ranks its groups as the reference did (rising with
//! the group parameter), with the effect size of the extreme groups: the difference of their
//! means over the pooled standard deviation of their scenarios,
//! `d = (m_last − m_first) / √(((n₁ − 1) s₁² + (n₂ − 1) s₂²) / (n₁ + n₂ − 2))`.
//!
//! Input: a `summary_<name>.parquet` of a study (docs/study-format.md, "Summaries") grouped by
//! one parameter, e.g. `results/ground-validation/summary_per_grade.parquet` (by `sq_ii`).
//! Groups are sorted by that parameter. Output: one line per metric (`<node>_<metric>`): the
//! group means, the order ("rises", "falls" or "mixed") and `d`.
//!
//! Run: `cargo run --release --example grade_trend -- SUMMARY.parquet [METRIC_SUBSTRING]`

use std::fs::File;
use std::process::ExitCode;

use polars::prelude::*;

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("grade_trend: {message}");
            ExitCode::FAILURE
        }
    }
}

/// One metric's mean, standard deviation and count per group, in group order.
struct Series {
    mean: Vec<f64>,
    std: Vec<f64>,
    n: Vec<f64>,
}

impl Series {
    fn order(&self) -> &'static str {
        let steps: Vec<f64> = self.mean.windows(2).map(|w| w[1] - w[0]).collect();
        if steps.iter().all(|&s| s > 0.0) {
            "rises"
        } else if steps.iter().all(|&s| s < 0.0) {
            "falls"
        } else {
            "mixed"
        }
    }

    /// Effect size of the last group against the first; `None` without a pooled spread.
    fn effect_size(&self) -> Option<f64> {
        let (first, last) = (0, self.mean.len() - 1);
        let (n1, n2) = (self.n[first], self.n[last]);
        let pooled = ((n1 - 1.0) * self.std[first].powi(2) + (n2 - 1.0) * self.std[last].powi(2))
            / (n1 + n2 - 2.0);
        let d = (self.mean[last] - self.mean[first]) / pooled.sqrt();
        d.is_finite().then_some(d)
    }
}

fn column(frame: &DataFrame, name: &str) -> Result<Vec<f64>, String> {
    let series = frame
        .column(name)
        .and_then(|c| c.cast(&DataType::Float64))
        .map_err(|e| format!("column '{name}': {e}"))?;
    let values = series.f64().map_err(|e| e.to_string())?;
    Ok(values.iter().map(|v| v.unwrap_or(f64::NAN)).collect())
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (path, filter) = match args.as_slice() {
        [path] => (path, ""),
        [path, filter] => (path, filter.as_str()),
        _ => {
            return Err(String::from(
                "usage: grade_trend SUMMARY.parquet [METRIC_SUBSTRING]",
            ))
        }
    };
    let file = File::open(path).map_err(|e| format!("{path}: {e}"))?;
    let frame = ParquetReader::new(file)
        .finish()
        .map_err(|e| format!("{path}: {e}"))?;
    let names: Vec<String> = frame
        .get_column_names()
        .iter()
        .map(|n| n.to_string())
        .collect();
    let group = names.first().ok_or_else(|| format!("{path}: no columns"))?;
    let groups = column(&frame, group)?;
    let mut order: Vec<usize> = (0..groups.len()).collect();
    order.sort_by(|&a, &b| groups[a].total_cmp(&groups[b]));
    if order.len() < 2 {
        return Err(format!("{path}: fewer than two groups of '{group}'"));
    }
    let sorted = |v: Vec<f64>| order.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    println!("groups by {group}: {:?}", sorted(groups.clone()));
    for n_name in names
        .iter()
        .filter(|n| n.ends_with("_n") && n.contains(filter))
    {
        let metric = &n_name[..n_name.len() - 2];
        let with_prefix = |suffix: &str| {
            names
                .iter()
                .find(|c| c.starts_with(&format!("{metric}{suffix}")))
                .cloned()
        };
        let (Some(mean), Some(std)) = (with_prefix("_mean"), with_prefix("_std")) else {
            continue;
        };
        let series = Series {
            mean: sorted(column(&frame, &mean)?),
            std: sorted(column(&frame, &std)?),
            n: sorted(column(&frame, n_name)?),
        };
        let means: Vec<String> = series.mean.iter().map(|m| format!("{m:.5}")).collect();
        let d = series
            .effect_size()
            .map_or_else(|| String::from("-"), |d| format!("{d:+.2}"));
        println!(
            "{metric}: {} ({}), d = {d}",
            means.join(" / "),
            series.order()
        );
    }
    Ok(())
}
