//! The measured 2-D power spectrum a spectrum twin reproduces ([`MeasuredSpectrum`]), its value
//! at any wavevector, and the checks that the spectra of several files can be averaged
//! ([`check_compatible`]).
//!
//! # Estimate
//! The 2-D periodogram of the complete, preprocessed map with the separable Hann window,
//! `C(q) = A |Z_w(q)|² / (N² ⟨w²⟩)` in m⁴ ([`crate::surface::spectral::periodogram`], the
//! convention of the `surfaces` PSD of a measured map; the window suppresses the leakage of a
//! non-periodic map's edges), on the map's own wavevectors `q = (2π i/Lx, 2π j/Ly)`. The
//! `q = 0` value is set to zero (the twin has zero mean). `Σ_q C / A` estimates the map's Sq²
//! ([`MeasuredSpectrum::spectrum_sq`]); the window weighs the map's centre (at the edges the
//! weight falls to zero), so on a map whose roughness varies across it, or that holds few
//! correlation lengths, the estimate differs from the map's Sq by several per cent (−10 % on the
//! shipped Alicona crop, whose centre is smoother than its edges).
//!
//! # Value at a wavevector ([`MeasuredSpectrum::at`])
//! With `C(−q) = C(q)` (a real map) every wavevector is taken to `qx ≥ 0`. In units of the
//! map's wavenumber spacing, `u = qx Lx / 2π`, `v = qy Ly / 2π`, the wavevector is
//! * **resolved** when `u ≤ ⌊nx/2⌋`, `|v| ≤ ⌊ny/2⌋` (inside the map's Nyquist rectangle) and it
//!   is not in the cell around the origin (`u < 1` and `|v| < 1`: wavelengths longer than the
//!   map along both axes, which it does not hold); its value is the **bilinear interpolation of
//!   C** (linear in C, so the interpolated density keeps the periodogram's expectation) between
//!   the four periodogram values around it;
//! * **longer than the map** in the origin cell ([`SpectrumValue::LongerThanMeasured`]);
//! * **shorter than the map's sampling** outside the Nyquist rectangle
//!   ([`SpectrumValue::ShorterThanMeasured`]), where the caller extrapolates: zero, or the
//!   map's power-law tail ([`MeasuredSpectrum::with_tail`]) `C(q) = C₁ |q|^s`, an isotropic
//!   continuation of the radial PSD fitted over the band where it is a power law.
//!
//! # Compatibility of several files ([`check_compatible`])
//! Spectra of several measurements are averaged only if they describe one surface in the same
//! units: every pair of maps must share a band of wavelengths (between 2 pixels and the map's
//! longer side; disjoint bands mean a lateral scale off by orders of magnitude), and over the
//! annulus of wavenumbers every map resolves along both axes their rms heights
//! (`√(Σ C / A)` over the annulus) must agree within [`MAX_BAND_RMS_RATIO`] (a ratio beyond it
//! means a height unit off, or different surfaces).

use std::f64::consts::PI;

use super::format_micrometres;
use crate::surface::spectral::{periodogram, HurstFit, Periodogram, SpectralError, Window};
use crate::surface::synthetic::SyntheticError;
use crate::surface::HeightMap;

/// Largest ratio between the rms heights of two files over their common band: a factor of 10
/// in height (100 in power) is beyond two measurements of one surface and typical of a height
/// unit off by 10³ or 10⁶.
pub const MAX_BAND_RMS_RATIO: f64 = 10.0;

/// The 2-D power spectrum of one measured map (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredSpectrum {
    periodogram: Periodogram,
    /// Rows of the map.
    ny: usize,
    /// Size `(Lx, Ly)` of the map, m.
    size: (f64, f64),
    /// Spacing `(dx, dy)` of the map, m.
    spacing: (f64, f64),
    /// Sq of the map about its mean, m.
    sq: f64,
    /// `√(Σ_q C / A)`, m.
    spectrum_sq: f64,
    tail: Option<HurstFit>,
}

/// A measured spectrum's value at one wavevector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SpectrumValue {
    /// Interpolated from the periodogram, m⁴.
    Measured(f64),
    /// The wavevector is shorter than the map's sampling resolves (outside its Nyquist
    /// rectangle).
    ShorterThanMeasured,
    /// The wavevector's wavelength exceeds the map along both axes.
    LongerThanMeasured,
}

