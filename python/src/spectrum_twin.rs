//! The spectrum twin on arrays (`synthetic_twin(..., spectrum="measured")`): the numerics of
//! `surface::twins::spectrum_twin`, the same as a study's `twin: {spectrum: measured}` on maps
//! the caller has preprocessed.

use std::f64::consts::PI;

use asperity::surface::spectral::{
    find_power_law_band, fit_power_law, radial_psd, BandCriteria, Window,
};
use asperity::surface::twins::{
    spectrum_twin as make_twin, Extrapolation, MeasuredSpectrum, SpectrumTwinSpec,
};
use asperity::surface::HeightMap;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::guard::{compute, value_error};
use crate::row::key;
use crate::surface::height_map;
use asperity::units::Dimension::Length;
use asperity::vocabulary::twin_metrics::{
    TWIN_EXTRAPOLATED_POWER_SHARE, TWIN_EXTRAPOLATION, TWIN_GRID_POWER_SHARE,
    TWIN_MEASURED_SPECTRUM_SQ, TWIN_MEASURED_SQ, TWIN_MODES_CUT, TWIN_MODES_EXTRAPOLATED,
    TWIN_MODES_LONGER_THAN_MEASURED, TWIN_MODES_MEASURED, TWIN_SPECTRUM, TWIN_SPECTRUM_SCALE,
    TWIN_SPECTRUM_SQ, TWIN_SQ,
};

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(spectrum_twin, m)?)?;
    Ok(())
}

/// A twin's heights, dx, dy (m) and its provenance.
type Twin<'py> = (Bound<'py, PyArray2<f64>>, f64, f64, Bound<'py, PyDict>);

/// A twin whose 2-D power spectrum is that of the complete maps `measured` (`(heights, dx, dy)`,
/// m), averaged, with random phases from `seed`, at Sq `sq` (m; `None`: the maps' quadratic
/// mean Sq) on `grid` points over `size` (m; `None`: the first map's). `extrapolation`: `zero`
/// or `power_law` (each map's power law over the widest band where its radial PSD is one,
/// searched between 2 pixels and half its shorter side). Returns `(heights, dx, dy, provenance)`.
#[pyfunction]
#[pyo3(signature = (measured, sq, grid, size, seed, short_wavelength_cutoff=None, extrapolation="zero"))]
#[allow(clippy::too_many_arguments)]
fn spectrum_twin<'py>(
    py: Python<'py>,
    measured: Vec<(PyReadonlyArray2<'py, f64>, f64, f64)>,
    sq: Option<f64>,
    grid: Option<(usize, usize)>,
    size: Option<(f64, f64)>,
    seed: u64,
    short_wavelength_cutoff: Option<f64>,
    extrapolation: &str,
) -> PyResult<Twin<'py>> {
    let extrapolation = match extrapolation {
        "zero" => Extrapolation::Zero,
        "power_law" => Extrapolation::PowerLaw,
        other => {
            return Err(value_error(
                "extrapolation",
                format!("expected 'zero' or 'power_law', got {other:?}"),
            ))
        }
    };
    let maps = measured
        .iter()
        .enumerate()
        .map(|(i, (h, dx, dy))| height_map(&format!("measured[{i}]"), h, *dx, *dy))
        .collect::<PyResult<Vec<_>>>()?;
    let first = maps
        .first()
        .ok_or_else(|| value_error("measured", "needs at least one map"))?;
    let ((nx, ny), (lx, ly)) = match (grid, size) {
        (Some(g), Some(s)) => (g, s),
        (None, None) => ((first.nx(), first.ny()), first.size()),
        _ => return Err(value_error("grid", "give both grid and size, or neither")),
    };
    let spec = SpectrumTwinSpec {
        nx,
        ny,
        lx,
        ly,
        sq,
        short_wavelength_cutoff,
        extrapolation,
        seed,
    };
    let twin = compute(py, || {
        let spectra = maps
            .iter()
            .enumerate()
            .map(|(i, m)| spectrum_of(m, extrapolation, &format!("measured[{i}]")))
            .collect::<PyResult<Vec<_>>>()?;
        make_twin(&spectra, &spec).map_err(|e| value_error("measured", e))
    })?;
    let d = PyDict::new(py);
    d.set_item(TWIN_SPECTRUM, "measured")?;
    d.set_item(TWIN_EXTRAPOLATION, extrapolation.name())?;
    d.set_item(key(TWIN_SQ, Length), twin.sq)?;
    d.set_item(key(TWIN_MEASURED_SQ, Length), twin.measured_sq)?;
    d.set_item(
        key(TWIN_MEASURED_SPECTRUM_SQ, Length),
        twin.measured_spectrum_sq,
    )?;
    d.set_item(key(TWIN_SPECTRUM_SQ, Length), twin.spectrum_sq)?;
    d.set_item(
        TWIN_GRID_POWER_SHARE,
        (twin.spectrum_sq / twin.measured_spectrum_sq).powi(2),
    )?;
    d.set_item(TWIN_SPECTRUM_SCALE, twin.sq / twin.spectrum_sq)?;
    d.set_item(TWIN_MODES_MEASURED, twin.modes.measured)?;
    d.set_item(TWIN_MODES_EXTRAPOLATED, twin.modes.shorter)?;
    d.set_item(TWIN_MODES_LONGER_THAN_MEASURED, twin.modes.longer)?;
    d.set_item(TWIN_MODES_CUT, twin.modes.cut)?;
    d.set_item(
        TWIN_EXTRAPOLATED_POWER_SHARE,
        twin.modes.extrapolated_power_share,
    )?;
    let (dx, dy) = (twin.surface.dx(), twin.surface.dy());
    Ok((twin.surface.into_heights().into_pyarray(py), dx, dy, d))
}

/// The spectrum of one map and, for a power-law tail, its fit over the widest power-law band.
fn spectrum_of(
    map: &HeightMap,
    extrapolation: Extrapolation,
    name: &str,
) -> PyResult<MeasuredSpectrum> {
    let spectrum = MeasuredSpectrum::of_map(map).map_err(|e| value_error(name, e))?;
    if extrapolation == Extrapolation::Zero {
        return Ok(spectrum);
    }
    let tail_error = |e: &dyn std::fmt::Display| {
        value_error(
            name,
            format!("extrapolation='power_law': {e}; use extrapolation='zero'"),
        )
    };
    let psd = radial_psd(map, Window::Hann).map_err(|e| value_error(name, e))?;
    let (lx, ly) = map.size();
    let q_low = 2.0 * PI / (0.5 * lx.min(ly));
    let q_high = 2.0 * PI / (2.0 * map.dx().max(map.dy()));
    let band = find_power_law_band(&psd, q_low, q_high, BandCriteria::default())
        .map_err(|e| tail_error(&e))?;
    let fit = fit_power_law(&psd, band.q_min, band.q_max).map_err(|e| tail_error(&e))?;
    Ok(spectrum.with_tail(fit))
}
