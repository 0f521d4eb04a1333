//! Texture direction Std from the angular power spectrum.
//!
//! The angular power spectrum (ISO 25178-2:2012, after Stout et al., *The development of methods
//! for the characterisation of roughness in three dimensions*, 1993) sums the 2-D PSD over
//! wavevector directions: `APS(θ) = Σ_{modes with arg q ∈ θ ± ½°} C(q)` for `0 < |q| ≤ q_N`,
//! `q_N = min(π/dx, π/dy)`, in 1° bins over [0°, 180°) (`C(q) = C(−q)`). Most power sits in the
//! few long-wavelength modes, so a single bin of one random realisation is noisy; the peak is
//! taken on the APS smoothed by a circular moving average over ±5° (11 bins). A lay (grinding
//! marks) along direction `φ` puts its power at wavevectors normal to it, so
//!
//! **Std = (θ_peak + 90°) mod 180°**, the lay direction, counter-clockwise from the x axis.
//!
//! Instrument software differs in the reference axis (some measure from y); this crate always
//! measures from x. On isotropic surfaces the peak is dominated by the grid's lattice directions
//! (0°, 45°, 90°) and Std is not meaningful; `peak_share` (the share of the total power within
//! ±5° of the peak, 11/180 for an ideally isotropic spectrum) tells how dominant the direction is.

use std::f64::consts::PI;

use rayon::prelude::*;

use super::error::SpectralError;
use super::psd::{periodogram, Periodogram, Window};
use crate::surface::HeightMap;

/// Half width, in 1° bins, of the moving average applied before locating the peak.
pub const SMOOTHING_HALF_WIDTH: usize = 5;

/// Std and the angular power spectrum it comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureDirection {
    /// Std: lay direction, degrees from x in [0, 180).
    pub std_deg: f64,
    /// Wavevector direction of the spectral peak, degrees in [0, 180).
    pub spectrum_peak_deg: f64,
    /// Share of the total power within ±5° of the peak, in (0, 1] (11/180 ≈ 0.061 for an
    /// ideally isotropic spectrum).
    pub peak_share: f64,
    /// `APS` in 1° bins centred on 0°, 1°, …, 179°, normalised to sum 1.
    pub angular_spectrum: Vec<f64>,
}

/// The bin of a mode that is not counted.
const NO_BIN: u8 = u8::MAX;

/// The 1° bin of `arg q` of each mode of half-grid row `j` with `0 < |q| ≤ q_max`, [`NO_BIN`]
/// for the others and for modes without power (a synthetic surface's beyond its cutoff: no
/// angle needed).
fn angle_bins(p: &Periodogram, j: usize, q_max: f64) -> Vec<u8> {
    p.c.row(j)
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            if c == 0.0 {
                return NO_BIN;
            }
            let (qx, qy) = p.wavevector(j, i);
            let q = qx.hypot(qy);
            if q == 0.0 || q > q_max {
                return NO_BIN;
            }
            let degrees = qy.atan2(qx).to_degrees().rem_euclid(180.0);
            ((degrees.round() as usize) % 180) as u8
        })
        .collect()
}

/// Computes Std of a complete height map (see module docs).
pub fn texture_direction(
    map: &HeightMap,
    window: Window,
) -> Result<TextureDirection, SpectralError> {
    texture_direction_of(&periodogram(map, window)?, map)
}

/// [`texture_direction`] from a periodogram of `map` (one FFT shared by several statistics).
pub fn texture_direction_of(
    p: &Periodogram,
    map: &HeightMap,
) -> Result<TextureDirection, SpectralError> {
    let q_max = (PI / map.dx()).min(PI / map.dy());
    // The bins of the modes in parallel, then their power summed in row-major order.
    let bins: Vec<Vec<u8>> = (0..p.c.nrows())
        .into_par_iter()
        .map(|j| angle_bins(p, j, q_max))
        .collect();
    let mut aps = vec![0.0; 180];
    for (bins, power) in bins.iter().zip(p.c.rows()) {
        for (i, (&bin, c)) in bins.iter().zip(power).enumerate() {
            if bin != NO_BIN {
                aps[usize::from(bin)] += p.multiplicity(i) * c;
            }
        }
    }
    let total: f64 = aps.iter().sum();
    if total.is_nan() || total <= 0.0 {
        return Err(SpectralError::FlatSurface);
    }
    aps.iter_mut().for_each(|v| *v /= total);
    let smoothed: Vec<f64> = (0..180)
        .map(|k| {
            (k + 180 - SMOOTHING_HALF_WIDTH..=k + 180 + SMOOTHING_HALF_WIDTH)
                .map(|m| aps[m % 180])
                .sum::<f64>()
        })
        .collect();
    let (peak, share) =
        smoothed.iter().enumerate().fold(
            (0, f64::MIN),
            |best, (k, v)| if *v > best.1 { (k, *v) } else { best },
        );
    Ok(TextureDirection {
        std_deg: ((peak + 90) % 180) as f64,
        spectrum_peak_deg: peak as f64,
        peak_share: share,
        angular_spectrum: aps,
    })
}