/// Why a spectrum twin could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpectrumTwinError {
    #[error("a spectrum twin needs at least one measured map")]
    NoMaps,
    #[error(transparent)]
    Spectral(#[from] SpectralError),
    #[error(
        "measured maps {first} and {second} share no band of wavelengths (map {first}: {} to {}, \
         map {second}: {} to {}): their spectra cannot be averaged; check their lateral units \
         (pixel size)",
        format_micrometres(bands[0][0]), format_micrometres(bands[0][1]),
        format_micrometres(bands[1][0]), format_micrometres(bands[1][1])
    )]
    NoCommonBand {
        first: usize,
        second: usize,
        /// `[[λ_short, λ_long]; 2]` of the two maps, m.
        bands: [[f64; 2]; 2],
    },
    #[error(
        "measured maps {first} and {second} differ by a factor of {ratio:.3} in rms height over \
         the wavelengths both resolve ({} to {}: {:e} m against {:e} m), more than the {} two \
         measurements of one surface can differ by: check their height units, or twin them \
         separately",
        format_micrometres(band[0]), format_micrometres(band[1]), rms[0], rms[1],
        MAX_BAND_RMS_RATIO
    )]
    SpectraDisagree {
        first: usize,
        second: usize,
        ratio: f64,
        /// `[λ_short, λ_long]` of the common annulus, m.
        band: [f64; 2],
        /// rms heights of the two maps over it, m.
        rms: [f64; 2],
    },
    #[error(
        "the twin's grid holds no wavevector the measurement resolved (the twin's wavelengths \
         {} to {}, the measurement's {} to {}): choose a size and grid that overlap them",
        format_micrometres(twin[0]), format_micrometres(twin[1]),
        format_micrometres(measured[0]), format_micrometres(measured[1])
    )]
    NothingResolved {
        /// `[2·max(dx, dy), max(Lx, Ly)]` of the twin, m.
        twin: [f64; 2],
        /// The widest `[λ_short, λ_long]` of the measured maps, m.
        measured: [f64; 2],
    },
    #[error(
        "the measured maps have Sq = {sq:e} m after preprocessing, below {:e} m: no roughness \
         is left to twin (did the form removal take all of it?)",
        crate::surface::synthetic::MIN_SQ
    )]
    NoRoughness {
        /// Quadratic mean of the maps' Sq, m.
        sq: f64,
    },
    #[error("spectrum twin: `{name}` = {value} is out of range, expected {expected}")]
    InvalidParameter {
        name: &'static str,
        value: String,
        expected: String,
    },
    #[error(transparent)]
    Synthetic(#[from] SyntheticError),
}

impl MeasuredSpectrum {
    /// The Hann-window periodogram of a complete map (module docs; a height map has at least
    /// 2 × 2 points, so a line profile never gets here).
    pub fn of_map(map: &HeightMap) -> Result<Self, SpectrumTwinError> {
        let mut periodogram = periodogram(map, Window::Hann)?;
        periodogram.c[[0, 0]] = 0.0;
        let z = map.heights();
        let n = z.len() as f64;
        let mean = z.sum() / n;
        let sq = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
        let power: f64 = periodogram
            .c
            .indexed_iter()
            .map(|((_, i), c)| periodogram.multiplicity(i) * c)
            .sum();
        let (lx, ly) = map.size();
        Ok(Self {
            periodogram,
            ny: map.ny(),
            size: (lx, ly),
            spacing: (map.dx(), map.dy()),
            sq,
            spectrum_sq: (power / (lx * ly)).sqrt(),
            tail: None,
        })
    }

    /// The same spectrum, continued beyond its sampling by the power law `fit` (the radial
    /// PSD's fit over a band where it is one): `C(q) = fit.prefactor · |q|^fit.slope`.
    pub fn with_tail(mut self, fit: HurstFit) -> Self {
        self.tail = Some(fit);
        self
    }

    /// The power-law tail, when one was given.
    pub fn tail(&self) -> Option<&HurstFit> {
        self.tail.as_ref()
    }

    /// Sq of the map about its mean, m.
    pub fn sq(&self) -> f64 {
        self.sq
    }

    /// The Sq the spectrum holds, `√(Σ_q C / A)`, m (module docs).
    pub fn spectrum_sq(&self) -> f64 {
        self.spectrum_sq
    }

    /// Wavelengths the map resolves, `[λ_short, λ_long] = [2·max(dx, dy), max(Lx, Ly)]`, m.
    pub fn band(&self) -> [f64; 2] {
        let (dx, dy) = self.spacing;
        let (lx, ly) = self.size;
        [2.0 * dx.max(dy), lx.max(ly)]
    }

    /// The power-law tail at wavenumber `q` (rad/m), m⁴; `None` without a tail.
    pub fn tail_at(&self, q: f64) -> Option<f64> {
        self.tail.map(|fit| fit.prefactor * q.powf(fit.slope))
    }

