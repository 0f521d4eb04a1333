//! A twin whose 2-D power spectrum is the measured one ([`spectrum_twin`]): the measured spectra
//! ([`super::MeasuredSpectrum`]) averaged and resampled onto the twin's wavevectors, with random
//! phases — a phase-randomised ("isospectral") surrogate of the measurement (Theiler, Eubank,
//! Longtin, Galdrikian & Farmer, *Physica D* 58 (1992) 77), extended to the twin's own size and
//! spacing.
//!
//! # Spectrum on the twin's grid
//! The twin is periodic, `Lx × Ly` on `nx × ny` points, with wavevectors
//! `q = (2π i/Lx, 2π j/Ly)`. At each of them the spectrum is
//! * the **mean of the measured spectra that resolve it** (each interpolated there, see
//!   [`super::MeasuredSpectrum::at`]), equal weights per file;
//! * where none does, **zero** when it is longer than every map holds (no measurement shows
//!   those wavelengths, and a self-affine law has no roll-off to stop it), and, when it is
//!   shorter than every map's sampling, zero ([`Extrapolation::Zero`]) or the mean of the maps'
//!   fitted power-law tails ([`Extrapolation::PowerLaw`]);
//! * zero beyond the optional short-wavelength cutoff `|q| > 2π/λs`.
//!
//! On the Nyquist row and column the aliased wavevectors `±q_N` are one mode: its value is the
//! mean over them.
//!
//! # Amplitudes, Sq and phases
//! Each mode of the half spectrum gets the fixed amplitude `|a(q)| = s √(C(q)/A)` (`A = Lx·Ly`),
//! so that the twin's periodogram `A |a|²` equals `s² C(q)` at every mode — not only on
//! average — and its Sq is `s · √(Σ_q C(q)/A)` exactly (Parseval). The scale `s` brings Sq to
//! the requested value, or, with `sq: None`, to the measurement's: the quadratic mean
//! `√(mean Sq_f²)` of the maps' Sq (the Sq of their averaged spectrum; one map: its Sq). The
//! spectrum's shape comes from the windowed periodogram, its level from the Sq of all the map's
//! points, which the window weighs unequally: where the Hann estimate of the power differs from
//! the map's Sq² (see [`super::MeasuredSpectrum`]), the twin's periodogram is the measured one
//! times `s²`, reported.
//!
//! The phase `φ(q)` is uniform in `[0, 2π)`: ChaCha8 (`rand_chacha`, value-stable across
//! platforms) seeded with the little-endian `seed` in the first 8 key bytes, as the synthetic
//! surfaces; the mode `(kx, ky)` draws the `kx`-th 64-bit value of stream `ky` in zigzag order
//! (0, −1, 1, −2, … → 0, 1, 2, 3, …), so phases do not depend on the thread count nor on the
//! grid: twins of one seed on grids of the same size share the phases of the modes they both
//! hold. The modes that are their own conjugate (`kx ∈ {0, nx/2}`, `ky ∈ {0, ny/2}`) are real
//! with a random sign (the draw below or above ½); on the `kx = 0` and `kx = nx/2` columns the
//! mode at `−ky` is the conjugate of the one at `ky` (Hermitian symmetry: real heights). The
//! heights are the inverse FFT, shifted to zero mean and scaled to the Sq exactly (removing
//! round-off only).

use std::f64::consts::PI;

use ndarray::Array2;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use realfft::num_complex::Complex64;

use super::spectrum::{check_compatible, MeasuredSpectrum, SpectrumTwinError, SpectrumValue};
use crate::fft2::inverse_real_2d;
use crate::surface::synthetic::{SyntheticError, LENGTH_RANGE, MAX_SYNTHETIC_POINTS, MIN_SQ};
use crate::surface::HeightMap;

/// What the twin holds at wavevectors shorter than every measured map's sampling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Extrapolation {
    /// Nothing: the twin is band-limited to what was measured.
    #[default]
    Zero,
    /// The maps' fitted power-law tails ([`MeasuredSpectrum::with_tail`]), averaged.
    PowerLaw,
}

impl Extrapolation {
    /// The name a study writes and a table holds.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Zero => "zero",
            Self::PowerLaw => "power_law",
        }
    }
}

/// Grid, Sq and randomness of a spectrum twin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectrumTwinSpec {
    pub nx: usize,
    pub ny: usize,
    /// m
    pub lx: f64,
    /// m
    pub ly: f64,
    /// Target Sq, m, between [`MIN_SQ`] and the shorter side (as a synthetic surface's); `None`:
    /// the measurement's (module docs), at least [`MIN_SQ`].
    pub sq: Option<f64>,
    /// Optional short-wavelength cutoff λs, m.
    pub short_wavelength_cutoff: Option<f64>,
    pub extrapolation: Extrapolation,
    pub seed: u64,
}

