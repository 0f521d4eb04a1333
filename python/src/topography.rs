//! `read_topography`: a topography file as NumPy arrays, with the command line's rule for the
//! lateral scale (`asperity::nodes::apply_lateral_calibration`): a spacing the file does not
//! state is never guessed, the caller gives `pixel_size` or `size`.

use std::path::PathBuf;

use asperity::nodes::{apply_lateral_calibration, LateralCalibration};
use asperity::surface::io::{
    detect_format, read_topography as read_file, read_topography_bytes, ScaleSource, Topography,
    TopographyData,
};
use numpy::IntoPyArray;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::guard::{compute, value_error};

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(read_topography, m)?)?;
    m.add_function(wrap_pyfunction!(topography_format, m)?)?;
    Ok(())
}

/// The format name the reader would use for `path` (magic bytes, then the extension), or
/// `None` when no reader of asperity reads it.
#[pyfunction]
fn topography_format(py: Python<'_>, path: PathBuf) -> PyResult<Option<&'static str>> {
    compute(py, || {
        let bytes = read_topography_bytes(&path).map_err(|e| PyOSError::new_err(e.to_string()))?;
        Ok(detect_format(&path, &bytes).map(|f| f.name))
    })
}

/// The lateral calibration the caller gave, if any (checked: positive and finite, in metres).
fn calibration(
    pixel_size: Option<(f64, f64)>,
    size: Option<(f64, f64)>,
) -> PyResult<Option<LateralCalibration>> {
    let check = |name: &str, (a, b): (f64, f64)| {
        if a.is_finite() && b.is_finite() && a > 0.0 && b > 0.0 {
            Ok([a, b])
        } else {
            Err(value_error(
                name,
                format!("({a:e}, {b:e}) m is out of range: both must be finite and > 0 m"),
            ))
        }
    };
    match (pixel_size, size) {
        (Some(_), Some(_)) => Err(value_error(
            "pixel_size",
            "give either pixel_size (dx, dy) or size (Lx, Ly), not both",
        )),
        (Some(p), None) => Ok(Some(LateralCalibration::PixelSize(check("pixel_size", p)?))),
        (None, Some(s)) => Ok(Some(LateralCalibration::Size(check("size", s)?))),
        (None, None) => Ok(None),
    }
}

/// The positions (m) of a line scan: the file's, or those of the calibration the caller gave
/// (`pixel_size`'s dx, or `size`'s Lx over the points), under the rule of areal maps.
fn line_positions(
    x: Vec<f64>,
    spacing: ScaleSource,
    given: Option<LateralCalibration>,
    override_file_spacing: bool,
    path: &std::path::Path,
) -> PyResult<Vec<f64>> {
    let step = match given {
        None if spacing == ScaleSource::Assumed => {
            return Err(value_error(
                "pixel_size",
                format!(
                    "{}: spacing: not in the file (this line scan's positions are not \
                     calibrated); give pixel_size (dx in m) or size (the scan length in m)",
                    path.display()
                ),
            ))
        }
        None => return Ok(x),
        Some(_) if spacing == ScaleSource::File && !override_file_spacing => {
            return Err(value_error(
                "pixel_size",
                format!(
                    "{}: the file calibrates this line scan's positions; remove pixel_size/size \
                     or set override_file_spacing=True",
                    path.display()
                ),
            ))
        }
        Some(LateralCalibration::PixelSize([dx, _])) => dx,
        Some(LateralCalibration::Size([lx, _])) => lx / x.len() as f64,
    };
    Ok((0..x.len()).map(|i| i as f64 * step).collect())
}

/// Reads `path`; see `asperity.read_topography` for the returned dictionary.
#[pyfunction]
#[pyo3(signature = (path, pixel_size=None, size=None, override_file_spacing=false))]
fn read_topography<'py>(
    py: Python<'py>,
    path: PathBuf,
    pixel_size: Option<(f64, f64)>,
    size: Option<(f64, f64)>,
    override_file_spacing: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let given = calibration(pixel_size, size)?;
    let topography = compute(py, || {
        read_file(&path).map_err(|e| PyOSError::new_err(e.to_string()))
    })?;
    let Topography {
        data,
        spacing,
        height_unit,
        channel,
        channels,
        metadata,
    } = topography;
    let d = PyDict::new(py);
    match data {
        TopographyData::Areal(map) => {
            let map = compute(py, || {
                apply_lateral_calibration(map, spacing, given, override_file_spacing, &path)
                    .map_err(|e| value_error("pixel_size", e.message))
            })?;
            d.set_item("dx", map.dx())?;
            d.set_item("dy", map.dy())?;
            d.set_item("heights", map.into_heights().into_pyarray(py))?;
        }
        TopographyData::Line(line) => {
            let x = line_positions(line.x, spacing, given, override_file_spacing, &path)?;
            d.set_item("x", x.into_pyarray(py))?;
            d.set_item("heights", line.z.into_pyarray(py))?;
        }
    }
    d.set_item("spacing_from_file", spacing == ScaleSource::File)?;
    d.set_item("height_unit_from_file", height_unit == ScaleSource::File)?;
    d.set_item("channel", channel)?;
    d.set_item("channels", channels)?;
    d.set_item("metadata", metadata)?;
    Ok(d)
}