    /// The spectrum at wavevector `(qx, qy)` (rad/m), see the module docs.
    pub fn at(&self, qx: f64, qy: f64) -> SpectrumValue {
        let (qx, qy) = if qx < 0.0 { (-qx, -qy) } else { (qx, qy) };
        let p = &self.periodogram;
        let u = qx / p.dqx;
        let v = qy / p.dqy;
        let (u_max, v_max) = ((p.nx / 2) as f64, (self.ny / 2) as f64);
        // Round-off in `q / dq` must not move a wavevector on the rectangle's edge outside it.
        let slack = 1.0 + 1e-9;
        if u > u_max * slack || v.abs() > v_max * slack {
            return SpectrumValue::ShorterThanMeasured;
        }
        let inside_origin_cell = |w: f64| w.abs() < 1.0 - 1e-9;
        if inside_origin_cell(u) && inside_origin_cell(v) {
            if u == 0.0 && v == 0.0 {
                return SpectrumValue::Measured(0.0);
            }
            return SpectrumValue::LongerThanMeasured;
        }
        let (u, v) = (u.min(u_max), v.clamp(-v_max, v_max));
        let (i0, k0) = (u.floor(), v.floor());
        let (tu, tv) = (u - i0, v - k0);
        let column = |i: f64| (i as usize).min(p.nx / 2);
        let row = |k: f64| {
            let k = k.clamp(-v_max, v_max) as isize;
            if k >= 0 {
                k as usize
            } else {
                (self.ny as isize + k) as usize
            }
        };
        let (c0, c1) = (column(i0), column(i0 + 1.0));
        let (r0, r1) = (row(k0), row(k0 + 1.0));
        let c = &p.c;
        let value = (1.0 - tv) * ((1.0 - tu) * c[[r0, c0]] + tu * c[[r0, c1]])
            + tv * ((1.0 - tu) * c[[r1, c0]] + tu * c[[r1, c1]]);
        SpectrumValue::Measured(value)
    }

    /// rms height (m) over the wavenumbers `q_low ≤ |q| ≤ q_high`: `√(Σ C / A)` over the
    /// periodogram's modes in that annulus (both signs of `qx`).
    fn band_rms(&self, q_low: f64, q_high: f64) -> f64 {
        let p = &self.periodogram;
        let mut sum = 0.0;
        for ((j, i), c) in p.c.indexed_iter() {
            let (qx, qy) = p.wavevector(j, i);
            let q = qx.hypot(qy);
            if q >= q_low && q <= q_high {
                sum += p.multiplicity(i) * c;
            }
        }
        (sum / (self.size.0 * self.size.1)).sqrt()
    }

    /// `[q_low, q_high]` (rad/m) of the wavenumbers this map resolves along both axes.
    fn annulus(&self) -> [f64; 2] {
        let (lx, ly) = self.size;
        let (dx, dy) = self.spacing;
        [2.0 * PI / lx.min(ly), (PI / dx).min(PI / dy)]
    }
}

/// Checks that the spectra can be averaged (module docs): every pair shares a band of
/// wavelengths, and over the annulus all of them resolve their rms heights agree within
/// [`MAX_BAND_RMS_RATIO`].
pub fn check_compatible(spectra: &[MeasuredSpectrum]) -> Result<(), SpectrumTwinError> {
    for (a, first) in spectra.iter().enumerate() {
        for (b, second) in spectra.iter().enumerate().skip(a + 1) {
            let (x, y) = (first.band(), second.band());
            if x[0].max(y[0]) >= x[1].min(y[1]) {
                return Err(SpectrumTwinError::NoCommonBand {
                    first: a,
                    second: b,
                    bands: [x, y],
                });
            }
        }
    }
    let q_low = spectra.iter().map(|s| s.annulus()[0]).fold(0.0, f64::max);
    let q_high = spectra
        .iter()
        .map(|s| s.annulus()[1])
        .fold(f64::INFINITY, f64::min);
    if spectra.len() < 2 || q_low >= q_high {
        return Ok(());
    }
    let rms: Vec<f64> = spectra.iter().map(|s| s.band_rms(q_low, q_high)).collect();
    let (low, high) = extreme_indices(&rms);
    let ratio = rms[high] / rms[low];
    if ratio > MAX_BAND_RMS_RATIO || !ratio.is_finite() {
        let (first, second) = (low.min(high), low.max(high));
        return Err(SpectrumTwinError::SpectraDisagree {
            first,
            second,
            ratio,
            band: [2.0 * PI / q_high, 2.0 * PI / q_low],
            rms: [rms[first], rms[second]],
        });
    }
    Ok(())
}

/// Indices of the smallest and largest value.
fn extreme_indices(values: &[f64]) -> (usize, usize) {
    let mut low = 0;
    let mut high = 0;
    for (i, v) in values.iter().enumerate() {
        if *v < values[low] {
            low = i;
        }
        if *v > values[high] {
            high = i;
        }
    }
    (low, high)
}
