//! What a `surface` node reports: the `surfaces` table row and its long tables (`summits`, `psd`,
//! `acf`).
//!
//! * Amplitude and hybrid parameters (ISO 25178-2) over valid points, mean removed, no levelling.
//! * Spectral parameters need a complete map: for a map with missing points they are left out
//!   (null cells) unless the study fills the points (`fill_missing: true`). Periodic (synthetic)
//!   maps use no window, the periodic ACF and spectrum moments; measured maps use a Hann window,
//!   the zero-padded ACF and finite-difference moments (see `surface::spectral`). The Hurst
//!   exponent (PSD slope over wavelengths of 4–16 pixels) is reported only where that band is
//!   self-affine: 0 < H ≤ 1 and r² ≥ 0.9.
//! * Greenwood–Williamson summit statistics (η, R, σ_s, y_s, β) from the isotropic profile moments
//!   (Nayak/McCool, `friction::SummitStatistics`); omitted when α ≤ 0.8968, where they are undefined.
//! * Identified summits (8-neighbour maxima): count, density, mean radius, and one row each.
//! * ISO 25178-2 functional and volume parameters (Sk, Spk, Svk, Smr1, Smr2, Sxp, Vmp, Vmc, Vvc,
//!   Vvv at the default ratios) over valid points, and the material ratio curve every 1 %.

use std::borrow::Cow;
use std::collections::BTreeMap;

use crate::engine::artifact::Table;
use crate::engine::node::NodeError;
use crate::engine::value::Field;
use crate::friction::SummitStatistics as GwSummits;
use crate::nodes::surface_view::{DX, DY, GRID_NX, GRID_NY, M0, M2, M4};
use crate::nodes::validity;
use crate::surface::spectral::{
    autocorrelation, hurst_exponent_of, periodic_autocorrelation_of, periodogram, radial_psd_of,
    spectral_moments, spectral_moments_of, texture_direction_of, AcfBoundary, Autocorrelation,
    HurstFitOptions, MomentMethod, Periodogram, PsdTable, SpectralMoments, Window,
    ISO_ACF_THRESHOLD,
};
use crate::surface::{
    amplitude_statistics, find_summits, functional_parameters_of, Boundary, FunctionalOptions,
    HeightMap, MaterialRatioCurve, SummitOptions,
};
use crate::units::Dimension;

/// The long table of the material ratio curve (`surfaces_material_ratio`).
pub(crate) use crate::vocabulary::tables::MATERIAL_RATIO as MATERIAL_RATIO_TABLE;

/// Below this coefficient of determination the PSD band is not a power law: no Hurst exponent.
const MIN_HURST_FIT_R_SQUARED: f64 = 0.9;

/// The table row and long tables of one surface.
pub(super) struct SurfaceReport {
    pub metrics: Vec<Field>,
    pub tables: BTreeMap<String, Table>,
    /// The RMS slope Sdq (also among the metrics), for checks of the lateral scale.
    pub sdq: Option<f64>,
    /// Sq (also among the metrics), for the check against the map's size.
    pub sq: f64,
}

/// The grid spacings `dx`, `dy` as the row reports them.
pub(super) fn spacing_fields(map: &HeightMap) -> [Field; 2] {
    [len(DX, map.dx()), len(DY, map.dy())]
}

fn len(name: &'static str, v: f64) -> Field {
    Field::float(name, v, Dimension::Length)
}

fn num(name: impl Into<Cow<'static, str>>, v: f64) -> Field {
    Field::float(name, v, Dimension::Dimensionless)
}

/// Computes every metric and table of `map`; `periodogram`, where the source has it (a
/// synthetic surface's modes), is the unwindowed periodogram of `map` (else the spectra
/// transform the heights).
pub(super) fn surface_report(
    map: &HeightMap,
    boundary: Boundary,
    periodogram: Option<Periodogram>,
) -> Result<SurfaceReport, NodeError> {
    let a = amplitude_statistics(map, boundary)
        .map_err(|e| NodeError::new(format!("statistics: {e}")))?;
    let mut metrics = vec![
        Field::int(GRID_NX, map.nx() as i64),
        Field::int(GRID_NY, map.ny() as i64),
        len(DX, map.dx()),
        len(DY, map.dy()),
        Field::int("missing_points", a.missing_count as i64),
        len("sq", a.sq),
        len("sa", a.sa),
        len("sp", a.sp),
        len("sv", a.sv),
        len("sz", a.sz),
    ];
    // Undefined statistics (a flat map has no skewness) are left out: the cell is null.
    let optional = [
        ("ssk", a.ssk),
        ("sku", a.sku),
        ("sdq", a.sdq),
        ("sdr_percent", a.sdr_percent),
    ];
    metrics.extend(
        optional
            .into_iter()
            .filter_map(|(name, v)| v.map(|v| num(name, v))),
    );
    // An overflowed or underflowed amplitude is the cause of whatever the spectra would report.
    validity::check_fields(validity::SURFACE, &metrics)?;
    let mut tables = BTreeMap::new();
    functional_metrics(map, &mut metrics, &mut tables)?;
    if a.missing_count == 0 && a.sq > 0.0 {
        spectral_metrics(map, boundary, periodogram, &mut metrics, &mut tables)?;
    }
    summit_metrics(map, boundary, &mut metrics, &mut tables)?;
    Ok(SurfaceReport {
        metrics,
        tables,
        sdq: a.sdq,
        sq: a.sq,
    })
}

