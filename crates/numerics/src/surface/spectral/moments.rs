//! Profile spectral moments m0, m2, m4 along x, along y, and isotropic (direction-averaged).
//!
//! Definitions (Nayak, *J. Lubr. Technol.* 93 (1971) 398; McCool, *Wear* 107 (1986) 37): for a
//! profile along unit direction `e`, `m0 = ⟨z²⟩`, `m2 = ⟨(∂z/∂e)²⟩`, `m4 = ⟨(∂²z/∂e²)²⟩`, with
//! mean-removed heights. Spectrally, with the 2-D PSD `C(q)` of [`super::psd`],
//! `m_n(e) = (1/A) Σ_q (q·e)^n C(q)`. The **isotropic** moments are the average over all
//! in-plane directions: `m0`, `m2 = (1/A) Σ |q|² C / 2 = (m2x + m2y)/2`,
//! `m4 = (1/A) Σ (3/8)|q|⁴ C = (3/8)(⟨zxx²⟩ + ⟨zyy²⟩) + ½⟨zxy²⟩ + ¼⟨zxx zyy⟩`.
//!
//! Two methods:
//! * [`MomentMethod::Spectrum`] — the sums above over the unwindowed periodogram: the exact
//!   moments of the periodic trigonometric interpolant. Use for periodic (synthetic) surfaces;
//!   on a non-periodic measured map the edge jump adds spurious high-q power.
//! * [`MomentMethod::FiniteDifference`] — no periodicity assumed: forward differences
//!   `(z[i+1] − z[i])/dx` for slopes (averaged over all `nx − 1` pairs of every row), the
//!   three-point second difference `(z[i+1] − 2z[i] + z[i−1])/dx²` for curvatures (over the
//!   `nx − 2` interior points of every row), the forward mixed difference over all cells, and
//!   `⟨zxx zyy⟩` over points interior in both directions. For a sinusoid of wavenumber `k` these
//!   give `m2 = (A²/2)(2 sin(k dx/2)/dx)²` and `m4 = (A²/2)(2(1 − cos k dx)/dx²)²`: they
//!   under-estimate the spectral values by `1 − O((k dx)²)`.
//!
//! **Resolution dependence**: m0 converges with resolution, but for a self-affine surface with
//! Hurst exponent H the spectral sums grow with the largest wavenumber resolved,
//! `m2 ∝ q_max^(2−2H)` and `m4 ∝ q_max^(4−2H)`, so m2, m4 and everything derived from them (slopes,
//! summit curvature and density) depend on the pixel size and the S-filter; compare them only at
//! equal sampling and filtering.

use rayon::prelude::*;

use super::error::{require_complete, SpectralError};
use super::psd::{periodogram, Periodogram, Window};
use crate::surface::HeightMap;

/// How the moments are computed (see module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MomentMethod {
    Spectrum,
    FiniteDifference,
}

/// m0 (m²), m2 (dimensionless, mean square slope), m4 (m⁻², mean square curvature).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfileMoments {
    pub m0: f64,
    pub m2: f64,
    pub m4: f64,
}

/// Moments along x, along y, and averaged over directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralMoments {
    pub x: ProfileMoments,
    pub y: ProfileMoments,
    pub isotropic: ProfileMoments,
    pub method: MomentMethod,
}

impl SpectralMoments {
    /// Assembles the three directions from the common m0 and each direction's `(m2, m4)`.
    fn assemble(
        m0: f64,
        [x, y, isotropic]: [(f64, f64); 3],
        method: MomentMethod,
    ) -> SpectralMoments {
        let profile = |(m2, m4): (f64, f64)| ProfileMoments { m0, m2, m4 };
        SpectralMoments {
            x: profile(x),
            y: profile(y),
            isotropic: profile(isotropic),
            method,
        }
    }
}

/// Computes m0, m2, m4 of a complete height map.
pub fn spectral_moments(
    map: &HeightMap,
    method: MomentMethod,
) -> Result<SpectralMoments, SpectralError> {
    match method {
        MomentMethod::Spectrum => from_spectrum(map),
        MomentMethod::FiniteDifference => from_differences(map),
    }
}

fn from_spectrum(map: &HeightMap) -> Result<SpectralMoments, SpectralError> {
    spectral_moments_of(&periodogram(map, Window::None)?, map)
}

