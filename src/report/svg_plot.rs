//! Line plots as inline `<svg>` elements for HTML (no `xmlns`: the HTML parser assigns the SVG
//! namespace): axes with nice ticks and grid lines, axis labels with units,
//! lines with markers, vertical error bars (± one standard deviation), optional log axes and a
//! legend to the right of the plot area. Text is drawn in the viewer's sans-serif font; nothing
//! external is referenced.

use std::fmt::Write;

use super::axis::Scale;
use super::html::escape;

/// One point: `y ± y_error` at `x` (already in display units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotPoint {
    pub x: f64,
    pub y: f64,
    /// Half-length of the error bar (one standard deviation); `None` or 0: no bar.
    pub y_error: Option<f64>,
}

/// A named line of points.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotSeries {
    /// Legend text; an empty label with a single series draws no legend.
    pub label: String,
    pub points: Vec<PlotPoint>,
    /// Points joined by a line in order of x (a trend); `false`: markers only (a scatter).
    pub joined: bool,
}

/// A line plot.
#[derive(Debug, Clone, PartialEq)]
pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_log: bool,
    pub y_log: bool,
    pub series: Vec<PlotSeries>,
}

/// Okabe–Ito colours (distinguishable with colour-vision deficiencies), yellow left out.
const PALETTE: [&str; 7] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000",
];

const PLOT_WIDTH: f64 = 520.0;
const PLOT_HEIGHT: f64 = 300.0;
const LEFT: f64 = 78.0;
const TOP: f64 = 36.0;
const BOTTOM: f64 = 54.0;
const RIGHT: f64 = 18.0;
/// Approximate advance of one character at the 12 px label size.
const CHAR_WIDTH: f64 = 6.8;

impl LinePlot {
    /// Whether the values (of x or of y) are positive and spread over two decades or more (then a log axis
    /// reads better).
    pub fn spans_decades(values: impl IntoIterator<Item = f64>) -> bool {
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for v in values {
            if v <= 0.0 || !v.is_finite() {
                return false;
            }
            lo = lo.min(v);
            hi = hi.max(v);
        }
        lo.is_finite() && hi / lo >= 100.0
    }

    fn legend_width(&self) -> f64 {
        if self.series.len() < 2 && self.series.iter().all(|s| s.label.is_empty()) {
            return 0.0;
        }
        let longest = self
            .series
            .iter()
            .map(|s| s.label.chars().count())
            .max()
            .unwrap_or(0);
        36.0 + CHAR_WIDTH * longest as f64
    }

    /// The plot as an `<svg>` element.
    pub fn to_svg(&self) -> String {
        let legend = self.legend_width();
        let width = LEFT + PLOT_WIDTH + RIGHT + legend;
        // A long legend makes the figure taller rather than running off its bottom.
        let legend_height = if legend > 0.0 {
            TOP + 20.0 * self.series.len() as f64 + 10.0
        } else {
            0.0
        };
        let height = (TOP + PLOT_HEIGHT + BOTTOM).max(legend_height);
        let points = || self.series.iter().flat_map(|s| s.points.iter());
        let x_scale = Scale::covering(points().map(|p| p.x), self.x_log);
        let y_scale = Scale::covering(
            points().flat_map(|p| {
                let e = p.y_error.unwrap_or(0.0);
                [p.y - e, p.y, p.y + e]
            }),
            self.y_log,
        );
        let px = |x: f64| LEFT + x_scale.fraction(x) * PLOT_WIDTH;
        let py = |y: f64| TOP + (1.0 - y_scale.fraction(y)) * PLOT_HEIGHT;
        let mut s = String::new();
        let _ = write!(
            s,
            r#"<svg width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="12">"#
        );
        let _ = write!(
            s,
            r#"<rect width="{width:.0}" height="{height:.0}" fill="white"/><text x="{LEFT}" y="20" font-size="14" font-weight="bold">{}</text>"#,
            escape(&self.title)
        );
        self.draw_axes(&mut s, &x_scale, &y_scale);
        for (i, series) in self.series.iter().enumerate() {
            self.draw_series(&mut s, series, PALETTE[i % PALETTE.len()], &px, &py);
        }
        self.draw_legend(&mut s, LEFT + PLOT_WIDTH + RIGHT);
        s.push_str("</svg>");
        s
    }

