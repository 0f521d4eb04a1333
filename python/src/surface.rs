//! Surfaces on arrays: statistics and long tables (the `surfaces` row and tables of the command
//! line, with the node's checks), form removal, ISO 16610-61 Gaussian filters, filling of
//! missing points, synthetic surfaces and twins.

use asperity::engine::artifact::{ColumnData, Table};
use asperity::nodes::validity::{check_artifact, SURFACE};
use asperity::nodes::{scale_checks as node_scale_checks, surface_artifact};
use asperity::surface::synthetic::{generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec};
use asperity::surface::twins::{
    fit_twin_model, measure_texture, synthetic_twin as make_twin, TextureOptions, TwinGrid,
};
use asperity::surface::{
    fill_missing as fill, gaussian_band_pass, gaussian_high_pass, gaussian_low_pass,
    remove_polynomial_form, Boundary, FillOptions, HeightMap,
};
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::guard::{compute, owned, value_error};
use crate::row::{key, set_fields};
use asperity::units::Dimension::Length;
use asperity::vocabulary::twin_metrics::{
    TWIN_CORRELATION_LENGTH_X, TWIN_CORRELATION_LENGTH_Y, TWIN_HURST, TWIN_HURST_PREDICTED,
    TWIN_SQ, TWIN_WARNINGS,
};

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(surface_report, m)?)?;
    m.add_function(wrap_pyfunction!(scale_checks, m)?)?;
    m.add(
        "MATERIAL_RATIO_TABLE",
        asperity::vocabulary::tables::MATERIAL_RATIO,
    )?;
    m.add_function(wrap_pyfunction!(remove_form, m)?)?;
    m.add_function(wrap_pyfunction!(gaussian_filter, m)?)?;
    m.add_function(wrap_pyfunction!(fill_missing, m)?)?;
    m.add_function(wrap_pyfunction!(synthetic_surface, m)?)?;
    m.add_function(wrap_pyfunction!(synthetic_twin, m)?)?;
    Ok(())
}

/// A height map of `heights` (m, NaN missing) at spacings `dx`, `dy` (m); errors name `name`.
pub fn height_map(
    name: &str,
    heights: &PyReadonlyArray2<'_, f64>,
    dx: f64,
    dy: f64,
) -> PyResult<HeightMap> {
    HeightMap::new(owned(heights), dx, dy).map_err(|e| value_error(name, e))
}

/// The heights of a computed map as a NumPy array.
fn to_numpy<'py>(py: Python<'py>, map: HeightMap) -> Bound<'py, PyArray2<f64>> {
    map.into_heights().into_pyarray(py)
}

/// What a study's surface node computes from this map (`nodes::surface_artifact`), checked by
/// its validity rules: `(statistics, tables, flags)`, the `surfaces` row keyed by column name
/// (with its SI unit), the long tables (`psd`, `acf`, `summits`, the material ratio curve) as
/// `{table: {column: array}}`, and the sentences that would flag the row or warn of its lateral
/// scale. A value the node would fail raises `ValueError`.
#[pyfunction]
#[pyo3(signature = (heights, dx, dy, periodic=false))]
fn surface_report<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    periodic: bool,
) -> PyResult<Report<'py>> {
    let map = height_map("heights", &heights, dx, dy)?;
    let boundary = if periodic {
        Boundary::Periodic
    } else {
        Boundary::Open
    };
    let (artifact, lateral_scale_warning) = compute(py, || {
        let (mut artifact, warning) = surface_artifact(&map, boundary, None)
            .map_err(|e| value_error("heights", e.message))?;
        check_artifact(SURFACE, &mut artifact).map_err(|e| value_error("heights", e.message))?;
        Ok((artifact, warning))
    })?;
    let statistics = PyDict::new(py);
    set_fields(&statistics, artifact.metrics)?;
    let tables = PyDict::new(py);
    for (name, table) in artifact.tables {
        tables.set_item(name, table_dict(py, table)?)?;
    }
    let mut flags = artifact.flags;
    flags.extend((!lateral_scale_warning.is_empty()).then_some(lateral_scale_warning));
    Ok((statistics, tables, flags))
}