/// Where a twin mode's spectrum came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Origin {
    Measured,
    Shorter,
    Longer,
    Cut,
}

/// Modes of the twin's full spectrum (both signs of `qx`, without `q = 0`) by origin, and the
/// share of the twin's Sq² each carries.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ModeTally {
    /// Interpolated from a measured spectrum.
    pub measured: usize,
    /// Shorter than every map's sampling: extrapolated (zero or the tail).
    pub shorter: usize,
    /// Longer than every map: zero.
    pub longer: usize,
    /// Beyond the short-wavelength cutoff: zero.
    pub cut: usize,
    /// Share of the twin's Sq² in the extrapolated (`shorter`) modes.
    pub extrapolated_power_share: f64,
}

/// A spectrum twin and its provenance. The share of the measured spectrum's power the twin's
/// grid holds is `(spectrum_sq / measured_spectrum_sq)²`; the scale applied to it,
/// `sq / spectrum_sq`.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectrumTwin {
    pub surface: HeightMap,
    /// The measurement's Sq, `√(mean Sq_f²)` of the maps, m.
    pub measured_sq: f64,
    /// The Sq of the measured spectra, `√(mean_f Σ_q C_f / A_f)`, m: `measured_sq` as the Hann
    /// estimate sees it ([`super::MeasuredSpectrum::spectrum_sq`]).
    pub measured_spectrum_sq: f64,
    /// Sq of the spectrum on the twin's grid before scaling, m (below `measured_spectrum_sq`
    /// when the grid misses measured wavelengths).
    pub spectrum_sq: f64,
    /// The twin's Sq, m.
    pub sq: f64,
    pub modes: ModeTally,
}

impl SpectrumTwinSpec {
    /// Checks the grid, size, cutoff and Sq (when given).
    pub fn validate(&self) -> Result<(), SpectrumTwinError> {
        let invalid = |name: &'static str, value: String, expected: String| {
            Err(SpectrumTwinError::InvalidParameter {
                name,
                value,
                expected,
            })
        };
        for (name, n) in [("nx", self.nx), ("ny", self.ny)] {
            if n < 2 {
                return invalid(name, n.to_string(), "an integer ≥ 2 (points)".into());
            }
        }
        if self
            .nx
            .checked_mul(self.ny)
            .is_none_or(|n| n > MAX_SYNTHETIC_POINTS)
        {
            return Err(SyntheticError::TooLarge {
                nx: self.nx,
                ny: self.ny,
                max: MAX_SYNTHETIC_POINTS,
            }
            .into());
        }
        let (low, high) = LENGTH_RANGE;
        for (name, l) in [("lx", self.lx), ("ly", self.ly)] {
            if !(low..=high).contains(&l) {
                return invalid(name, format!("{l:e} m"), format!("{low:e} m to {high:e} m"));
            }
        }
        if let Some(sq) = self.sq {
            self.check_sq(sq)?;
        }
        if let Some(cutoff) = self.short_wavelength_cutoff {
            let (lo, hi) = (
                (self.lx / self.nx as f64).min(self.ly / self.ny as f64),
                self.lx.min(self.ly),
            );
            if !(cutoff >= lo && cutoff < hi) {
                return invalid(
                    "short_wavelength_cutoff",
                    format!("{cutoff:e} m"),
                    format!("min(dx, dy) = {lo:e} m ≤ λs < min(lx, ly) = {hi:e} m"),
                );
            }
        }
        Ok(())
    }

    /// An Sq (m) between [`MIN_SQ`] and the twin's shorter side.
    fn check_sq(&self, sq: f64) -> Result<(), SpectrumTwinError> {
        let max = self.lx.min(self.ly);
        if (MIN_SQ..=max).contains(&sq) {
            return Ok(());
        }
        Err(SpectrumTwinError::InvalidParameter {
            name: "sq",
            value: format!("{sq:e} m"),
            expected: format!("{MIN_SQ:e} m ≤ Sq ≤ min(lx, ly) = {max:e} m"),
        })
    }
}

