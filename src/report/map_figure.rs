//! Height and contact-pressure maps as figures: the map is rasterised into a PNG (viridis colour
//! map, row 0 at the bottom so y points up, block-averaged down to at most
//! [`MAX_PIXELS`] per side) embedded as a data URI in an SVG with axes in µm or mm and a colour
//! bar in the quantity's display unit.

use std::fmt::Write;

use base64::Engine;
use ndarray::{Array2, ArrayView2};

use super::axis::{format_tick, linear_ticks};
use super::colormap::colour;
use super::error::ReportError;
use super::html::escape;
use super::quantity::DisplayUnit;

/// The largest raster side; larger maps are block-averaged.
pub const MAX_PIXELS: usize = 400;
/// The largest side of the drawn map in the figure (CSS pixels).
const BOX: f64 = 320.0;
const NAN_GREY: [u8; 3] = [208, 208, 208];
const EMPTY_WHITE: [u8; 3] = [255, 255, 255];

/// A map to draw.
#[derive(Debug, Clone)]
pub struct MapFigure<'a> {
    pub title: String,
    /// Values `[[iy, ix]]` in SI units; `NaN` = missing.
    pub values: ArrayView2<'a, f64>,
    /// Grid spacings in metres.
    pub dx: f64,
    pub dy: f64,
    /// Quantity name for the colour bar (`height`, `contact pressure`).
    pub quantity: String,
    /// SI unit of the values (`m`, `Pa`).
    pub si_unit: String,
    /// Values ≤ 0 are drawn white and labelled "no contact" (pressure maps).
    pub zero_is_empty: bool,
}

/// A PNG image encoded as a `data:image/png;base64,` URI.
pub fn png_data_uri(width: usize, height: usize, rgb: &[u8]) -> Result<String, ReportError> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width as u32, height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder
            .write_header()
            .map_err(|e| ReportError::Image(e.to_string()))?;
        writer
            .write_image_data(rgb)
            .map_err(|e| ReportError::Image(e.to_string()))?;
        writer
            .finish()
            .map_err(|e| ReportError::Image(e.to_string()))?;
    }
    Ok(format!(
        "data:image/png;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    ))
}

/// Block means over `factor × factor` cells, ignoring `NaN` (a block of only `NaN` stays `NaN`).
fn block_average(values: ArrayView2<f64>, factor: usize) -> Array2<f64> {
    let (ny, nx) = values.dim();
    let (my, mx) = (ny.div_ceil(factor), nx.div_ceil(factor));
    Array2::from_shape_fn((my, mx), |(by, bx)| {
        let (mut sum, mut count) = (0.0, 0usize);
        for iy in by * factor..((by + 1) * factor).min(ny) {
            for ix in bx * factor..((bx + 1) * factor).min(nx) {
                let v = values[[iy, ix]];
                if v.is_finite() {
                    sum += v;
                    count += 1;
                }
            }
        }
        if count == 0 {
            f64::NAN
        } else {
            sum / count as f64
        }
    })
}

/// Repeats every pixel of an RGB raster `width` pixels wide `zoom × zoom` times.
fn enlarge(rgb: &[u8], width: usize, zoom: usize) -> Vec<u8> {
    if zoom == 1 {
        return rgb.to_vec();
    }
    let mut out = Vec::with_capacity(rgb.len() * zoom * zoom);
    for row in rgb.chunks_exact(width * 3) {
        let wide: Vec<u8> = row
            .chunks_exact(3)
            .flat_map(|px| std::iter::repeat_n(px, zoom).flatten().copied())
            .collect();
        for _ in 0..zoom {
            out.extend_from_slice(&wide);
        }
    }
    out
}

impl MapFigure<'_> {
    /// The figure as an `<svg>` element.
    pub fn to_svg(&self) -> Result<String, ReportError> {
        let (ny, nx) = self.values.dim();
        let factor = nx.max(ny).div_ceil(MAX_PIXELS).max(1);
        let raster = block_average(self.values, factor);
        let (my, mx) = raster.dim();
        let (lo, hi) = self.colour_range(&raster);
        let (rgb, missing) = self.pixels(&raster, (lo, hi));
        // Small maps are enlarged by whole pixels here so every viewer shows crisp cells.
        let zoom = ((BOX as usize) / mx.max(my)).max(1);
        let image = png_data_uri(mx * zoom, my * zoom, &enlarge(&rgb, mx, zoom))?;
        let bar: Vec<u8> = (0..128)
            .rev()
            .flat_map(|i| colour(f64::from(i) / 127.0))
            .collect();
        let bar_image = png_data_uri(1, 128, &bar)?;

        let (lx, ly) = (nx as f64 * self.dx, ny as f64 * self.dy);
        let scale = BOX / lx.max(ly);
        let (w, h) = ((lx * scale).max(40.0), (ly * scale).max(40.0));
        let length = DisplayUnit::for_values("m", lx.max(ly));
        let value_unit = DisplayUnit::for_slice(&self.si_unit, [lo, hi]);
        let (left, top) = (62.0, 34.0);
        let bar_x = left + w + 24.0;
        let width = bar_x + 110.0;
        let height = top + h + 56.0;
        let mut s = String::new();
        let _ = write!(
            s,
            r#"<svg width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="12"><rect width="{width:.0}" height="{height:.0}" fill="white"/><text x="{left}" y="20" font-size="13" font-weight="bold">{}</text>"#,
            escape(&self.title)
        );
        let _ = write!(
            s,
            r##"<image x="{left}" y="{top}" width="{w:.1}" height="{h:.1}" preserveAspectRatio="none" style="image-rendering:pixelated" href="{image}"/><rect x="{left}" y="{top}" width="{w:.1}" height="{h:.1}" fill="none" stroke="#333"/>"##
        );
        let bottom = top + h;
        draw_axes(&mut s, (left, top, w, h), (lx, ly), &length);
        self.draw_colour_bar(&mut s, (bar_x, top, h), (lo, hi), &value_unit, &bar_image);
        let mut notes = Vec::new();
        if self.zero_is_empty {
            notes.push(("#ffffff", "no contact"));
        }
        if missing {
            notes.push(("#d0d0d0", "missing"));
        }
        for (i, (fill, text)) in notes.iter().enumerate() {
            let y = bottom + 14.0 + 18.0 * i as f64;
            let _ = write!(
                s,
                r##"<rect x="{bar_x:.1}" y="{y:.1}" width="14" height="12" fill="{fill}" stroke="#333"/><text x="{:.1}" y="{:.1}">{text}</text>"##,
                bar_x + 20.0,
                y + 10.0
            );
        }
        s.push_str("</svg>");
        Ok(s)
    }

    /// The colour scale's range: the shown values' minimum (0 when zero means no contact) and
    /// maximum, widened when they coincide.
    fn colour_range(&self, raster: &Array2<f64>) -> (f64, f64) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &v in raster.iter().filter(|v| self.shown(**v)) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if self.zero_is_empty {
            lo = 0.0;
        }
        if !hi.is_finite() {
            (lo, hi) = (0.0, 1.0);
        } else if hi <= lo {
            hi = lo + lo.abs().max(1e-30);
        }
        (lo, hi)
    }

    /// Whether `v` is drawn in colour (not missing, not an empty zero).
    fn shown(&self, v: f64) -> bool {
        v.is_finite() && (!self.zero_is_empty || v > 0.0)
    }

    /// RGB rows of the raster, top row first, and whether any point is missing.
    fn pixels(&self, raster: &Array2<f64>, (lo, hi): (f64, f64)) -> (Vec<u8>, bool) {
        let (my, mx) = raster.dim();
        let mut rgb = Vec::with_capacity(mx * my * 3);
        let mut missing = false;
        for iy in (0..my).rev() {
            for ix in 0..mx {
                let v = raster[[iy, ix]];
                let c = if v.is_nan() {
                    missing = true;
                    NAN_GREY
                } else if !self.shown(v) {
                    EMPTY_WHITE
                } else {
                    colour((v - lo) / (hi - lo))
                };
                rgb.extend_from_slice(&c);
            }
        }
        (rgb, missing)
    }

    fn draw_colour_bar(
        &self,
        s: &mut String,
        (x, top, h): (f64, f64, f64),
        (lo, hi): (f64, f64),
        unit: &DisplayUnit,
        bar_image: &str,
    ) {
        let _ = write!(
            s,
            r##"<text x="{x:.1}" y="{:.1}">{}</text><image x="{x:.1}" y="{top}" width="16" height="{h:.1}" preserveAspectRatio="none" href="{bar_image}"/><rect x="{x:.1}" y="{top}" width="16" height="{h:.1}" fill="none" stroke="#333"/>"##,
            top - 8.0,
            escape(&unit.axis_label(&self.quantity))
        );
        let (a, b) = (lo * unit.factor, hi * unit.factor);
        let ticks = linear_ticks(a, b, 5);
        let step = ticks
            .get(1)
            .zip(ticks.first())
            .map_or(b - a, |(t1, t0)| t1.0 - t0.0);
        for (v, _) in ticks {
            let y = top + (1.0 - (v - a) / (b - a)) * h;
            let _ = write!(
                s,
                r##"<line x1="{:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#333"/><text x="{:.1}" y="{:.1}">{}</text>"##,
                x + 16.0,
                x + 20.0,
                x + 23.0,
                y + 4.0,
                escape(&format_tick(v, step))
            );
        }
    }
}

