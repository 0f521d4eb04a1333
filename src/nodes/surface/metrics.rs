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
    autocorrelation, hurst_exponent_of, periodic_autocorrelation_with, periodogram, radial_psd_of,
    spectral_moments, spectral_moments_of, texture_direction_of, AcfBoundary, Autocorrelation,
    HurstFitOptions, InverseTransform, MomentMethod, Periodogram, PsdTable, SpectralMoments,
    Window, ISO_ACF_THRESHOLD,
};
use crate::surface::{
    amplitude_statistics, find_summits, functional_parameters_of, Boundary, FunctionalOptions,
    HeightMap, MaterialRatioCurve, SummitOptions,
};
use crate::units::Dimension;
use crate::vocabulary::metrics::{
    GW_BETA, GW_SIGMA_S, GW_SUMMIT_DENSITY, GW_SUMMIT_RADIUS, SQ, SUMMIT_COUNT, SUMMIT_DENSITY,
    SUMMIT_MEAN_RADIUS,
};
use crate::vocabulary::surface_metrics::{
    CORRELATION_LENGTH_X, CORRELATION_LENGTH_Y, GW_ALPHA, GW_Y_S, HURST_FIT, HURST_FIT_Q_MAX,
    HURST_FIT_Q_MIN, HURST_FIT_R_SQUARED, MISSING_POINTS, SA, SAL, SDQ, SDR_PERCENT, SK, SKU,
    SMR1_PERCENT, SMR2_PERCENT, SP, SPK, SSK, STD, STR, SUMMIT_HEIGHT_STD, SV, SVK, SXP, SZ, VMC,
    VMP, VVC, VVV, X_SUFFIX, Y_SUFFIX,
};
use crate::vocabulary::{acf_columns, material_ratio_columns, psd_columns, summit_columns, tables};

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

/// Computes every metric and table of `map`; `spectrum`, where the source has it (a synthetic
/// surface's modes), is the unwindowed periodogram of `map` and the inverse transform planned
/// for its grid (else the spectra transform the heights).
pub(super) fn surface_report(
    map: &HeightMap,
    boundary: Boundary,
    spectrum: Option<(Periodogram, InverseTransform)>,
) -> Result<SurfaceReport, NodeError> {
    let a = amplitude_statistics(map, boundary)
        .map_err(|e| NodeError::new(format!("statistics: {e}")))?;
    let mut metrics = vec![
        Field::int(GRID_NX, map.nx() as i64),
        Field::int(GRID_NY, map.ny() as i64),
        len(DX, map.dx()),
        len(DY, map.dy()),
        Field::int(MISSING_POINTS, a.missing_count as i64),
        len(SQ, a.sq),
        len(SA, a.sa),
        len(SP, a.sp),
        len(SV, a.sv),
        len(SZ, a.sz),
    ];
    // Undefined statistics (a flat map has no skewness) are left out: the cell is null.
    let optional = [
        (SSK, a.ssk),
        (SKU, a.sku),
        (SDQ, a.sdq),
        (SDR_PERCENT, a.sdr_percent),
    ];
    metrics.extend(
        optional
            .into_iter()
            .filter_map(|(name, v)| v.map(|v| num(name, v))),
    );
    // An overflowed or underflowed amplitude is the cause of whatever the spectra would report.
    validity::check_fields(validity::SURFACE, &metrics)?;
    let mut tables = BTreeMap::new();
    // The material ratio curve's memory (one value a point) then holds the autocorrelation.
    let spare = functional_metrics(map, &mut metrics, &mut tables)?;
    if a.missing_count == 0 && a.sq > 0.0 {
        let source = Spectra { spectrum, spare };
        spectral_metrics(map, boundary, source, &mut metrics, &mut tables)?;
    }
    summit_metrics(map, boundary, &mut metrics, &mut tables)?;
    Ok(SurfaceReport {
        metrics,
        tables,
        sdq: a.sdq,
        sq: a.sq,
    })
}

/// What the spectral statistics may take from before: the source's periodogram and inverse
/// transform, and a buffer of one value a point no statistic needs any more.
struct Spectra {
    spectrum: Option<(Periodogram, InverseTransform)>,
    spare: Vec<f64>,
}

fn spectral_metrics(
    map: &HeightMap,
    boundary: Boundary,
    source: Spectra,
    metrics: &mut Vec<Field>,
    tables: &mut BTreeMap<String, Table>,
) -> Result<(), NodeError> {
    let periodic = boundary == Boundary::Periodic;
    let window = if periodic { Window::None } else { Window::Hann };
    let fail = |what: &str, e: &dyn std::fmt::Display| NodeError::new(format!("{what}: {e}"));
    // One periodogram serves the moments and the ACF (periodic maps: unwindowed), the texture
    // direction, the Hurst fit and the PSD table: the source's where it has one.
    let (p, transform) = match source.spectrum.filter(|(p, _)| p.window == window) {
        Some((p, transform)) => (p, Some(transform)),
        None => (periodogram(map, window).map_err(|e| fail("PSD", &e))?, None),
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
        let mut transform = transform.unwrap_or_else(|| InverseTransform::new(map.nx(), map.ny()));
        periodic_autocorrelation_with(&p, map, &mut transform, source.spare)
    } else {
        autocorrelation(map, AcfBoundary::ZeroPadded)
    }
    .map_err(|e| fail("autocorrelation", &e))?;
    acf_metrics(&acf, metrics);
    if let Ok(direction) = texture_direction_of(&p, map) {
        metrics.push(Field::float(
            STD,
            direction.std_deg.to_radians(),
            Dimension::Angle,
        ));
    }
    hurst_metrics(&psd, map, window, metrics);
    let radial = acf.radial();
    let mut acf_table = Table::default();
    acf_table.push_float(acf_columns::R, Dimension::Length, radial.r);
    acf_table.push_float(acf_columns::ACF, Dimension::Dimensionless, radial.acf);
    tables.insert(String::from(tables::ACF), acf_table);
    let mut psd_table = Table::default();
    psd_table.push_float(psd_columns::Q, Dimension::Dimensionless, psd.q);
    psd_table.push_float(psd_columns::C, Dimension::Dimensionless, psd.c);
    tables.insert(String::from(tables::PSD), psd_table);
    Ok(())
}

