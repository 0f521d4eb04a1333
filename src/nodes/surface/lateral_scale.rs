//! The lateral calibration of a file surface: `pixel_size` or `size` in the node supplies the
//! spacing of a file that has none (npy, a bare text/CSV matrix, a GSF without `XReal`) and is
//! checked against the calibration of a file that has one.
//!
//! Nothing is guessed: a file without a calibration and without either field fails the node with
//! an error naming both fields; a file whose calibration differs from the given one by more than
//! [`AGREEMENT`] (relative, on either axis) fails unless `override_file_spacing: true`.

use crate::engine::node::NodeError;
use crate::engine::study::FromParamValue;
use crate::engine::value::ParamValue;
use crate::surface::io::ScaleSource;
use crate::surface::HeightMap;
use crate::units::{Dimension, Length, Quantity};

/// Root-mean-square slopes outside [MIN, MAX] flag a lateral scale that is probably wrong.
pub(crate) const PLAUSIBLE_SDQ: (f64, f64) = (1e-4, 10.0);

/// Relative difference below which a given spacing and the file's agree.
pub(crate) const AGREEMENT: f64 = 1e-6;

/// One length (square pixels, square map) or `[x, y]`, in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LateralLengths(pub [f64; 2]);

impl FromParamValue for LateralLengths {
    fn from_param(value: &ParamValue) -> Result<Self, String> {
        let one = |v: &ParamValue| {
            let q = Quantity::<Length>::from_param(v)?;
            if q.si() > 0.0 && q.si().is_finite() {
                Ok(q.si())
            } else {
                Err(format!("{v} is out of range: lengths must be > 0 m"))
            }
        };
        match value {
            ParamValue::List(items) if items.len() == 2 => {
                Ok(Self([one(&items[0])?, one(&items[1])?]))
            }
            ParamValue::List(items) => Err(format!(
                "expected one length or a list of two [x, y], got a list of {}",
                items.len()
            )),
            single => one(single).map(|v| Self([v, v])),
        }
    }
}

impl schemars::JsonSchema for LateralLengths {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "LateralLengths".into()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let length = generator.subschema_for::<Quantity<Length>>();
        schemars::json_schema!({
            "description": "One length (square) or [x, y], e.g. '0.5 um' or ['0.5 um', '0.6 um'].",
            "anyOf": [
                length,
                {"type": "array", "items": length, "minItems": 2, "maxItems": 2}
            ]
        })
    }
}

/// What the node states about the lateral scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LateralCalibration {
    /// `pixel_size`: [dx, dy] (m).
    PixelSize([f64; 2]),
    /// `size`: [Lx, Ly] (m) of the whole map as read, dx = Lx/nx.
    Size([f64; 2]),
}

impl LateralCalibration {
    /// The field as written in the study.
    fn field(self) -> &'static str {
        match self {
            Self::PixelSize(_) => "pixel_size",
            Self::Size(_) => "size",
        }
    }

    /// [dx, dy] (m) for a map of nx × ny points.
    fn spacing(self, nx: usize, ny: usize) -> [f64; 2] {
        match self {
            Self::PixelSize(d) => d,
            Self::Size([lx, ly]) => [lx / nx as f64, ly / ny as f64],
        }
    }
}

/// The map with its lateral scale settled: the file's, the node's (when the file has none, or
/// `override_file_spacing`), or an error.
pub fn apply_lateral_calibration(
    map: HeightMap,
    file_scale: ScaleSource,
    given: Option<LateralCalibration>,
    override_file: bool,
    path: &std::path::Path,
) -> Result<HeightMap, NodeError> {
    let (nx, ny) = (map.nx(), map.ny());
    let Some(given) = given else {
        return match file_scale {
            ScaleSource::File => Ok(map),
            ScaleSource::Assumed => Err(NodeError::new(format!(
                "{}: spacing: not in the file (this format stores no lateral calibration), so the \
                 size of the {nx} × {ny} map is unknown; give it in the node: `pixel_size: 0.5 um` \
                 (or `[dx, dy]`), or `size: [Lx, Ly]` for the whole map",
                path.display()
            ))),
        };
    };
    let [dx, dy] = given.spacing(nx, ny);
    if file_scale == ScaleSource::File && !override_file {
        let disagrees = |a: f64, b: f64| (a - b).abs() > AGREEMENT * b.abs();
        if disagrees(dx, map.dx()) || disagrees(dy, map.dy()) {
            return Err(NodeError::new(format!(
                "{}: `{}` gives dx = {dx:e} m, dy = {dy:e} m but the file is calibrated at \
                 dx = {:e} m, dy = {:e} m; remove `{}` to use the file's calibration, or set \
                 `override_file_spacing: true` to use yours",
                path.display(),
                given.field(),
                map.dx(),
                map.dy(),
                given.field()
            )));
        }
        return Ok(map);
    }
    HeightMap::new(map.into_heights(), dx, dy)
        .map_err(|e| NodeError::new(format!("{}: `{}`: {e}", path.display(), given.field())))
}

/// The key fields of a stated calibration (`pixel_size_x_m`, … or `size_x_m`, …).
pub(crate) fn calibration_fields(given: LateralCalibration) -> [crate::engine::value::Field; 2] {
    use crate::engine::value::Field;
    use crate::vocabulary::surface_parameters::{PIXEL_SIZE_X, PIXEL_SIZE_Y, SIZE_X, SIZE_Y};
    match given {
        LateralCalibration::PixelSize([dx, dy]) => [
            Field::float(PIXEL_SIZE_X, dx, Dimension::Length),
            Field::float(PIXEL_SIZE_Y, dy, Dimension::Length),
        ],
        LateralCalibration::Size([lx, ly]) => [
            Field::float(SIZE_X, lx, Dimension::Length),
            Field::float(SIZE_Y, ly, Dimension::Length),
        ],
    }
}

/// An empty string, or a sentence when the root-mean-square slope Sdq of a map with spacings
/// dx, dy (m) is
/// outside [`PLAUSIBLE_SDQ`]: below 1e-4 (0.006°) the map is flatter at its own sampling than any
/// engineering surface — typically a pixel size far too large (1 m read for 1 µm); above 10
/// (84°) it is steeper than an optical or stylus instrument can measure — typically a pixel
/// size far too small. Reported, not an error: a super-polished flat can be that smooth.
pub(crate) fn lateral_scale_warning(sdq: Option<f64>, dx: f64, dy: f64) -> String {
    let Some(sdq) = sdq else {
        return String::new();
    };
    let (low, high) = PLAUSIBLE_SDQ;
    let what = if sdq < low {
        "flatter than any engineering surface at its own sampling: is the pixel size too large?"
    } else if sdq > high {
        "steeper than an instrument can measure: is the pixel size too small?"
    } else {
        return String::new();
    };
    format!(
        "rms slope Sdq = {sdq:.3e} with dx = {dx:.3e} m, dy = {dy:.3e} m is {what} Check the \
         file's calibration or `pixel_size`/`size`."
    )
}
