//! What a resolved `surface: {twin: {...}}` is (the twin's files, preprocessing, Sq, size, seed
//! and kind), shared by the spec in [`super::twin`] and the two kinds of twin it dispatches to,
//! [`super::twin_self_affine`] and [`super::twin_spectrum`].

use crate::engine::study::FromParamValue;
use crate::engine::value::ParamValue;
use crate::surface::twins::Extrapolation;
use crate::units::{Length, Quantity};

use super::measured::MeasuredFile;
use super::preprocess::Preprocessing;
use super::synthetic::positive_length;

/// The Sq a twin is generated at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TwinSq {
    /// m
    Given(f64),
    /// The geometric mean Sq of the measured files.
    Measured,
}

impl FromParamValue for TwinSq {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        if let ParamValue::Text(t) = value {
            if t == "measured" {
                return Ok(Self::Measured);
            }
        }
        let q = Quantity::<Length>::from_param(value)
            .map_err(|e| format!("{e} (or `measured`: the files' Sq)"))?;
        positive_length(&q)?;
        Ok(Self::Given(q.si()))
    }
}

impl schemars::JsonSchema for TwinSq {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "TwinSq".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let length = generator.subschema_for::<Quantity<Length>>();
        schemars::json_schema!({
            "description": "A length, e.g. '1.19 um', or 'measured' (the files' geometric mean Sq).",
            "anyOf": [length, {"const": "measured"}]
        })
    }
}

/// A resolved twin.
#[derive(Debug, Clone)]
pub(crate) struct TwinSource {
    pub(super) measured: Vec<MeasuredFile>,
    pub(super) preprocessing: Preprocessing,
    /// `[λ_short, λ_long]` of the Hurst fit (m); `None`: found per file (`twin_band::band_of`).
    pub(super) hurst_band: Option<[f64; 2]>,
    /// `None`: the self-affine twin; else the measured spectrum with this extrapolation.
    pub(super) spectrum: Option<Extrapolation>,
    pub(super) sq: TwinSq,
    /// `None`: the first file's grid and size (spectrum twins only).
    pub(super) size: Option<TwinSize>,
    /// m
    pub(super) short_wavelength_cutoff: Option<f64>,
    pub(super) seed: u64,
}

/// Grid points and size of a twin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct TwinSize {
    pub nx: usize,
    pub ny: usize,
    /// m
    pub lx: f64,
    /// m
    pub ly: f64,
}
