//! Areal Gaussian filter (ISO 16610-61) with the S-filter, L-filter and band (S-L) combinations.
//!
//! Weighting function (ISO 16610-61:2015, eq. 1, isotropic cutoff `λ` in both directions):
//!
//! `s(x, y) = 1/(α² λ²) · exp(−π (x/(αλ))² − π (y/(αλ))²)`, `α = sqrt(ln 2 / π) ≈ 0.4697`,
//!
//! whose amplitude transmission for a sinusoid of wavelength `w` is `exp(−π (αλ/w)²)`: exactly 50 %
//! at `w = λ`. The low-pass output is the **S-filter** (cutoff `λs`, removes short-scale noise); the
//! **L-filter** output is the input minus the low-pass with cutoff `λc` (removes long wavelengths).
//!
//! Implementation: separable discrete convolution (x pass, then y pass) with the sampled weights
//! `g_k = exp(−π (k·d/(αλ))²)`, truncated at `|k·d| ≤ λ` (the weight there is `exp(−π²/ln 2) ≈ 6.5e-7`
//! of the centre, so truncation changes the transmission by less than 1e-5; ISO 16610-21 allows
//! truncation at 0.5 λ, which we avoid for accuracy).
//!
//! Edges and missing points — **normalised convolution** (weights renormalised over valid points):
//! `out(p) = Σ_q s(p−q) m(q) z(q) / Σ_q s(p−q) m(q)`, with `m(q) = 1` for a valid point inside the grid and
//! `0` for a missing point or a point beyond the edge. Far from edges and holes this is the ordinary
//! Gaussian filter; near them it is the end-effect treatment by renormalised weights (no padding, no
//! periodic wrap). Both sums are separable, so the result equals the 2-D normalised convolution.
//! Missing points remain missing in the output (the filter does not fill holes; see
//! [`crate::surface::fill_missing`]).

use super::{HeightMap, HeightMapError};
use ndarray::Array2;
use rayon::prelude::*;

/// `α = sqrt(ln 2 / π)` of ISO 16610-61 (50 % transmission at the cutoff wavelength).
pub const GAUSSIAN_ALPHA: f64 = 0.469_718_639_349_825_7;

/// Kernel half-width in units of the cutoff wavelength.
pub const KERNEL_HALF_WIDTH_IN_CUTOFFS: f64 = 1.0;

/// Why a filter could not be applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FilterError {
    #[error("cutoff wavelength must be finite and > 0 m, got {cutoff} m")]
    BadCutoff { cutoff: f64 },
    #[error("band filter needs short cutoff λs = {short} m < long cutoff λc = {long} m")]
    BadBand { short: f64, long: f64 },
    #[error("filtered heights do not form a valid height map: {0}")]
    HeightMap(#[from] HeightMapError),
}

/// Gaussian low-pass (S-filter) with cutoff wavelength `cutoff` (m): keeps wavelengths ≫ `cutoff`.
pub fn gaussian_low_pass(map: &HeightMap, cutoff: f64) -> Result<HeightMap, FilterError> {
    check_cutoff(cutoff)?;
    let smooth = normalised_gaussian(map, cutoff);
    Ok(HeightMap::new(smooth, map.dx(), map.dy())?)
}

/// Gaussian high-pass (L-filter) with cutoff wavelength `cutoff` (m): `z − low_pass(z)`, keeps
/// wavelengths ≪ `cutoff`.
pub fn gaussian_high_pass(map: &HeightMap, cutoff: f64) -> Result<HeightMap, FilterError> {
    check_cutoff(cutoff)?;
    let smooth = normalised_gaussian(map, cutoff);
    let rough = map.heights() - &smooth;
    Ok(HeightMap::new(rough, map.dx(), map.dy())?)
}

/// Band-pass S-L surface: S-filter with `short_cutoff` (λs) followed by the L-filter with
/// `long_cutoff` (λc), `λs < λc`.
pub fn gaussian_band_pass(
    map: &HeightMap,
    short_cutoff: f64,
    long_cutoff: f64,
) -> Result<HeightMap, FilterError> {
    check_cutoff(short_cutoff)?;
    check_cutoff(long_cutoff)?;
    if short_cutoff >= long_cutoff {
        return Err(FilterError::BadBand {
            short: short_cutoff,
            long: long_cutoff,
        });
    }
    let s_surface = gaussian_low_pass(map, short_cutoff)?;
    gaussian_high_pass(&s_surface, long_cutoff)
}

