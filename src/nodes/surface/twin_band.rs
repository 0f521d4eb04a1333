//! The band of a twin's Hurst fit: `hurst_band` when the study gives it, otherwise, per file, the
//! widest band over which the file's PSD is a power law
//! (`surface::spectral::find_power_law_band`, its criterion in its docs), searched between the
//! limits the preprocessing and the map set:
//!
//! * long wavelengths: at most the L-filter's λc (longer ones are attenuated) and at most half
//!   the map's shorter side;
//! * short wavelengths: at least the S-filter's λs and at least 2 pixels (the sampling limit,
//!   Nyquist's wavelength).
//!
//! A found band's Hurst exponent may exceed 1 (a spectrum steeper than self-affine, e.g. an
//! optical instrument's low-pass): the twin model then clamps the predicted exponent to 1 and
//! says so (`twin_hurst_clamped`, `twin_warnings`), as for any prediction outside its range.
//!
//! A file without such a band fails the node, naming the best band seen, its fit and the field
//! that overrides the search.

use std::f64::consts::PI;

use crate::engine::node::NodeError;
use crate::engine::study::FromParamValue;
use crate::engine::value::{Field, ParamValue};
use crate::surface::spectral::{
    find_power_law_band, radial_psd, BandCriteria, BandFit, BandSearchError, Window,
};
use crate::surface::twins::format_micrometres;
use crate::surface::HeightMap;
use crate::units::{Dimension, Length, Quantity};
use crate::vocabulary::twin_metrics::{
    TWIN_HURST_BANDS, TWIN_HURST_BAND_LONG, TWIN_HURST_BAND_SHORT, TWIN_HURST_BAND_SOURCE,
};

use super::preprocess::Preprocessing;

/// `hurst_band` as written: `[λ_short, λ_long]`, or `auto` (the search, as when it is left out;
/// a parameter axis can then mix both).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HurstBand {
    Auto,
    /// m, as written (the order is checked where the field's location is known).
    Given([f64; 2]),
}

impl FromParamValue for HurstBand {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        match value {
            ParamValue::Text(t) if t == "auto" => Ok(Self::Auto),
            ParamValue::List(items) if items.len() == 2 => {
                let length = |v: &ParamValue| {
                    let si = Quantity::<Length>::from_param(v)?.si();
                    if si > 0.0 && si.is_finite() {
                        Ok(si)
                    } else {
                        Err(format!("{v} is out of range: lengths must be > 0 m"))
                    }
                };
                Ok(Self::Given([length(&items[0])?, length(&items[1])?]))
            }
            other => Err(format!(
                "expected `auto` or two lengths [short, long], e.g. [0.6 um, 2.4 um], got {other}"
            )),
        }
    }
}

impl schemars::JsonSchema for HurstBand {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "HurstBand".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let length = generator.subschema_for::<Quantity<Length>>();
        schemars::json_schema!({
            "description": "`auto` (search the widest power-law band) or [λ_short, λ_long].",
            "anyOf": [
                {"const": "auto"},
                {"type": "array", "items": length, "minItems": 2, "maxItems": 2},
                {"type": "string"}
            ]
        })
    }
}

/// Shortest wavelength of a found band, pixels (Nyquist's).
pub(crate) const MIN_BAND_PIXELS: f64 = 2.0;

/// A file's band: `[λ_short, λ_long]` (m) and, when found, the fit that qualified it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FileBand {
    pub band: [f64; 2],
    pub found: Option<BandFit>,
}

/// The band of `map` (read from `path`): the given one, or the widest power-law band.
pub(crate) fn band_of(
    map: &HeightMap,
    given: Option<[f64; 2]>,
    preprocessing: &Preprocessing,
    path: &std::path::Path,
) -> Result<FileBand, NodeError> {
    if let Some(band) = given {
        return Ok(FileBand { band, found: None });
    }
    let (lx, ly) = map.size();
    let longest = preprocessing
        .l_filter
        .map_or(f64::INFINITY, |lc| lc)
        .min(0.5 * lx.min(ly));
    let shortest = preprocessing
        .s_filter
        .unwrap_or(0.0)
        .max(MIN_BAND_PIXELS * map.dx().max(map.dy()));
    let limits = format!(
        "between {} (S-filter or {MIN_BAND_PIXELS} pixels) and {} (L-filter or half the map)",
        format_micrometres(shortest),
        format_micrometres(longest)
    );
    let psd = radial_psd(map, Window::Hann)
        .map_err(|e| NodeError::new(format!("measuring {}: PSD: {e}", path.display())))?;
    let criteria = BandCriteria::default();
    match find_power_law_band(&psd, 2.0 * PI / longest, 2.0 * PI / shortest, criteria) {
        Ok(fit) => Ok(FileBand {
            band: [2.0 * PI / fit.q_max, 2.0 * PI / fit.q_min],
            found: Some(fit),
        }),
        Err(e) => Err(NodeError::new(format!(
            "measuring {}: searching the Hurst band {limits}: {}; set `hurst_band: [short, \
             long]` where the spectrum falls as a power law, or measure a larger area",
            path.display(),
            describe(&e)
        ))),
    }
}

/// The search's failure in wavelengths.
fn describe(e: &BandSearchError) -> String {
    match e {
        BandSearchError::TooNarrow { .. } => format!(
            "the limits leave less than {} decade of the spectrum",
            BandCriteria::default().min_decades
        ),
        BandSearchError::NoPowerLaw {
            best,
            min_decades,
            min_r_squared,
        } => format!(
            "no band of {min_decades} decade or more is a power law (R² ≥ {min_r_squared}, every \
             log bin within max(0.1 decade, 3 standard errors) of the line, H > 0); the best \
             one, {} to {}, has H = {:.2}, R² = {:.3} and a bin {:.2} decade off ({:.1} times \
             its tolerance)",
            format_micrometres(2.0 * PI / best.q_max),
            format_micrometres(2.0 * PI / best.q_min),
            best.hurst,
            best.r_squared,
            best.max_residual_decades,
            best.max_residual_ratio
        ),
    }
}

/// The twin's band columns: `twin_hurst_band_source` (`study` or `found`), the band of every
/// file in the list `twin_hurst_bands` (with the fit when found), and `twin_hurst_band_short`/`_long`
/// when every file has the same band (one file, or `hurst_band`).
pub(crate) fn band_fields(bands: &[FileBand], given: bool, names: &[String]) -> Vec<Field> {
    let per_file = bands
        .iter()
        .zip(names)
        .map(|(b, name)| {
            let range = format!(
                "{} to {}",
                format_micrometres(b.band[0]),
                format_micrometres(b.band[1])
            );
            match b.found {
                Some(fit) => format!(
                    "{name}: {range} ({:.2} decade, H = {:.3}, R² = {:.3}, largest residual \
                     {:.3} decade)",
                    fit.decades(),
                    fit.hurst,
                    fit.r_squared,
                    fit.max_residual_decades
                ),
                None => format!("{name}: {range}"),
            }
        })
        .collect();
    let mut fields = vec![
        Field::text(
            TWIN_HURST_BAND_SOURCE,
            if given { "study" } else { "found" },
        ),
        Field::texts(TWIN_HURST_BANDS, per_file),
    ];
    if let Some(first) = bands.first() {
        if bands.iter().all(|b| b.band == first.band) {
            fields.push(Field::float(
                TWIN_HURST_BAND_SHORT,
                first.band[0],
                Dimension::Length,
            ));
            fields.push(Field::float(
                TWIN_HURST_BAND_LONG,
                first.band[1],
                Dimension::Length,
            ));
        }
    }
    fields
}