/// The twin of `spectra` on `spec`'s grid (module docs).
pub fn spectrum_twin(
    spectra: &[MeasuredSpectrum],
    spec: &SpectrumTwinSpec,
) -> Result<SpectrumTwin, SpectrumTwinError> {
    if spectra.is_empty() {
        return Err(SpectrumTwinError::NoMaps);
    }
    spec.validate()?;
    if spec.extrapolation == Extrapolation::PowerLaw {
        if let Some(index) = spectra.iter().position(|s| s.tail().is_none()) {
            return Err(SpectrumTwinError::InvalidParameter {
                name: "extrapolation",
                value: format!("power_law (measured map {index} has no fitted tail)"),
                expected: "`zero`, or a power-law tail fitted to every map".into(),
            });
        }
    }
    check_compatible(spectra)?;
    let (density, modes) = resample(spectra, spec);
    let area = spec.lx * spec.ly;
    let quadratic_mean = |f: fn(&MeasuredSpectrum) -> f64| {
        (spectra.iter().map(|s| f(s).powi(2)).sum::<f64>() / spectra.len() as f64).sqrt()
    };
    let measured_sq = quadratic_mean(MeasuredSpectrum::sq);
    let power = total_power(&density, spec.nx);
    let spectrum_sq = (power / area).sqrt();
    if !(spectrum_sq > 0.0 && spectrum_sq.is_finite()) {
        return Err(nothing_resolved(spectra, spec));
    }
    // A given Sq is bounded as a synthetic surface's; the measurement's is what it is, if any.
    let sq = match spec.sq {
        Some(sq) => sq,
        None if measured_sq >= MIN_SQ && measured_sq.is_finite() => measured_sq,
        None => return Err(SpectrumTwinError::NoRoughness { sq: measured_sq }),
    };
    let scale = sq / spectrum_sq;
    let amplitude = density.mapv(|c| (c / area).sqrt() * scale);
    let mut z = random_phase_heights(&amplitude, spec.nx, spec.seed)?;
    let n = z.len() as f64;
    let mean = z.sum() / n;
    z.mapv_inplace(|v| v - mean);
    let rms = (z.iter().map(|v| v * v).sum::<f64>() / n).sqrt();
    if !(rms > 0.0 && rms.is_finite()) {
        return Err(SyntheticError::NoSpectralContent.into());
    }
    z.mapv_inplace(|v| v * (sq / rms));
    let surface = HeightMap::new(z, spec.lx / spec.nx as f64, spec.ly / spec.ny as f64)
        .map_err(SyntheticError::from)?;
    Ok(SpectrumTwin {
        surface,
        measured_sq,
        measured_spectrum_sq: quadratic_mean(MeasuredSpectrum::spectrum_sq),
        spectrum_sq,
        sq,
        modes: ModeTally {
            extrapolated_power_share: modes.extrapolated_power_share / power,
            ..modes
        },
    })
}

fn nothing_resolved(spectra: &[MeasuredSpectrum], spec: &SpectrumTwinSpec) -> SpectrumTwinError {
    let bands: Vec<[f64; 2]> = spectra.iter().map(MeasuredSpectrum::band).collect();
    let (dx, dy) = (spec.lx / spec.nx as f64, spec.ly / spec.ny as f64);
    SpectrumTwinError::NothingResolved {
        twin: [2.0 * dx.max(dy), spec.lx.max(spec.ly)],
        measured: [
            bands.iter().map(|b| b[0]).fold(f64::INFINITY, f64::min),
            bands.iter().map(|b| b[1]).fold(0.0, f64::max),
        ],
    }
}

/// Signed wavenumber index of half-spectrum row `j` of `n` rows.
fn signed(j: usize, n: usize) -> i64 {
    if 2 * j <= n {
        j as i64
    } else {
        j as i64 - n as i64
    }
}

/// Multiplicity of half-spectrum column `i` in the full spectrum (module docs of
/// [`crate::surface::spectral::psd`]).
fn multiplicity(i: usize, nx: usize) -> f64 {
    if i == 0 || 2 * i == nx {
        1.0
    } else {
        2.0
    }
}

/// `Σ_q C(q)` over the full spectrum, m⁴.
fn total_power(density: &Array2<f64>, nx: usize) -> f64 {
    density
        .indexed_iter()
        .map(|((_, i), c)| multiplicity(i, nx) * c)
        .sum()
}

/// The averaged measured spectrum on the twin's half spectrum `[ny, nx/2 + 1]` (m⁴) and the
/// tally of the modes' origins (`extrapolated_power_share` still in m⁴, not yet a share).
fn resample(spectra: &[MeasuredSpectrum], spec: &SpectrumTwinSpec) -> (Array2<f64>, ModeTally) {
    let (nx, ny) = (spec.nx, spec.ny);
    let nxh = nx / 2 + 1;
    let (dqx, dqy) = (2.0 * PI / spec.lx, 2.0 * PI / spec.ly);
    let rows: Vec<Vec<(f64, Origin)>> = (0..ny)
        .into_par_iter()
        .map(|j| {
            let qy = signed(j, ny) as f64 * dqy;
            (0..nxh)
                .map(|i| {
                    let qx = i as f64 * dqx;
                    let xs: &[f64] = if 2 * i == nx { &[qx, -qx] } else { &[qx] };
                    let ys: &[f64] = if 2 * j == ny { &[qy, -qy] } else { &[qy] };
                    aliased_mean(spectra, spec, xs, ys)
                })
                .collect()
        })
        .collect();
    let mut density = Array2::zeros((ny, nxh));
    let mut tally = ModeTally::default();
    for (j, row) in rows.iter().enumerate() {
        for (i, &(c, origin)) in row.iter().enumerate() {
            density[[j, i]] = c;
            if i == 0 && j == 0 {
                continue;
            }
            let m = multiplicity(i, nx);
            let count = match origin {
                Origin::Measured => &mut tally.measured,
                Origin::Shorter => {
                    tally.extrapolated_power_share += m * c;
                    &mut tally.shorter
                }
                Origin::Longer => &mut tally.longer,
                Origin::Cut => &mut tally.cut,
            };
            *count += m as usize;
        }
    }
    (density, tally)
}