fn check_cutoff(cutoff: f64) -> Result<(), FilterError> {
    if cutoff.is_finite() && cutoff > 0.0 {
        Ok(())
    } else {
        Err(FilterError::BadCutoff { cutoff })
    }
}

/// One-sided sampled weights `g_0..=g_w` for spacing `spacing` on an axis of `n` points.
fn half_kernel(cutoff: f64, spacing: f64, n: usize) -> Vec<f64> {
    let reach = (KERNEL_HALF_WIDTH_IN_CUTOFFS * cutoff / spacing).floor();
    let width = if reach < (n - 1) as f64 {
        reach as usize
    } else {
        n - 1
    };
    let scale = GAUSSIAN_ALPHA * cutoff;
    (0..=width)
        .map(|k| {
            let t = k as f64 * spacing / scale;
            (-std::f64::consts::PI * t * t).exp()
        })
        .collect()
}

/// Normalised separable Gaussian convolution of the valid heights; `NaN` at missing points.
fn normalised_gaussian(map: &HeightMap, cutoff: f64) -> Array2<f64> {
    let (nx, ny) = (map.nx(), map.ny());
    // Row-major copy (x fastest), whatever the memory layout of the input array.
    let z: Vec<f64> = map.heights().iter().copied().collect();
    let gx = half_kernel(cutoff, map.dx(), nx);
    let gy = half_kernel(cutoff, map.dy(), ny);

    // x pass: numerator Σ g z m and denominator Σ g m along each row.
    let mut num_x = vec![0.0; nx * ny];
    let mut den_x = vec![0.0; nx * ny];
    num_x
        .par_chunks_mut(nx)
        .zip(den_x.par_chunks_mut(nx))
        .zip(z.par_chunks(nx))
        .for_each(|((num, den), row)| {
            for ix in 0..nx {
                let (mut s, mut w) = (0.0, 0.0);
                let lo = ix.saturating_sub(gx.len() - 1);
                let hi = (ix + gx.len()).min(nx);
                for (jx, &h) in row.iter().enumerate().take(hi).skip(lo) {
                    if !h.is_nan() {
                        let g = gx[jx.abs_diff(ix)];
                        s += g * h;
                        w += g;
                    }
                }
                num[ix] = s;
                den[ix] = w;
            }
        });

    // y pass, row-wise so that memory is read contiguously.
    let mut out = vec![0.0; nx * ny];
    out.par_chunks_mut(nx)
        .enumerate()
        .for_each(|(iy, out_row)| {
            let mut num = vec![0.0; nx];
            let mut den = vec![0.0; nx];
            let lo = iy.saturating_sub(gy.len() - 1);
            let hi = (iy + gy.len()).min(ny);
            for jy in lo..hi {
                let g = gy[jy.abs_diff(iy)];
                let src = jy * nx..(jy + 1) * nx;
                for ((n, d), (&a, &b)) in num
                    .iter_mut()
                    .zip(den.iter_mut())
                    .zip(num_x[src.clone()].iter().zip(&den_x[src]))
                {
                    *n += g * a;
                    *d += g * b;
                }
            }
            let z_row = &z[iy * nx..(iy + 1) * nx];
            for (ix, o) in out_row.iter_mut().enumerate() {
                // A valid point has at least its own weight g_0² = 1 in the denominator.
                *o = if z_row[ix].is_nan() {
                    f64::NAN
                } else {
                    num[ix] / den[ix]
                };
            }
        });
    Array2::from_shape_vec((ny, nx), out).expect("the output holds exactly nx·ny values")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alpha_gives_half_transmission() {
        let expected = (std::f64::consts::LN_2 / std::f64::consts::PI).sqrt();
        assert!((GAUSSIAN_ALPHA - expected).abs() < 1e-16);
    }

    #[test]
    fn rejects_bad_cutoffs() {
        let map = HeightMap::new(Array2::zeros((4, 4)), 1.0, 1.0).unwrap();
        assert!(matches!(
            gaussian_low_pass(&map, 0.0),
            Err(FilterError::BadCutoff { .. })
        ));
        assert!(matches!(
            gaussian_band_pass(&map, 2.0, 1.0),
            Err(FilterError::BadBand { .. })
        ));
    }
}