fn spectral_metrics(
    map: &HeightMap,
    boundary: Boundary,
    source_periodogram: Option<Periodogram>,
    metrics: &mut Vec<Field>,
    tables: &mut BTreeMap<String, Table>,
) -> Result<(), NodeError> {
    let periodic = boundary == Boundary::Periodic;
    let window = if periodic { Window::None } else { Window::Hann };
    let fail = |what: &str, e: &dyn std::fmt::Display| NodeError::new(format!("{what}: {e}"));
    // One periodogram serves the moments and the ACF (periodic maps: unwindowed), the texture
    // direction, the Hurst fit and the PSD table: the source's where it has one.
    let p = match source_periodogram.filter(|p| p.window == window) {
        Some(p) => p,
        None => periodogram(map, window).map_err(|e| fail("PSD", &e))?,
    };
    let psd = radial_psd_of(&p, map);
    let m = if periodic {
        spectral_moments_of(&p, map)
    } else {
        spectral_moments(map, MomentMethod::FiniteDifference)
    }
    .map_err(|e| fail("spectral moments", &e))?;
    moment_metrics(&m, metrics);
    let acf = if periodic {
        periodic_autocorrelation_of(&p, map)
    } else {
        autocorrelation(map, AcfBoundary::ZeroPadded)
    }
    .map_err(|e| fail("autocorrelation", &e))?;
    acf_metrics(&acf, metrics);
    if let Ok(direction) = texture_direction_of(&p, map) {
        metrics.push(Field::float(
            "std",
            direction.std_deg.to_radians(),
            Dimension::Angle,
        ));
    }
    hurst_metrics(&psd, map, window, metrics);
    let radial = acf.radial();
    let mut acf_table = Table::default();
    acf_table.push_float("r", Dimension::Length, radial.r);
    acf_table.push_float("acf", Dimension::Dimensionless, radial.acf);
    tables.insert(String::from("acf"), acf_table);
    let mut psd_table = Table::default();
    psd_table.push_float("q_rad_per_m", Dimension::Dimensionless, psd.q);
    psd_table.push_float("c_m4", Dimension::Dimensionless, psd.c);
    tables.insert(String::from("psd"), psd_table);
    Ok(())
}

/// The spectral moments m0, m2, m4 (isotropic, along x and y) and the Greenwood–Williamson
/// summit statistics they imply.
fn moment_metrics(m: &SpectralMoments, metrics: &mut Vec<Field>) {
    for (suffix, p) in [("", m.isotropic), ("_x", m.x), ("_y", m.y)] {
        metrics.push(Field::float(format!("{M0}{suffix}"), p.m0, Dimension::Area));
        metrics.push(num(format!("{M2}{suffix}"), p.m2));
        metrics.push(Field::float(
            format!("{M4}{suffix}"),
            p.m4,
            Dimension::InverseArea,
        ));
    }
    if let Ok(gw) = GwSummits::from_moments(m.isotropic.m0, m.isotropic.m2, m.isotropic.m4) {
        metrics.extend([
            Field::float("gw_summit_density", gw.density, Dimension::InverseArea),
            len("gw_summit_radius", gw.radius),
            len("gw_sigma_s", gw.sigma_s),
            len("gw_y_s", gw.y_s),
            num("gw_beta", gw.beta),
            num("gw_alpha", gw.alpha),
        ]);
    }
}

/// The ISO 25178-2 texture parameters Sal and Str and the correlation lengths of `acf`.
fn acf_metrics(acf: &Autocorrelation, metrics: &mut Vec<Field>) {
    if let Ok(texture) = acf.texture(ISO_ACF_THRESHOLD) {
        metrics.push(len("sal", texture.sal));
        if let Some(str_ratio) = texture.str_ratio {
            metrics.push(num("str", str_ratio));
        }
    }
    if let Ok(lengths) = acf.correlation_lengths(ISO_ACF_THRESHOLD) {
        metrics.extend(lengths.x.map(|x| len("correlation_length_x", x)));
        metrics.extend(lengths.y.map(|y| len("correlation_length_y", y)));
    }
}

