//! `read_topography`: a topography file as NumPy arrays, with the command line's rules for the
//! lateral scale (`asperity::nodes::apply_lateral_calibration`: a spacing the file does not
//! state is never guessed, the caller gives `pixel_size` or `size`) and the height unit
//! (`asperity::nodes::apply_height_unit`: a file without one is read as metres and flagged
//! unless the caller gives `height_unit`).

use std::path::PathBuf;

use asperity::nodes::{
    apply_height_unit, apply_lateral_calibration, height_unit_rule, HeightUnitSource,
    LateralCalibration,
};
use asperity::surface::io::{
    detect_format, read_topography_bytes, read_topography_channel, ScaleSource, Topography,
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

/// Reads `path` (the channel `channel`, default the height channel), with the command line's
/// rules for the lateral scale and the height unit (`height_unit`: the length one stored value
/// stands for, m, for a file that states none); see `asperity.read_topography` for the
/// returned dictionary. Its `flags` are the sentences that would flag the node's row.
#[pyfunction]
#[pyo3(signature = (path, pixel_size=None, size=None, override_file_spacing=false, channel=None, height_unit=None))]
fn read_topography<'py>(
    py: Python<'py>,
    path: PathBuf,
    pixel_size: Option<(f64, f64)>,
    size: Option<(f64, f64)>,
    override_file_spacing: bool,
    channel: Option<String>,
    height_unit: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let given = calibration(pixel_size, size)?;
    let topography = compute(py, || {
        read_topography_channel(&path, channel.as_deref())
            .map_err(|e| PyOSError::new_err(e.to_string()))
    })?;
    let Topography {
        data,
        spacing,
        height_unit: file_unit,
        channel,
        channels,
        metadata,
    } = topography;
    let d = PyDict::new(py);
    let (unit_source, flag) = match data {
        TopographyData::Areal(map) => {
            let (map, unit_source, flag) = compute(py, || {
                let map =
                    apply_lateral_calibration(map, spacing, given, override_file_spacing, &path)
                        .map_err(|e| value_error("pixel_size", e.message))?;
                apply_height_unit(map, file_unit, height_unit, &path)
                    .map_err(|e| value_error("height_unit", e.message))
            })?;
            d.set_item("dx", map.dx())?;
            d.set_item("dy", map.dy())?;
            d.set_item("heights", map.into_heights().into_pyarray(py))?;
            (unit_source, flag)
        }
        TopographyData::Line(line) => {
            let x = line_positions(line.x, spacing, given, override_file_spacing, &path)?;
            let (z, unit_source, flag) = line_heights(line.z, file_unit, height_unit, &path)?;
            d.set_item("x", x.into_pyarray(py))?;
            d.set_item("heights", z.into_pyarray(py))?;
            (unit_source, flag)
        }
    };
    let overridden = given.is_some() && override_file_spacing;
    d.set_item(
        "spacing_from_file",
        spacing == ScaleSource::File && !overridden,
    )?;
    d.set_item("height_unit_source", unit_source.name())?;
    d.set_item("channel", channel)?;
    d.set_item("channels", channels)?;
    d.set_item("metadata", metadata)?;
    d.set_item("flags", flag.into_iter().collect::<Vec<_>>())?;
    Ok(d)
}

/// A line scan's heights in metres under the rule of areal maps (`height_unit_rule`).
fn line_heights(
    z: Vec<f64>,
    file_unit: ScaleSource,
    given: Option<f64>,
    path: &std::path::Path,
) -> PyResult<(Vec<f64>, HeightUnitSource, Option<String>)> {
    let (factor, source, flag) = height_unit_rule(file_unit, given, path)
        .map_err(|e| value_error("height_unit", e.message))?;
    let z = match factor {
        Some(unit) => z.into_iter().map(|v| v * unit).collect(),
        None => z,
    };
    Ok((z, source, flag))
}