/// The spectral moments m0, m2, m4 (isotropic, along x and y) and the Greenwood–Williamson
/// summit statistics they imply.
fn moment_metrics(m: &SpectralMoments, metrics: &mut Vec<Field>) {
    for (suffix, p) in [("", m.isotropic), (X_SUFFIX, m.x), (Y_SUFFIX, m.y)] {
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
            Field::float(GW_SUMMIT_DENSITY, gw.density, Dimension::InverseArea),
            len(GW_SUMMIT_RADIUS, gw.radius),
            len(GW_SIGMA_S, gw.sigma_s),
            len(GW_Y_S, gw.y_s),
            num(GW_BETA, gw.beta),
            num(GW_ALPHA, gw.alpha),
        ]);
    }
}

/// The ISO 25178-2 texture parameters Sal and Str and the correlation lengths of `acf`.
fn acf_metrics(acf: &Autocorrelation, metrics: &mut Vec<Field>) {
    if let Ok(texture) = acf.texture(ISO_ACF_THRESHOLD) {
        metrics.push(len(SAL, texture.sal));
        if let Some(str_ratio) = texture.str_ratio {
            metrics.push(num(STR, str_ratio));
        }
    }
    if let Ok(lengths) = acf.correlation_lengths(ISO_ACF_THRESHOLD) {
        metrics.extend(lengths.x.map(|x| len(CORRELATION_LENGTH_X, x)));
        metrics.extend(lengths.y.map(|y| len(CORRELATION_LENGTH_Y, y)));
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
                num(HURST_FIT, fit.hurst),
                num(HURST_FIT_Q_MIN, fit.q_min),
                num(HURST_FIT_Q_MAX, fit.q_max),
                num(HURST_FIT_R_SQUARED, fit.r_squared),
            ]);
        }
    }
}

/// Samples of the material ratio curve in the `material_ratio` table: every 1 %.
const MATERIAL_RATIO_SAMPLES: usize = 101;

/// The ISO 25178-2 functional and volume parameters at the standard's default ratios
/// (`surface::functional_parameters`) and the material ratio curve, over the valid points;
/// returns the curve's memory.
fn functional_metrics(
    map: &HeightMap,
    metrics: &mut Vec<Field>,
    tables: &mut BTreeMap<String, Table>,
) -> Result<Vec<f64>, NodeError> {
    let fail = |e: &dyn std::fmt::Display| NodeError::new(format!("material ratio curve: {e}"));
    let curve = MaterialRatioCurve::of(map).map_err(|e| fail(&e))?;
    let f = functional_parameters_of(&curve, FunctionalOptions::default()).map_err(|e| fail(&e))?;
    metrics.extend([
        len(SK, f.sk),
        len(SPK, f.spk),
        len(SVK, f.svk),
        num(SMR1_PERCENT, 100.0 * f.smr1),
        num(SMR2_PERCENT, 100.0 * f.smr2),
        len(SXP, f.sxp),
    ]);
    // Volumes per unit area, m³/m²: named with their unit, as ISO writes them (ml/m² = µm).
    metrics.extend([
        num(VMP, f.vmp),
        num(VMC, f.vmc),
        num(VVC, f.vvc),
        num(VVV, f.vvv),
    ]);
    let (mr, height) = curve.sampled(MATERIAL_RATIO_SAMPLES);
    let mut t = Table::default();
    t.push_float(
        material_ratio_columns::MATERIAL_RATIO_PERCENT,
        Dimension::Dimensionless,
        mr.iter().map(|r| 100.0 * r).collect(),
    );
    t.push_float(material_ratio_columns::HEIGHT, Dimension::Length, height);
    tables.insert(String::from(MATERIAL_RATIO_TABLE), t);
    Ok(curve.into_heights())
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
    metrics.push(Field::int(SUMMIT_COUNT, s.count as i64));
    metrics.push(Field::float(
        SUMMIT_DENSITY,
        s.density,
        Dimension::InverseArea,
    ));
    metrics.extend(s.mean_radius.map(|r| len(SUMMIT_MEAN_RADIUS, r)));
    metrics.extend(s.height_std.map(|h| len(SUMMIT_HEIGHT_STD, h)));
    let mut t = Table::default();
    t.push_int(
        summit_columns::IX,
        found.summits.iter().map(|x| x.ix as i64).collect(),
    );
    t.push_int(
        summit_columns::IY,
        found.summits.iter().map(|x| x.iy as i64).collect(),
    );
    t.push_float(
        summit_columns::X,
        Dimension::Length,
        found.summits.iter().map(|x| x.x).collect(),
    );
    t.push_float(
        summit_columns::Y,
        Dimension::Length,
        found.summits.iter().map(|x| x.y).collect(),
    );
    t.push_float(
        summit_columns::HEIGHT,
        Dimension::Length,
        found.summits.iter().map(|x| x.height).collect(),
    );
    t.push_float(
        summit_columns::SLOPE,
        Dimension::Dimensionless,
        found.summits.iter().map(|x| x.slope).collect(),
    );
    t.push_float(
        summit_columns::RADIUS,
        Dimension::Length,
        found.summits.iter().map(|x| x.radius).collect(),
    );
    tables.insert(String::from(tables::SUMMITS), t);
    Ok(())
}
