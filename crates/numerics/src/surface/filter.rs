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
//! of the centre, so truncation changes the transmission by less than 1e-5; a shorter truncation at
//! ±0.5 λ, also in use, would drop about 0.8 % of the weight).
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

/// Symmetric sampled weights `g_{−w}..=g_w` for spacing `spacing` on an axis of `n` points, with
/// `w = min(⌊λ/d⌋, n − 1)`.
fn kernel(cutoff: f64, spacing: f64, n: usize) -> Vec<f64> {
    let reach = (KERNEL_HALF_WIDTH_IN_CUTOFFS * cutoff / spacing).floor();
    let width = if reach < (n - 1) as f64 {
        reach as usize
    } else {
        n - 1
    };
    let scale = GAUSSIAN_ALPHA * cutoff;
    (0..=2 * width)
        .map(|i| {
            let t = (i as f64 - width as f64) * spacing / scale;
            (-std::f64::consts::PI * t * t).exp()
        })
        .collect()
}

/// `out[i] = Σ_k kernel[k] · src[i + k − w]` over the indices inside `src` (zero beyond the ends).
fn convolve_line(src: &[f64], kernel: &[f64], out: &mut [f64]) {
    let n = src.len();
    let w = kernel.len() / 2;
    for (i, o) in out.iter_mut().enumerate() {
        let lo = i.saturating_sub(w);
        let hi = (i + w + 1).min(n);
        let k0 = lo + w - i;
        *o = dot(&src[lo..hi], &kernel[k0..k0 + (hi - lo)]);
    }
}

/// Dot product with four interleaved partial sums (vectorisable, deterministic order).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (a4, b4) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = a4
        .remainder()
        .iter()
        .zip(b4.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in a4.zip(b4) {
        for lane in 0..4 {
            acc[lane] += x[lane] * y[lane];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Normalised separable Gaussian convolution of the valid heights; `NaN` at missing points.
fn normalised_gaussian(map: &HeightMap, cutoff: f64) -> Array2<f64> {
    let (nx, ny) = (map.nx(), map.ny());
    // Row-major copy (x fastest) with missing points as 0 (their weight is 0 in the denominator).
    let z: Vec<f64> = map.heights().iter().copied().collect();
    let masked: Vec<f64> = z
        .iter()
        .map(|&h| if h.is_nan() { 0.0 } else { h })
        .collect();
    let has_missing = z.iter().any(|h| h.is_nan());
    let gx = kernel(cutoff, map.dx(), nx);
    let gy = kernel(cutoff, map.dy(), ny);
    // Denominators of a line without missing points: the kernel mass inside the grid.
    let mut norm_x = vec![0.0; nx];
    convolve_line(&vec![1.0; nx], &gx, &mut norm_x);
    let mut norm_y = vec![0.0; ny];
    convolve_line(&vec![1.0; ny], &gy, &mut norm_y);

    // x pass: numerator Σ g z m and (only where a row has missing points) denominator Σ g m.
    let mut num_x = vec![0.0; nx * ny];
    let mut den_x = if has_missing {
        vec![0.0; nx * ny]
    } else {
        Vec::new()
    };
    num_x
        .par_chunks_mut(nx)
        .zip(masked.par_chunks(nx))
        .for_each(|(num, row)| convolve_line(row, &gx, num));
    if has_missing {
        den_x
            .par_chunks_mut(nx)
            .zip(z.par_chunks(nx))
            .for_each(|(den, row)| {
                if row.iter().any(|h| h.is_nan()) {
                    let mask: Vec<f64> = row.iter().map(|h| f64::from(!h.is_nan())).collect();
                    convolve_line(&mask, &gx, den);
                } else {
                    den.copy_from_slice(&norm_x);
                }
            });
    }

    // y pass, row-wise so that memory is read contiguously.
    let half_y = gy.len() / 2;
    let mut out = vec![0.0; nx * ny];
    out.par_chunks_mut(nx)
        .enumerate()
        .for_each(|(iy, out_row)| {
            let lo = iy.saturating_sub(half_y);
            let hi = (iy + half_y + 1).min(ny);
            let mut num = vec![0.0; nx];
            let mut den = if has_missing {
                vec![0.0; nx]
            } else {
                norm_x.iter().map(|v| v * norm_y[iy]).collect()
            };
            for jy in lo..hi {
                let g = gy[jy + half_y - iy];
                let src = jy * nx..(jy + 1) * nx;
                for (n, &a) in num.iter_mut().zip(&num_x[src.clone()]) {
                    *n += g * a;
                }
                if has_missing {
                    for (d, &b) in den.iter_mut().zip(&den_x[src]) {
                        *d += g * b;
                    }
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