/// The surface node's checks of a map's scale (`nodes::scale_checks`) without its statistics:
/// `(Sdq or None, sentences)`; a spacing the node would fail raises `ValueError`.
#[pyfunction]
#[pyo3(signature = (heights, dx, dy, periodic=false))]
fn scale_checks<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    periodic: bool,
) -> PyResult<(Option<f64>, Vec<String>)> {
    let map = height_map("heights", &heights, dx, dy)?;
    let boundary = if periodic {
        Boundary::Periodic
    } else {
        Boundary::Open
    };
    compute(py, || {
        node_scale_checks(&map, boundary).map_err(|e| value_error("heights", e.message))
    })
}

/// A surface report: statistics, long tables and sentences.
type Report<'py> = (Bound<'py, PyDict>, Bound<'py, PyDict>, Vec<String>);

/// A long table as `{column name (with its SI unit): NumPy array}`.
fn table_dict(py: Python<'_>, table: Table) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    for column in table.columns {
        let key = column.column_name();
        match column.data {
            ColumnData::Float(v) => d.set_item(key, v.into_pyarray(py))?,
            ColumnData::Int(v) => d.set_item(key, v.into_pyarray(py))?,
            ColumnData::Bool(v) => d.set_item(key, v)?,
            ColumnData::Text(v) => d.set_item(key, v)?,
        }
    }
    Ok(d)
}

/// Least-squares Legendre form of total degree `degree` removed: `(residual heights, rms)`.
#[pyfunction]
fn remove_form<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    degree: usize,
) -> PyResult<(Bound<'py, PyArray2<f64>>, f64)> {
    let map = height_map("heights", &heights, dx, dy)?;
    let removal = compute(py, || {
        remove_polynomial_form(&map, degree).map_err(|e| value_error("degree", e))
    })?;
    Ok((to_numpy(py, removal.surface), removal.residual_rms))
}

/// ISO 16610-61 Gaussian filter: `kind` is "low" (S-filter, `cutoff` λs), "high" (L-filter,
/// `cutoff` λc) or "band" (`cutoff` λs and `long_cutoff` λc); cut-offs in m.
#[pyfunction]
#[pyo3(signature = (heights, dx, dy, kind, cutoff, long_cutoff=None))]
fn gaussian_filter<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
    kind: &str,
    cutoff: f64,
    long_cutoff: Option<f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let map = height_map("heights", &heights, dx, dy)?;
    let filtered = compute(py, || {
        let result = match (kind, long_cutoff) {
            ("low", None) => gaussian_low_pass(&map, cutoff),
            ("high", None) => gaussian_high_pass(&map, cutoff),
            ("band", Some(long)) => gaussian_band_pass(&map, cutoff, long),
            ("band", None) => return Err(value_error("long_cutoff", "a band-pass needs λc in m")),
            ("low" | "high", Some(_)) => {
                return Err(value_error("long_cutoff", "only a band-pass takes it"))
            }
            _ => {
                return Err(value_error(
                    "kind",
                    format!("'{kind}' is not a filter; expected 'low', 'high' or 'band'"),
                ))
            }
        };
        result.map_err(|e| value_error("cutoff", e))
    })?;
    Ok(to_numpy(py, filtered))
}

/// Missing (NaN) points filled by the harmonic (Laplace) interpolation of the measured ones:
/// `(heights, filled point count)`.
#[pyfunction]
fn fill_missing<'py>(
    py: Python<'py>,
    heights: PyReadonlyArray2<'py, f64>,
    dx: f64,
    dy: f64,
) -> PyResult<(Bound<'py, PyArray2<f64>>, usize)> {
    let map = height_map("heights", &heights, dx, dy)?;
    let filled = compute(py, || {
        fill(&map, FillOptions::default()).map_err(|e| value_error("heights", e))
    })?;
    Ok((to_numpy(py, filled.surface), filled.filled_count))
}

