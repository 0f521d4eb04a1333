//! Axis scales and tick marks: "nice" linear ticks (1, 2, 5 × 10ᵏ steps), decade ticks on log
//! axes, and tick labels with as many decimals as the step needs.

/// A linear or logarithmic mapping of a data interval onto a pixel interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    pub min: f64,
    pub max: f64,
    pub log: bool,
}

impl Scale {
    /// A scale covering `values` (finite ones; on a log scale positive ones) with 5 % padding
    /// on a linear scale; a degenerate interval is widened so it has a visible extent.
    pub fn covering(values: impl IntoIterator<Item = f64>, log: bool) -> Self {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values {
            if v.is_finite() && (!log || v > 0.0) {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if !lo.is_finite() {
            return Self {
                min: if log { 1.0 } else { 0.0 },
                max: if log { 10.0 } else { 1.0 },
                log,
            };
        }
        if log {
            let (lo, hi) = if hi / lo < 1.5 {
                (lo / 1.5, hi * 1.5)
            } else {
                (lo, hi)
            };
            return Self {
                min: 10f64.powf(lo.log10().floor()),
                max: 10f64.powf(hi.log10().ceil()),
                log,
            };
        }
        let span = hi - lo;
        let pad = if span > 0.0 {
            0.05 * span
        } else if lo != 0.0 {
            0.1 * lo.abs()
        } else {
            1.0
        };
        Self {
            min: lo - pad,
            max: hi + pad,
            log,
        }
    }

    /// The position of `v` in `[0, 1]` along the axis (outside for values out of range).
    pub fn fraction(&self, v: f64) -> f64 {
        if self.log {
            (v.log10() - self.min.log10()) / (self.max.log10() - self.min.log10())
        } else {
            (v - self.min) / (self.max - self.min)
        }
    }

    /// Tick positions and labels.
    pub fn ticks(&self) -> Vec<(f64, String)> {
        if self.log {
            log_ticks(self.min, self.max)
        } else {
            linear_ticks(self.min, self.max, 6)
        }
    }
}

/// The "nice" step (1, 2 or 5 × 10ᵏ) closest above `raw`.
fn nice_step(raw: f64) -> f64 {
    let magnitude = 10f64.powf(raw.log10().floor());
    let fraction = raw / magnitude;
    let nice = if fraction <= 1.0 {
        1.0
    } else if fraction <= 2.0 {
        2.0
    } else if fraction <= 5.0 {
        5.0
    } else {
        10.0
    };
    nice * magnitude
}

/// Ticks at multiples of a nice step inside `[min, max]`, about `target` of them.
pub fn linear_ticks(min: f64, max: f64, target: usize) -> Vec<(f64, String)> {
    if !(min.is_finite() && max.is_finite()) || max <= min {
        return Vec::new();
    }
    let step = nice_step((max - min) / target.max(2) as f64);
    let first = (min / step).ceil() as i64;
    let last = (max / step).floor() as i64;
    (first..=last)
        .map(|i| {
            let v = i as f64 * step;
            (v, format_tick(v, step))
        })
        .collect()
}

/// Decade ticks (with 2 and 5 × 10ᵏ when the axis spans fewer than three decades).
fn log_ticks(min: f64, max: f64) -> Vec<(f64, String)> {
    let (lo, hi) = (min.log10().floor() as i32, max.log10().ceil() as i32);
    let mantissas: &[f64] = if hi - lo < 3 {
        &[1.0, 2.0, 5.0]
    } else {
        &[1.0]
    };
    let mut ticks = Vec::new();
    for e in lo..=hi {
        for &m in mantissas {
            let v = m * 10f64.powi(e);
            if v >= min * (1.0 - 1e-9) && v <= max * (1.0 + 1e-9) {
                let label = if (-4..6).contains(&e) {
                    format_number(v)
                } else {
                    format!("{v:e}")
                };
                ticks.push((v, label));
            }
        }
    }
    ticks
}

/// A tick label with the decimals the step needs (`0.25`, `20`, `1e-06` for extreme values).
pub fn format_tick(v: f64, step: f64) -> String {
    let v = if v.abs() < step * 1e-9 { 0.0 } else { v };
    if v != 0.0 && (v.abs() >= 1e6 || v.abs() < 1e-4) {
        return format!("{v:e}");
    }
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// A number with four significant digits, for labels and value tables.
pub fn format_number(v: f64) -> String {
    if !v.is_finite() {
        return String::from("—");
    }
    if v == 0.0 {
        return String::from("0");
    }
    let magnitude = v.abs().log10().floor();
    if !(-4.0..6.0).contains(&magnitude) {
        return format!("{v:.3e}");
    }
    let decimals = (3.0 - magnitude).max(0.0) as usize;
    let text = format!("{v:.decimals$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_use_nice_steps_inside_the_range() {
        let t = linear_ticks(0.03, 0.97, 6);
        let labels: Vec<&str> = t.iter().map(|t| t.1.as_str()).collect();
        assert_eq!(labels, ["0.2", "0.4", "0.6", "0.8"]);
        let t = linear_ticks(-3.0, 21.0, 6);
        assert_eq!(t.first().map(|t| t.1.as_str()), Some("0"));
        assert_eq!(t.last().map(|t| t.1.as_str()), Some("20"));
    }

    #[test]
    fn log_scales_snap_to_decades() {
        let s = Scale::covering([3e6, 2e7], true);
        assert_eq!((s.min, s.max), (1e6, 1e8));
        let labels: Vec<String> = s.ticks().into_iter().map(|t| t.1).collect();
        assert_eq!(labels.first().map(String::as_str), Some("1e6"));
        assert_eq!(labels.len(), 7);
    }

    #[test]
    fn numbers_keep_four_significant_digits() {
        assert_eq!(format_number(0.123456), "0.1235");
        assert_eq!(format_number(20.0), "20");
        assert_eq!(format_number(1234.6), "1235");
        assert_eq!(format_number(2.5e-7), "2.500e-7");
    }
}