/// [`spectral_moments`] by [`MomentMethod::Spectrum`] from the unwindowed periodogram of `map`
/// (one FFT shared by several statistics); a windowed periodogram is an error.
pub fn spectral_moments_of(
    p: &Periodogram,
    map: &HeightMap,
) -> Result<SpectralMoments, SpectralError> {
    if p.window != Window::None {
        return Err(SpectralError::Windowed {
            what: "spectral moments",
        });
    }
    let (lx, ly) = map.size();
    let area = lx * ly;
    let mut sums = [0.0f64; 7]; // m0, m2x, m4x, m2y, m4y, Σ|q|²C, Σ|q|⁴C
    for ((j, i), c) in p.c.indexed_iter() {
        let (qx, qy) = p.wavevector(j, i);
        let w = p.multiplicity(i) * c;
        let (qx2, qy2) = (qx * qx, qy * qy);
        let q2 = qx2 + qy2;
        for (sum, term) in sums
            .iter_mut()
            .zip([1.0, qx2, qx2 * qx2, qy2, qy2 * qy2, q2, q2 * q2])
        {
            *sum += w * term;
        }
    }
    let [m0, m2x, m4x, m2y, m4y, q2, q4] = sums.map(|s| s / area);
    Ok(SpectralMoments::assemble(
        m0,
        [(m2x, m4x), (m2y, m4y), (q2 / 2.0, 3.0 / 8.0 * q4)],
        MomentMethod::Spectrum,
    ))
}

fn from_differences(map: &HeightMap) -> Result<SpectralMoments, SpectralError> {
    require_complete(map)?;
    let (nx, ny) = (map.nx(), map.ny());
    let (dx, dy) = (map.dx(), map.dy());
    let z = map.heights();
    let mean = z.sum() / (nx * ny) as f64;
    let m0 = z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (nx * ny) as f64;

    let h: Vec<f64> = z.iter().copied().collect(); // row-major, x fastest
                                                   // Per-row sums in row order, then a sequential total: deterministic for any thread count.
    let rows: Vec<[f64; 6]> = (0..ny)
        .into_par_iter()
        .map(|j| difference_sums(&h, nx, ny, j))
        .collect();
    let mut sums = [0.0; 6];
    for row in &rows {
        for (total, value) in sums.iter_mut().zip(row) {
            *total += value;
        }
    }
    let [zx2, zy2, zxx2, zyy2, zxy2, cross] = sums;
    let mean = |sum: f64, count: usize, scale: f64| {
        if count > 0 {
            sum / (count as f64 * scale)
        } else {
            0.0
        }
    };
    let (dx2, dy2) = (dx * dx, dy * dy);
    let m2x = mean(zx2, ny * (nx - 1), dx2);
    let m2y = mean(zy2, (ny - 1) * nx, dy2);
    let m4x = mean(zxx2, ny * nx.saturating_sub(2), dx2 * dx2);
    let m4y = mean(zyy2, ny.saturating_sub(2) * nx, dy2 * dy2);
    let m4_iso = if nx >= 3 && ny >= 3 {
        3.0 / 8.0 * (m4x + m4y)
            + 0.5 * mean(zxy2, (ny - 1) * (nx - 1), dx2 * dy2)
            + 0.25 * mean(cross, (ny - 2) * (nx - 2), dx2 * dy2)
    } else {
        0.0
    };
    Ok(SpectralMoments::assemble(
        m0,
        [(m2x, m4x), (m2y, m4y), ((m2x + m2y) / 2.0, m4_iso)],
        MomentMethod::FiniteDifference,
    ))
}

/// Unscaled sums over row `j` of a row-major `[ny, nx]` grid: `Σ Δx²`, `Σ Δy²` (to row
/// `j + 1`), `Σ Δxx²`, `Σ Δyy²` (rows `j ± 1`), `Σ Δxy²` (cell to row `j + 1`), `Σ Δxx·Δyy`.
fn difference_sums(h: &[f64], nx: usize, ny: usize, j: usize) -> [f64; 6] {
    let row = &h[j * nx..(j + 1) * nx];
    let next = (j + 1 < ny).then(|| &h[(j + 1) * nx..(j + 2) * nx]);
    let prev = (j > 0).then(|| &h[(j - 1) * nx..j * nx]);
    let mut sums = [0.0; 6];
    for i in 0..nx {
        let zxx = (i > 0 && i + 1 < nx).then(|| row[i + 1] - 2.0 * row[i] + row[i - 1]);
        if i + 1 < nx {
            sums[0] += (row[i + 1] - row[i]).powi(2);
        }
        if let Some(zxx) = zxx {
            sums[2] += zxx * zxx;
        }
        if let Some(next) = next {
            sums[1] += (next[i] - row[i]).powi(2);
            if i + 1 < nx {
                sums[4] += (next[i + 1] - next[i] - row[i + 1] + row[i]).powi(2);
            }
            if let Some(prev) = prev {
                let zyy = next[i] - 2.0 * row[i] + prev[i];
                sums[3] += zyy * zyy;
                if let Some(zxx) = zxx {
                    sums[5] += zxx * zyy;
                }
            }
        }
    }
    sums
}
