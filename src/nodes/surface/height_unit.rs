//! The height unit of a file surface: `height_unit` in the node gives it for a file that stores
//! none (npy, a bare text/CSV matrix), as `pixel_size` gives the spacing
//! ([`super::lateral_scale`]).
//!
//! Nothing is guessed silently: a file without a height unit and without `height_unit` is read
//! as metres and its row is flagged with a sentence naming the field; a file that states its
//! unit refuses `height_unit` (its heights are already converted to metres). The row's
//! `height_unit_source` says which of the three happened ([`HeightUnitSource`]).

use crate::engine::node::NodeError;
use crate::engine::study::FromParamValue;
use crate::engine::value::ParamValue;
use crate::surface::io::ScaleSource;
use crate::surface::HeightMap;
use crate::units::{Length, Quantity};

/// The length one stored height value stands for (m): `um` (= `1 um`), `nm`, `0.1 nm`, ….
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightUnit(pub f64);

impl FromParamValue for HeightUnit {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        let si = match value {
            ParamValue::Text(t) => ParamValue::from_text(&format!("1 {}", t.trim()))
                .and_then(|v| Quantity::<Length>::from_param(&v))
                .map_err(|_| {
                    format!("expected a length unit (m, mm, um, nm) or a length, got {value}")
                })?
                .si(),
            other => Quantity::<Length>::from_param(other)?.si(),
        };
        if si > 0.0 && si.is_finite() {
            Ok(Self(si))
        } else {
            Err(format!(
                "{value} is out of range: a height unit is a length > 0 m"
            ))
        }
    }
}

impl schemars::JsonSchema for HeightUnit {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "HeightUnit".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let length = generator.subschema_for::<Quantity<Length>>();
        schemars::json_schema!({
            "description": "A length unit ('um', 'nm', 'm') or the length one stored value \
                            stands for ('0.1 nm').",
            "anyOf": [length, {"type": "string"}]
        })
    }
}

/// Where the heights' unit came from (the `height_unit_source` column).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HeightUnitSource {
    /// The file states it.
    File,
    /// The node's `height_unit`.
    Study,
    /// Neither: the values were read as metres (the row is flagged).
    Assumed,
}

impl HeightUnitSource {
    /// The column's text.
    pub fn name(self) -> &'static str {
        match self {
            Self::File => "file",
            Self::Study => "study",
            Self::Assumed => "assumed",
        }
    }
}

/// The map with its heights in metres: the file's unit, the node's `height_unit` (for a file
/// without one), or metres assumed — with the flag that says so ([`height_unit_rule`]).
pub fn apply_height_unit(
    map: HeightMap,
    file_unit: ScaleSource,
    given: Option<f64>,
    path: &std::path::Path,
) -> Result<(HeightMap, HeightUnitSource, Option<String>), NodeError> {
    let (factor, source, flag) = height_unit_rule(file_unit, given, path)?;
    let Some(unit) = factor else {
        return Ok((map, source, flag));
    };
    let (dx, dy) = (map.dx(), map.dy());
    let scaled = HeightMap::new(map.into_heights() * unit, dx, dy)
        .map_err(|e| NodeError::new(format!("{}: `height_unit`: {e}", path.display())))?;
    Ok((scaled, source, flag))
}

/// The rule of the height unit for heights stored with `file_unit`: the factor (m per stored
/// value) to multiply them by (`None`: they are metres already), where the unit came from, and
/// the flag of a unit assumed. A file that states its unit refuses `given`.
pub fn height_unit_rule(
    file_unit: ScaleSource,
    given: Option<f64>,
    path: &std::path::Path,
) -> Result<(Option<f64>, HeightUnitSource, Option<String>), NodeError> {
    match (file_unit, given) {
        (ScaleSource::File, None) => Ok((None, HeightUnitSource::File, None)),
        (ScaleSource::File, Some(_)) => Err(NodeError::new(format!(
            "{}: `height_unit`: the file states its own height unit (its heights are already \
             converted to metres); remove `height_unit`",
            path.display()
        ))),
        (ScaleSource::Assumed, Some(unit)) => Ok((Some(unit), HeightUnitSource::Study, None)),
        (ScaleSource::Assumed, None) => Ok((
            None,
            HeightUnitSource::Assumed,
            Some(format!(
                "{}: the file stores no height unit, so its values were read as metres; give \
                 the unit in the node (`height_unit: um`, `nm`, or `m` to confirm metres)",
                path.display()
            )),
        )),
    }
}
