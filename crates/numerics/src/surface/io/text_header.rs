//! Header lines of text topography files: sizes, spacings and units (see [`super::text`]).

use std::collections::BTreeMap;

use super::text_units::length_unit_to_metres;
use super::ParseError;

/// What the header lines of a text matrix say about the grid.
#[derive(Debug, Default)]
pub(crate) struct TextHeader {
    /// `h=` rows and `w=` columns.
    pub(crate) rows_columns: Option<(usize, usize)>,
    /// `pixel size=` in metres.
    pixel_size: Option<f64>,
    /// Gwyddion `Width:` and `Height:` in metres.
    width: Option<f64>,
    height: Option<f64>,
    /// `height conversion factor (-> m)=`.
    height_conversion: Option<f64>,
    /// Gwyddion `Value units:`.
    value_unit: Option<String>,
    /// `data unit=`.
    data_unit: Option<String>,
    /// Gwyddion `Channel:`.
    pub(crate) channel: Option<String>,
    /// Every `key = value` / `key: value` pair, keys lowercased.
    pub(crate) metadata: BTreeMap<String, String>,
}

impl TextHeader {
    /// Reads the known keys from the header lines (unknown lines are kept as metadata).
    pub(crate) fn parse(lines: &[&str]) -> Result<Self, ParseError> {
        let mut h = TextHeader::default();
        for raw in lines {
            let line = raw.trim_start_matches(['#', '%', ';']).trim();
            if let Some((rows, cols)) = rows_columns(line) {
                h.rows_columns = Some((rows, cols));
                continue;
            }
            let Some((key, value)) = split_key_value(line) else {
                continue;
            };
            let key = key.trim().to_lowercase();
            let value = value.trim();
            h.metadata.insert(key.clone(), value.to_string());
            match key.as_str() {
                "pixel size" => h.pixel_size = Some(length_with_unit(value, &key)?),
                "width" => h.width = Some(length_with_unit(value, &key)?),
                "height" => h.height = Some(length_with_unit(value, &key)?),
                "value units" => h.value_unit = Some(value.to_string()),
                "data unit" => h.data_unit = Some(value.to_string()),
                "channel" => h.channel = Some(value.to_string()),
                k if k.starts_with("height conversion factor") => {
                    h.height_conversion = Some(number(value, &key)?);
                }
                _ => {}
            }
        }
        Ok(h)
    }

    /// `true` when the header clearly describes a matrix grid.
    pub(crate) fn describes_matrix(&self) -> bool {
        self.rows_columns.is_some() || self.pixel_size.is_some() || self.width.is_some()
    }

    /// `(dx, dy)` in metres for a matrix of `columns × rows`, if the header gives it.
    pub(crate) fn spacing(&self, columns: usize, rows: usize) -> Option<(f64, f64)> {
        if let Some(p) = self.pixel_size {
            return Some((p, p));
        }
        let dx = self.width? / columns as f64;
        let dy = self.height.map_or(dx, |h| h / rows as f64);
        Some((dx, dy))
    }

    /// Metres per stored height value, if the header gives it.
    pub(crate) fn height_factor(&self) -> Result<Option<f64>, ParseError> {
        if let Some(f) = self.height_conversion {
            return Ok(Some(f));
        }
        for (key, unit) in [
            ("Value units", &self.value_unit),
            ("data unit", &self.data_unit),
        ] {
            if let Some(unit) = unit {
                return length_unit_to_metres(unit).map(Some).ok_or_else(|| {
                    ParseError::unsupported(format!(
                        "text: {key} {unit:?} is not a length and no height conversion factor is given"
                    ))
                });
            }
        }
        Ok(None)
    }
}

/// `h=650 w=650` → (rows, columns).
fn rows_columns(line: &str) -> Option<(usize, usize)> {
    let mut h = None;
    let mut w = None;
    for token in line.split_whitespace() {
        let (k, v) = token.split_once('=')?;
        match k {
            "h" => h = Some(v.parse().ok()?),
            "w" => w = Some(v.parse().ok()?),
            _ => return None,
        }
    }
    Some((h?, w?))
}

fn split_key_value(line: &str) -> Option<(&str, &str)> {
    let eq = line.find('=');
    let colon = line.find(':');
    let at = match (eq, colon) {
        (Some(a), Some(b)) => a.min(b),
        (a, b) => a.or(b)?,
    };
    Some((&line[..at], &line[at + 1..]))
}

fn number(value: &str, key: &str) -> Result<f64, ParseError> {
    value
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| ParseError::malformed(format!("text: {key} = {value:?} is not a number")))
}

/// `"3.69862e-007 m"` or `"10.00 µm"` in metres.
fn length_with_unit(value: &str, key: &str) -> Result<f64, ParseError> {
    let mut parts = value.split_whitespace();
    let v = number(parts.next().unwrap_or_default(), key)?;
    let unit = parts.next().unwrap_or("m");
    let factor = length_unit_to_metres(unit).ok_or_else(|| {
        ParseError::unsupported(format!("text: {key} unit {unit:?} is not a length unit"))
    })?;
    let m = v * factor;
    if m > 0.0 {
        Ok(m)
    } else {
        Err(ParseError::malformed(format!(
            "text: {key} = {value:?} is not > 0"
        )))
    }
}

/// Length units of the first two columns named in a CSV column-header line such as
/// `Lateral um,Raw Micrometer` or `x (mm)\tz [nm]`: `(x metres, z metres)` per unit.
pub(crate) fn column_units(line: &str) -> Option<(f64, f64)> {
    let fields: Vec<&str> = line
        .split([',', ';', '\t'])
        .map(str::trim)
        .filter(|f| !f.is_empty())
        .collect();
    let unit_of = |field: &str| {
        field
            .split(|c: char| c.is_whitespace() || "()[]".contains(c))
            .find_map(length_unit_to_metres)
    };
    match fields.as_slice() {
        [x, z, ..] => Some((unit_of(x)?, unit_of(z)?)),
        // `µm µm`: two bare unit names separated by spaces.
        [both] => match both.split_whitespace().collect::<Vec<_>>().as_slice() {
            [x, z] => Some((length_unit_to_metres(x)?, length_unit_to_metres(z)?)),
            _ => None,
        },
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_both_header_styles() {
        let h = TextHeader::parse(&[
            "h=305 w=75",
            "pixel size=3.69862e-007 m",
            "data unit=rad",
            "height conversion factor (-> m)=2.91818e-008",
        ])
        .unwrap();
        assert_eq!(h.rows_columns, Some((305, 75)));
        assert_eq!(h.spacing(75, 305), Some((3.69862e-7, 3.69862e-7)));
        assert_eq!(h.height_factor().unwrap(), Some(2.91818e-8));

        let g = TextHeader::parse(&["# Width: 10.00 µm", "# Height: 5 µm", "# Value units: nm"])
            .unwrap();
        let (dx, dy) = g.spacing(4, 2).unwrap();
        // 10 µm / 4 and 5 µm / 2; one rounding of 10·1e-6 allows a few ulp.
        assert!((dx - 2.5e-6).abs() < 1e-20 && (dy - 2.5e-6).abs() < 1e-20);
        assert_eq!(g.height_factor().unwrap(), Some(1e-9));
    }

    #[test]
    fn phase_without_factor_is_refused() {
        let h = TextHeader::parse(&["data unit=rad"]).unwrap();
        assert!(h.height_factor().is_err());
        assert_eq!(
            column_units("Lateral um,Raw Micrometer,"),
            Some((1e-6, 1e-6))
        );
        assert_eq!(column_units("x,z"), None);
    }
}