/// A periodic self-affine Gaussian surface (spectral synthesis, ChaCha8: the same heights as
/// a study's `synthetic` surface with the same parameters): `(heights, dx, dy)`.
#[pyfunction]
#[pyo3(signature = (grid, size, sq, hurst, correlation_length, seed, short_wavelength_cutoff=None, anisotropy=None))]
#[allow(clippy::too_many_arguments)]
fn synthetic_surface<'py>(
    py: Python<'py>,
    grid: (usize, usize),
    size: (f64, f64),
    sq: f64,
    hurst: f64,
    correlation_length: f64,
    seed: u64,
    short_wavelength_cutoff: Option<f64>,
    anisotropy: Option<(f64, f64)>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, f64, f64)> {
    let spec = SyntheticSurfaceSpec {
        nx: grid.0,
        ny: grid.1,
        lx: size.0,
        ly: size.1,
        sq,
        hurst,
        correlation_length,
        short_wavelength_cutoff,
        anisotropy: anisotropy.map(|(aspect_ratio, angle)| Anisotropy {
            aspect_ratio,
            angle,
        }),
        seed,
    };
    let map = compute(py, || {
        generate_synthetic_surface(&spec).map_err(|e| value_error("synthetic_surface", e))
    })?;
    let (dx, dy) = (map.dx(), map.dy());
    Ok((to_numpy(py, map), dx, dy))
}

/// A twin's heights, dx, dy (m) and its prediction.
type Twin<'py> = (Bound<'py, PyArray2<f64>>, f64, f64, Bound<'py, PyDict>);

/// A synthetic twin of measured surfaces (complete maps `(heights, dx, dy)`) at Sq `sq` (m) on
/// `grid` points over `size` (m): `(heights, dx, dy, prediction)`.
#[pyfunction]
#[pyo3(signature = (measured, sq, grid, size, seed, short_wavelength_cutoff=None, threshold=0.2))]
#[allow(clippy::too_many_arguments)]
fn synthetic_twin<'py>(
    py: Python<'py>,
    measured: Vec<(PyReadonlyArray2<'py, f64>, f64, f64)>,
    sq: f64,
    grid: (usize, usize),
    size: (f64, f64),
    seed: u64,
    short_wavelength_cutoff: Option<f64>,
    threshold: f64,
) -> PyResult<Twin<'py>> {
    let maps = measured
        .iter()
        .enumerate()
        .map(|(i, (h, dx, dy))| height_map(&format!("measured[{i}]"), h, *dx, *dy))
        .collect::<PyResult<Vec<_>>>()?;
    let twin_grid = TwinGrid {
        nx: grid.0,
        ny: grid.1,
        lx: size.0,
        ly: size.1,
        short_wavelength_cutoff,
        seed,
    };
    let twin = compute(py, || {
        let options = TextureOptions {
            threshold,
            ..TextureOptions::default()
        };
        let textures = maps
            .iter()
            .enumerate()
            .map(|(i, m)| {
                measure_texture(m, &options).map_err(|e| value_error(&format!("measured[{i}]"), e))
            })
            .collect::<PyResult<Vec<_>>>()?;
        let model = fit_twin_model(&textures).map_err(|e| value_error("measured", e))?;
        make_twin(&model, sq, &twin_grid, threshold).map_err(|e| value_error("sq", e))
    })?;
    let p = &twin.prediction;
    let d = PyDict::new(py);
    d.set_item(key(TWIN_SQ, Length), p.sq)?;
    d.set_item(
        key(TWIN_CORRELATION_LENGTH_X, Length),
        p.correlation_length_x,
    )?;
    d.set_item(
        key(TWIN_CORRELATION_LENGTH_Y, Length),
        p.correlation_length_y,
    )?;
    d.set_item(TWIN_HURST, p.hurst)?;
    d.set_item(TWIN_HURST_PREDICTED, p.hurst_predicted)?;
    d.set_item(
        TWIN_WARNINGS,
        p.warnings.iter().map(|w| w.to_string()).collect::<Vec<_>>(),
    )?;
    let (dx, dy) = (twin.surface.dx(), twin.surface.dy());
    Ok((to_numpy(py, twin.surface), dx, dy, d))
}
