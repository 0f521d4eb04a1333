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

use super::gradient::rms_gradient;
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

/// Count, mean, minimum and maximum of the valid heights (`None` if there is none). Rows are
/// summed on their own, in parallel, and their sums added in row order.
pub(crate) fn valid_mean_min_max(map: &HeightMap) -> Option<(usize, f64, f64, f64)> {
    let nx = map.nx();
    let rows = map.map_rows(|iy, z| {
        let (mut count, mut sum) = (0usize, 0.0);
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for &h in z[iy * nx..(iy + 1) * nx].iter().filter(|h| !h.is_nan()) {
            sum += h;
            count += 1;
            min = min.min(h);
            max = max.max(h);
        }
        (count, sum, min, max)
    });
    let (count, sum, min, max) = rows.into_iter().fold(
        (0usize, 0.0, f64::INFINITY, f64::NEG_INFINITY),
        |(count, sum, min, max), row| (count + row.0, sum + row.1, min.min(row.2), max.max(row.3)),
    );
    (count > 0).then(|| (count, sum / count as f64, min, max))
}

/// `Σ |d|, Σ d², Σ d³, Σ d⁴` of the valid heights' deviations `d = z − mean`, per row in
/// parallel, the rows added in row order.
fn central_sums(map: &HeightMap, mean: f64) -> [f64; 4] {
    let nx = map.nx();
    let rows = map.map_rows(|iy, z| {
        let mut r = [0.0; 4];
        for &h in z[iy * nx..(iy + 1) * nx].iter().filter(|h| !h.is_nan()) {
            let d = h - mean;
            let d2 = d * d;
            r[0] += d.abs();
            r[1] += d2;
            r[2] += d2 * d;
            r[3] += d2 * d2;
        }
        r
    });
    rows.into_iter().fold([0.0; 4], |mut s, r| {
        s.iter_mut().zip(r).for_each(|(s, r)| *s += r);
        s
    })
}

/// Amplitude and hybrid statistics of `map`; `boundary` applies to the gradient terms only.
pub fn amplitude_statistics(
    map: &HeightMap,
    boundary: Boundary,
) -> Result<AmplitudeStatistics, AmplitudeError> {
    let (count, mean, min, max) = valid_mean_min_max(map).ok_or(AmplitudeError::NoValidPoints)?;
    let [s1, s2, s3, s4] = central_sums(map, mean);
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
    // Its only error: no point has the neighbours it needs.
    let forward = rms_gradient(map, DifferenceScheme::Forward, boundary).ok();
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
        forward_gradient_point_count: forward.map_or(0, |g| g.1),
    })
}

/// `(Sdq, Sdr %, point count)`, or `None` when no point had the neighbours it needs.
fn optional(result: Result<super::GradientStatistics, GradientError>) -> Option<(f64, f64, usize)> {
    match result {
        Ok(g) => Some((g.sdq, g.sdr_percent, g.point_count)),
        Err(GradientError::NoGradientPoints { .. }) => None,
    }
}