/// The mean of the spectrum over the aliased wavevectors `xs × ys` of one mode; its origin is
/// that of the first one not measured.
fn aliased_mean(
    spectra: &[MeasuredSpectrum],
    spec: &SpectrumTwinSpec,
    xs: &[f64],
    ys: &[f64],
) -> (f64, Origin) {
    let mut sum = 0.0;
    let mut origin = Origin::Measured;
    for &qx in xs {
        for &qy in ys {
            let (c, o) = spectrum_at(spectra, spec, qx, qy);
            sum += c;
            if origin == Origin::Measured {
                origin = o;
            }
        }
    }
    (sum / (xs.len() * ys.len()) as f64, origin)
}

/// The twin's spectrum at one wavevector (module docs).
fn spectrum_at(
    spectra: &[MeasuredSpectrum],
    spec: &SpectrumTwinSpec,
    qx: f64,
    qy: f64,
) -> (f64, Origin) {
    let q = qx.hypot(qy);
    if spec
        .short_wavelength_cutoff
        .is_some_and(|cutoff| q > 2.0 * PI / cutoff)
    {
        return (0.0, Origin::Cut);
    }
    let mut sum = 0.0;
    let mut count = 0usize;
    let mut longer = false;
    for s in spectra {
        match s.at(qx, qy) {
            SpectrumValue::Measured(c) => {
                sum += c;
                count += 1;
            }
            SpectrumValue::LongerThanMeasured => longer = true,
            SpectrumValue::ShorterThanMeasured => {}
        }
    }
    if count > 0 {
        return (sum / count as f64, Origin::Measured);
    }
    if longer {
        return (0.0, Origin::Longer);
    }
    let tail = match spec.extrapolation {
        Extrapolation::Zero => 0.0,
        Extrapolation::PowerLaw => {
            spectra.iter().filter_map(|s| s.tail_at(q)).sum::<f64>() / spectra.len() as f64
        }
    };
    (tail, Origin::Shorter)
}

/// The ChaCha stream of signed wavenumber `ky`: 0, −1, 1, −2, … → 0, 1, 2, 3, ….
fn stream(ky: i64) -> u64 {
    if ky >= 0 {
        2 * ky as u64
    } else {
        2 * ky.unsigned_abs() - 1
    }
}

/// A uniform deviate in `[0, 1)` from the top 53 bits of a 64-bit draw.
fn uniform(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// Heights from the half spectrum of amplitudes `[ny, nx/2 + 1]` with random phases (module
/// docs).
fn random_phase_heights(
    amplitude: &Array2<f64>,
    nx: usize,
    seed: u64,
) -> Result<Array2<f64>, SyntheticError> {
    let (ny, nxh) = amplitude.dim();
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&seed.to_le_bytes());
    let base = ChaCha8Rng::from_seed(key);
    let hermitian_column = |i: usize| i == 0 || 2 * i == nx;
    let mut modes = vec![Complex64::new(0.0, 0.0); ny * nxh];
    modes.par_chunks_mut(nxh).enumerate().for_each(|(j, row)| {
        let ky = signed(j, ny);
        let mut rng = base.clone();
        rng.set_stream(stream(ky));
        for (i, mode) in row.iter_mut().enumerate() {
            let own = uniform(&mut rng);
            let a = amplitude[[j, i]];
            *mode = if hermitian_column(i) && (j == 0 || 2 * j == ny) {
                Complex64::new(if own < 0.5 { a } else { -a }, 0.0)
            } else if hermitian_column(i) && ky < 0 {
                // The conjugate of the mode at `−ky`: its draw, amplitude and opposite phase.
                let mut partner = base.clone();
                partner.set_stream(stream(-ky));
                partner.set_word_pos(2 * i as u128);
                let phase = uniform(&mut partner);
                Complex64::from_polar(amplitude[[ny - j, i]], -2.0 * PI * phase)
            } else {
                Complex64::from_polar(a, 2.0 * PI * own)
            };
        }
    });
    let half = Array2::from_shape_vec((ny, nxh), modes)
        .map_err(|e| crate::fft2::FftFailure::new(e.to_string()))?;
    Ok(inverse_real_2d(&half, nx)?)
}
