//! Height and contact-pressure maps of chosen scenarios, read from the cache through the
//! engine's verified [`Cache::load`]: surface entries hold `heights` (m, `[[iy, ix]]`) with the
//! spacings `dx`/`dy` among their metrics; contact entries run with `fields: true` hold
//! `pressure` (Pa) on the grid of their `lower` surface.

use ndarray::{ArrayD, Ix2};

use crate::engine::cache::{Cache, CachedEntry};
use crate::engine::hash::NodeKey;
use crate::engine::value::Value;
use crate::vocabulary::{arrays, kinds, metrics, roles};

use super::error::ReportError;
use super::figure::Figure;
use super::map_figure::MapFigure;
use super::metrics::NodeTable;
use super::scenarios::ScenarioSet;

/// The scenarios to draw by default: the first replicate of up to `count` configurations,
/// spread evenly over the configurations (every combination of the swept parameters).
pub fn default_scenarios(scenarios: &ScenarioSet, count: usize) -> Vec<usize> {
    let configurations: Vec<usize> = scenarios
        .groups(&scenarios.swept())
        .iter()
        .filter_map(|g| g.1.first().copied())
        .collect();
    let n = configurations.len();
    if count == 0 || n == 0 {
        return Vec::new();
    }
    if n <= count {
        return configurations;
    }
    let mut chosen: Vec<usize> = (0..count)
        .map(|i| configurations[(i * (n - 1)) / (count - 1).max(1)])
        .collect();
    chosen.dedup();
    chosen
}

fn load(cache: &Cache, kind: &str, key: &str, arrays: bool) -> Result<CachedEntry, String> {
    let node_key = NodeKey::from_hex(key).ok_or_else(|| format!("'{key}' is not a node key"))?;
    match cache.load(kind, &node_key, arrays) {
        Ok(Some(entry)) => Ok(entry),
        Ok(None) => Err(format!(
            "{kind} {} is not in the cache {}",
            node_key.short(),
            cache.root().display()
        )),
        Err(e) => Err(e.to_string()),
    }
}

fn spacing(entry: &CachedEntry) -> Option<(f64, f64)> {
    let metric = |name: &str| match entry.artifact.metrics.iter().find(|f| f.name == name) {
        Some(f) => match f.value {
            Value::Float(v) if v > 0.0 && v.is_finite() => Some(v),
            _ => None,
        },
        None => None,
    };
    Some((metric(metrics::DX)?, metric(metrics::DY)?))
}

fn as_map(array: &ArrayD<f64>) -> Option<ndarray::ArrayView2<'_, f64>> {
    array.view().into_dimensionality::<Ix2>().ok()
}

/// Map figures for `chosen` scenarios; what cannot be drawn is added to `skipped`. Each surface
/// instance is drawn once even when several scenarios use it.
pub fn map_figures(
    cache: &Cache,
    scenarios: &ScenarioSet,
    tables: &[NodeTable],
    chosen: &[usize],
    skipped: &mut Vec<String>,
) -> Result<Vec<Figure>, ReportError> {
    let mut figures = Vec::new();
    let mut drawn: Vec<String> = Vec::new();
    let all: Vec<usize> = (0..scenarios.parameters.len()).collect();
    for &s in chosen {
        if s >= scenarios.count {
            return Err(ReportError::ScenarioOutOfRange {
                index: s,
                count: scenarios.count,
            });
        }
        let context = format!("scenario {s} ({})", scenarios.describe(s, &all));
        for table in tables {
            for link in scenarios.links_into(&table.index) {
                let Some(key) = link.keys.get(s).cloned().flatten() else {
                    continue;
                };
                if drawn.contains(&key) {
                    continue;
                }
                let figure = match table.kind.as_str() {
                    kinds::SURFACE => height_figure(cache, &key, &link.node, &context),
                    kinds::CONTACT => pressure_figure(cache, &key, &link.node, &context),
                    _ => continue,
                };
                match figure {
                    Ok(f) => {
                        drawn.push(key);
                        figures.push(f?);
                    }
                    Err(reason) => {
                        skipped.push(format!("map of '{}' in {context}: {reason}", link.node))
                    }
                }
            }
        }
    }
    Ok(figures)
}

type MapResult = Result<Result<Figure, ReportError>, String>;

fn height_figure(cache: &Cache, key: &str, node: &str, context: &str) -> MapResult {
    let entry = load(cache, kinds::SURFACE, key, true)?;
    let (dx, dy) = spacing(&entry).ok_or("the entry records no grid spacing")?;
    let heights = entry
        .artifact
        .arrays
        .get(arrays::HEIGHTS)
        .and_then(as_map)
        .ok_or(
            "the entry holds no height array (synthetic surfaces above 1024² points are \
             regenerated when needed, not cached)",
        )?;
    let figure = MapFigure {
        title: format!("Heights of surface '{node}'"),
        values: heights,
        dx,
        dy,
        quantity: String::from("height"),
        si_unit: String::from("m"),
        zero_is_empty: false,
    };
    Ok(figure.to_svg().map(|svg| Figure {
        svg: Some(svg),
        caption: format!("{context}; surface {}", &key[..12.min(key.len())]),
        values: None,
    }))
}

fn pressure_figure(cache: &Cache, key: &str, node: &str, context: &str) -> MapResult {
    let entry = load(cache, kinds::CONTACT, key, true)?;
    let pressure = entry
        .artifact
        .arrays
        .get(arrays::PRESSURE)
        .and_then(as_map)
        .ok_or("no pressure field stored (run the contact with `fields: true`)")?;
    let lower = entry
        .manifest
        .upstream
        .iter()
        .find(|(role, _)| role == roles::LOWER)
        .ok_or("the entry names no lower surface")?;
    let surface = load(cache, kinds::SURFACE, &lower.1, false)?;
    let (dx, dy) = spacing(&surface).ok_or("the lower surface records no grid spacing")?;
    let nominal = entry
        .artifact
        .metrics
        .iter()
        .find(|f| f.name == metrics::NOMINAL_PRESSURE)
        .and_then(|f| match f.value {
            Value::Float(v) => Some(format!(" at {} MPa", super::axis::format_number(v * 1e-6))),
            _ => None,
        })
        .unwrap_or_default();
    let figure = MapFigure {
        title: format!("Contact pressure of '{node}'{nominal}"),
        values: pressure,
        dx,
        dy,
        quantity: String::from("pressure"),
        si_unit: String::from("Pa"),
        zero_is_empty: true,
    };
    Ok(figure.to_svg().map(|svg| Figure {
        svg: Some(svg),
        caption: format!(
            "{context}; contact {}, final load step",
            &key[..12.min(key.len())]
        ),
        values: None,
    }))
}