    /// One series: its points (those a log axis can show), joined by a line if asked, with
    /// error bars.
    fn draw_series(
        &self,
        s: &mut String,
        series: &PlotSeries,
        colour: &str,
        px: &impl Fn(f64) -> f64,
        py: &impl Fn(f64) -> f64,
    ) {
        let mut visible: Vec<&PlotPoint> = series
            .points
            .iter()
            .filter(|p| {
                p.x.is_finite()
                    && p.y.is_finite()
                    && (!self.x_log || p.x > 0.0)
                    && (!self.y_log || p.y > 0.0)
            })
            .collect();
        visible.sort_by(|a, b| a.x.total_cmp(&b.x));
        if series.joined && visible.len() > 1 {
            let path: Vec<String> = visible
                .iter()
                .map(|p| format!("{:.1},{:.1}", px(p.x), py(p.y)))
                .collect();
            let _ = write!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="1.8"/>"#,
                path.join(" ")
            );
        }
        for p in visible {
            let (x, y) = (px(p.x), py(p.y));
            if let Some(e) = p.y_error.filter(|e| *e > 0.0 && e.is_finite()) {
                let top = py(p.y + e);
                let bottom = if self.y_log && p.y - e <= 0.0 {
                    TOP + PLOT_HEIGHT
                } else {
                    py(p.y - e)
                };
                let _ = write!(
                    s,
                    r#"<path d="M{x:.1},{top:.1}V{bottom:.1}M{:.1},{top:.1}h8M{:.1},{bottom:.1}h8" stroke="{colour}" stroke-width="1.3" fill="none"/>"#,
                    x - 4.0,
                    x - 4.0
                );
            }
            let _ = write!(
                s,
                r#"<circle cx="{x:.1}" cy="{y:.1}" r="3.5" fill="{colour}"/>"#
            );
        }
    }

    fn draw_axes(&self, s: &mut String, x_scale: &Scale, y_scale: &Scale) {
        let bottom = TOP + PLOT_HEIGHT;
        for (v, label) in x_scale.ticks() {
            let x = LEFT + x_scale.fraction(v) * PLOT_WIDTH;
            let _ = write!(
                s,
                r##"<line x1="{x:.1}" y1="{TOP}" x2="{x:.1}" y2="{bottom}" stroke="#e3e3e3"/><line x1="{x:.1}" y1="{bottom}" x2="{x:.1}" y2="{:.1}" stroke="#333"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
                bottom + 5.0,
                bottom + 18.0,
                escape(&label)
            );
        }
        for (v, label) in y_scale.ticks() {
            let y = TOP + (1.0 - y_scale.fraction(v)) * PLOT_HEIGHT;
            let _ = write!(
                s,
                r##"<line x1="{LEFT}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#e3e3e3"/><line x1="{:.1}" y1="{y:.1}" x2="{LEFT}" y2="{y:.1}" stroke="#333"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
                LEFT + PLOT_WIDTH,
                LEFT - 5.0,
                LEFT - 8.0,
                y + 4.0,
                escape(&label)
            );
        }
        let _ = write!(
            s,
            r##"<rect x="{LEFT}" y="{TOP}" width="{PLOT_WIDTH}" height="{PLOT_HEIGHT}" fill="none" stroke="#333"/><text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text><text transform="translate(16,{:.1}) rotate(-90)" text-anchor="middle">{}</text>"##,
            LEFT + PLOT_WIDTH / 2.0,
            bottom + 42.0,
            escape(&self.x_label),
            TOP + PLOT_HEIGHT / 2.0,
            escape(&self.y_label)
        );
    }

    fn draw_legend(&self, s: &mut String, x0: f64) {
        if self.legend_width() == 0.0 {
            return;
        }
        for (i, series) in self.series.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            let y = TOP + 10.0 + 20.0 * i as f64;
            let _ = write!(
                s,
                r#"<line x1="{x0:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="{colour}" stroke-width="1.8"/><circle cx="{:.1}" cy="{y:.1}" r="3.5" fill="{colour}"/><text x="{:.1}" y="{:.1}">{}</text>"#,
                x0 + 24.0,
                x0 + 12.0,
                x0 + 30.0,
                y + 4.0,
                escape(&series.label)
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plots_have_labels_legend_and_error_bars() {
        let point = |x, y, e| PlotPoint {
            x,
            y,
            y_error: Some(e),
        };
        let plot = LinePlot {
            title: String::from("A & B"),
            x_label: String::from("Sq (µm)"),
            y_label: String::from("θ"),
            x_log: false,
            y_log: false,
            series: vec![
                PlotSeries {
                    label: String::from("one"),
                    points: vec![point(1.0, 2.0, 0.5), point(2.0, 3.0, 0.0)],
                    joined: true,
                },
                PlotSeries {
                    label: String::from("two"),
                    points: vec![point(1.0, 1.0, 0.1)],
                    joined: true,
                },
            ],
        };
        let svg = plot.to_svg();
        assert!(svg.contains("A &amp; B") && svg.contains("Sq (µm)"));
        assert_eq!(svg.matches("<polyline").count(), 1);
        // Two non-zero error bars, three markers plus two legend markers.
        assert_eq!(svg.matches("<path d=").count(), 2);
        assert_eq!(svg.matches("<circle").count(), 5);
    }
}
