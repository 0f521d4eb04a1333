//! Height (amplitude) parameters of ISO 25178-2 together with the hybrid parameters `Sdq`, `Sdr`.
//!
//! Over the `N` valid points with heights `z_i` and mean `m = (1/N) Σ z_i` (the mean plane; no
//! levelling — remove form first with [`crate::surface::remove_polynomial_form`] if wanted):
//!
//! * `Sq  = sqrt((1/N) Σ (z_i − m)²)`
//! * `Sa  = (1/N) Σ |z_i − m|`
//! * `Ssk = (1/N) Σ (z_i − m)³ / Sq³`, `Sku = (1/N) Σ (z_i − m)⁴ / Sq⁴`
//! * `Sp = max z − m`, `Sv = m − min z` (a positive depth), `Sz = Sp + Sv`
//!
//! (ISO 25178-2:2012 §4.1; the discrete means are those of SurfaceTopography and of the project's
//! reference values.) Missing (`NaN`) points are excluded, never treated as zeros. `Sdq` and `Sdr` come
//! from [`crate::surface::gradient_statistics`] with central differences (ISO-style), and the
//! forward-difference `rms_gradient` of SurfaceTopography is reported alongside.

use super::{gradient_statistics, Boundary, DifferenceScheme, GradientError, HeightMap};

/// Amplitude and hybrid statistics of one height map (lengths in metres).
#[derive(Debug, Clone, PartialEq)]
pub struct AmplitudeStatistics {
    /// Number of valid (measured) points `N`.
    pub valid_count: usize,
    /// Number of missing (`NaN`) points.
    pub missing_count: usize,
    /// Mean height `m` of the valid points (m).
    pub mean: f64,
    /// Root-mean-square height `Sq` (m).
    pub sq: f64,
    /// Arithmetic mean height `Sa` (m).
    pub sa: f64,
    /// Skewness `Ssk`; `None` when `Sq = 0` (flat surface: undefined).
    pub ssk: Option<f64>,
    /// Kurtosis `Sku`; `None` when `Sq = 0` (flat surface: undefined).
    pub sku: Option<f64>,
    /// Maximum peak height `Sp` above the mean (m).
    pub sp: f64,
    /// Maximum pit depth `Sv` below the mean, positive (m).
    pub sv: f64,
    /// Maximum height `Sz = Sp + Sv` (m).
    pub sz: f64,
    /// Root-mean-square gradient `Sdq` from central differences; `None` if no point has the four valid
    /// neighbours it needs.
    pub sdq: Option<f64>,
    /// Developed interfacial area ratio `Sdr` in percent, from the same central differences.
    pub sdr_percent: Option<f64>,
    /// Number of points that entered `Sdq`/`Sdr`.
    pub gradient_point_count: usize,
    /// SurfaceTopography's `rms_gradient`: forward differences on the cropped `(nx−1)×(ny−1)` grid
    /// (open boundary) or wrapped (periodic boundary); `None` if no point qualifies.
    pub rms_gradient_forward: Option<f64>,
    /// Number of points that entered `rms_gradient_forward`.
    pub forward_gradient_point_count: usize,
}

/// Why amplitude statistics could not be computed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum AmplitudeError {
    #[error("the height map has no valid (non-NaN) point")]
    NoValidPoints,
}

/// Count, mean, minimum and maximum of the valid heights (`None` if there is none).
pub(crate) fn valid_mean_min_max(map: &HeightMap) -> Option<(usize, f64, f64, f64)> {
    let mut count = 0usize;
    let mut sum = 0.0;
    let mut min = f64::INFINITY;
    let mut max = f64::NEG_INFINITY;
    for row in map.heights().rows() {
        let mut row_sum = 0.0;
        for &h in row.iter().filter(|h| !h.is_nan()) {
            row_sum += h;
            count += 1;
            min = min.min(h);
            max = max.max(h);
        }
        sum += row_sum;
    }
    (count > 0).then(|| (count, sum / count as f64, min, max))
}

/// Amplitude and hybrid statistics of `map`; `boundary` applies to the gradient terms only.
pub fn amplitude_statistics(
    map: &HeightMap,
    boundary: Boundary,
) -> Result<AmplitudeStatistics, AmplitudeError> {
    let (count, mean, min, max) = valid_mean_min_max(map).ok_or(AmplitudeError::NoValidPoints)?;
    let (mut s1, mut s2, mut s3, mut s4) = (0.0, 0.0, 0.0, 0.0);
    for row in map.heights().rows() {
        let (mut r1, mut r2, mut r3, mut r4) = (0.0, 0.0, 0.0, 0.0);
        for &h in row.iter().filter(|h| !h.is_nan()) {
            let d = h - mean;
            let d2 = d * d;
            r1 += d.abs();
            r2 += d2;
            r3 += d2 * d;
            r4 += d2 * d2;
        }
        s1 += r1;
        s2 += r2;
        s3 += r3;
        s4 += r4;
    }
    let n = count as f64;
    let sq = (s2 / n).sqrt();
    let (ssk, sku) = if sq > 0.0 {
        (Some(s3 / n / sq.powi(3)), Some(s4 / n / sq.powi(4)))
    } else {
        (None, None)
    };
    let central = optional(gradient_statistics(
        map,
        DifferenceScheme::Central,
        boundary,
    ));
    let forward = optional(gradient_statistics(
        map,
        DifferenceScheme::Forward,
        boundary,
    ));
    Ok(AmplitudeStatistics {
        valid_count: count,
        missing_count: map.nx() * map.ny() - count,
        mean,
        sq,
        sa: s1 / n,
        ssk,
        sku,
        sp: max - mean,
        sv: mean - min,
        sz: max - min,
        sdq: central.map(|g| g.0),
        sdr_percent: central.map(|g| g.1),
        gradient_point_count: central.map_or(0, |g| g.2),
        rms_gradient_forward: forward.map(|g| g.0),
        forward_gradient_point_count: forward.map_or(0, |g| g.2),
    })
}

/// `(Sdq, Sdr %, point count)`, or `None` when no point had the neighbours it needs.
fn optional(result: Result<super::GradientStatistics, GradientError>) -> Option<(f64, f64, usize)> {
    match result {
        Ok(g) => Some((g.sdq, g.sdr_percent, g.point_count)),
        Err(GradientError::NoGradientPoints { .. }) => None,
    }
}