/// The Hurst exponent fitted to the radial PSD.
fn hurst_metrics(psd: &PsdTable, map: &HeightMap, window: Window, metrics: &mut Vec<Field>) {
    // The fit is reported only where the PSD in the band is self-affine (0 < H ≤ 1 and
    // r² ≥ 0.9); a band inside the roll-off plateau would give a meaningless exponent.
    if let Ok(fit) = hurst_exponent_of(
        psd,
        map,
        HurstFitOptions {
            q_min: None,
            q_max: None,
            window,
        },
    ) {
        if fit.hurst > 0.0 && fit.hurst <= 1.0 && fit.r_squared >= MIN_HURST_FIT_R_SQUARED {
            metrics.extend([
                num("hurst_fit", fit.hurst),
                num("hurst_fit_q_min_rad_per_m", fit.q_min),
                num("hurst_fit_q_max_rad_per_m", fit.q_max),
                num("hurst_fit_r_squared", fit.r_squared),
            ]);
        }
    }
}

/// Samples of the material ratio curve in the `material_ratio` table: every 1 %.
const MATERIAL_RATIO_SAMPLES: usize = 101;

/// The ISO 25178-2 functional and volume parameters at the standard's default ratios
/// (`surface::functional_parameters`) and the material ratio curve, over the valid points.
fn functional_metrics(
    map: &HeightMap,
    metrics: &mut Vec<Field>,
    tables: &mut BTreeMap<String, Table>,
) -> Result<(), NodeError> {
    let fail = |e: &dyn std::fmt::Display| NodeError::new(format!("material ratio curve: {e}"));
    let curve = MaterialRatioCurve::of(map).map_err(|e| fail(&e))?;
    let f = functional_parameters_of(&curve, FunctionalOptions::default()).map_err(|e| fail(&e))?;
    metrics.extend([
        len("sk", f.sk),
        len("spk", f.spk),
        len("svk", f.svk),
        num("smr1_percent", 100.0 * f.smr1),
        num("smr2_percent", 100.0 * f.smr2),
        len("sxp", f.sxp),
    ]);
    // Volumes per unit area, m³/m²: named with their unit, as ISO writes them (ml/m² = µm).
    metrics.extend([
        num("vmp_m3_per_m2", f.vmp),
        num("vmc_m3_per_m2", f.vmc),
        num("vvc_m3_per_m2", f.vvc),
        num("vvv_m3_per_m2", f.vvv),
    ]);
    let (mr, height) = curve.sampled(MATERIAL_RATIO_SAMPLES);
    let mut t = Table::default();
    t.push_float(
        "material_ratio_percent",
        Dimension::Dimensionless,
        mr.iter().map(|r| 100.0 * r).collect(),
    );
    t.push_float("height", Dimension::Length, height);
    tables.insert(String::from(MATERIAL_RATIO_TABLE), t);
    Ok(())
}

fn summit_metrics(
    map: &HeightMap,
    boundary: Boundary,
    metrics: &mut Vec<Field>,
    tables: &mut BTreeMap<String, Table>,
) -> Result<(), NodeError> {
    let found = find_summits(
        map,
        SummitOptions {
            boundary,
            min_height: None,
            min_prominence: None,
        },
    )
    .map_err(|e| NodeError::new(format!("summits: {e}")))?;
    let s = &found.statistics;
    metrics.push(Field::int("summit_count", s.count as i64));
    metrics.push(Field::float(
        "summit_density",
        s.density,
        Dimension::InverseArea,
    ));
    metrics.extend(s.mean_radius.map(|r| len("summit_mean_radius", r)));
    metrics.extend(s.height_std.map(|h| len("summit_height_std", h)));
    let mut t = Table::default();
    t.push_int("ix", found.summits.iter().map(|x| x.ix as i64).collect());
    t.push_int("iy", found.summits.iter().map(|x| x.iy as i64).collect());
    t.push_float(
        "x",
        Dimension::Length,
        found.summits.iter().map(|x| x.x).collect(),
    );
    t.push_float(
        "y",
        Dimension::Length,
        found.summits.iter().map(|x| x.y).collect(),
    );
    t.push_float(
        "height",
        Dimension::Length,
        found.summits.iter().map(|x| x.height).collect(),
    );
    t.push_float(
        "slope",
        Dimension::Dimensionless,
        found.summits.iter().map(|x| x.slope).collect(),
    );
    t.push_float(
        "radius",
        Dimension::Length,
        found.summits.iter().map(|x| x.radius).collect(),
    );
    tables.insert(String::from("summits"), t);
    Ok(())
}