/// Ticks and labels of the map's x and y axes (lengths `lx`, `ly` in m) around the box
/// `(left, top, w, h)`.
fn draw_axes(
    s: &mut String,
    (left, top, w, h): (f64, f64, f64, f64),
    (lx, ly): (f64, f64),
    length: &DisplayUnit,
) {
    let bottom = top + h;
    for (v, label) in linear_ticks(0.0, lx * length.factor, 4) {
        let x = left + v / (lx * length.factor) * w;
        let _ = write!(
            s,
            r##"<line x1="{x:.1}" y1="{bottom:.1}" x2="{x:.1}" y2="{:.1}" stroke="#333"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            bottom + 5.0,
            bottom + 18.0,
            escape(&label)
        );
    }
    for (v, label) in linear_ticks(0.0, ly * length.factor, 4) {
        let y = bottom - v / (ly * length.factor) * h;
        let _ = write!(
            s,
            r##"<line x1="{:.1}" y1="{y:.1}" x2="{left}" y2="{y:.1}" stroke="#333"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
            left - 5.0,
            left - 8.0,
            y + 4.0,
            escape(&label)
        );
    }
    let _ = write!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text><text transform="translate(16,{:.1}) rotate(-90)" text-anchor="middle">{}</text>"#,
        left + w / 2.0,
        bottom + 40.0,
        escape(&length.axis_label("x")),
        top + h / 2.0,
        escape(&length.axis_label("y"))
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_average_ignores_missing_points() {
        let a = ndarray::array![[1.0, f64::NAN, 5.0], [3.0, f64::NAN, 7.0], [9.0, 9.0, 9.0]];
        let b = block_average(a.view(), 2);
        assert_eq!(b.dim(), (2, 2));
        assert_eq!(b[[0, 0]], 2.0);
        assert_eq!(b[[0, 1]], 6.0);
        assert_eq!(b[[1, 0]], 9.0);
    }
}
