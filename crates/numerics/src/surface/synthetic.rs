//! Synthetic periodic self-affine Gaussian random surfaces by spectral (Fourier) synthesis.
//!
//! # Power spectral density convention
//! For a periodic surface of size `Lx × Ly` on `nx × ny` points (`dx = Lx/nx`, `A = Lx·Ly`,
//! `N = nx·ny`) with discrete Fourier transform `Z(q) = Σ_r z(r) e^{−i q·r}`, the 2-D PSD is
//! `C(q) = A |Z(q)|² / N²` (m⁴), so that `Sq² = (1/A) Σ_q C(q) = ∫ C(q) d²q / (2π)²`
//! (Jacobs, Junge & Pastewka, *Surf. Topogr.: Metrol. Prop.* 5 (2017) 013001).
//!
//! # Model
//! Wavevectors are rotated into the texture frame `(u, v)`, `u` at `angle` θ from `x`:
//! `q_u = qx cos θ + qy sin θ`, `q_v = −qx sin θ + qy cos θ`. With roll-off wavelengths
//! `λ_u = correlation_length` and `λ_v = λ_u / aspect_ratio`, the dimensionless wavenumber is
//! `κ = √[(q_u λ_u / 2π)² + (q_v λ_v / 2π)²]` and
//!
//! ```text
//! C(q) = C0                      for κ < 1          (roll-off plateau)
//! C(q) = C0 · κ^−(2+2H)          for κ ≥ 1          (self-affine, Hurst exponent H)
//! C(q) = 0                       for |q| > 2π/λ_s   (optional short-wavelength cutoff)
//! C(0) = 0                                          (zero mean)
//! ```
//!
//! Isotropic surfaces (`anisotropy: None`) have `κ = |q|/q_r`, `q_r = 2π/λ_r`. An anisotropic
//! surface is the isotropic one stretched in the spectral domain: along `u` it is correlated over
//! `λ_u`, across it over `λ_v` (grinding marks along `u` have `aspect_ratio > 1`). `C0` follows
//! from the Sq normalisation, which is applied to the realised surface so its Sq is exact.
//!
//! # Roll-off wavelength vs measured correlation length
//! `correlation_length` is the roll-off wavelength `λ_r`, not an ACF decay length. The length a
//! measurement reports (the lag where the ACF first drops to 0.2, as for Sal) follows from the
//! model's ensemble ACF, [`model_autocorrelation`], on the same grid: for an isotropic surface
//! with `λ_r = L/16` on 512² it is ≈ 0.24 λ_r (H = 0.3), 0.28 λ_r (H = 0.5), 0.32 λ_r (H = 0.8),
//! 0.34 λ_r (H = 1). `crate::surface::twins` inverts this mapping numerically.
//!
//! # Synthesis
//! Each Fourier mode of the real-FFT half spectrum (`kx ≥ 0`) is a complex Gaussian with
//! `E|Z|² ∝ C(q)` (Box–Muller normal deviates). The modes that must be their own conjugate
//! (`kx ∈ {0, nx/2}` with `ky ∈ {0, ny/2}`) are real with the same variance; the remaining
//! `kx = 0` and `kx = nx/2` modes are set as conjugate pairs `Z(−ky) = Z(ky)*`, so the inverse
//! transform is exactly real (Hermitian symmetry). At the Nyquist row/column the aliased
//! wavevectors `±q_N` are one mode; its density is the mean of both. The surface is the inverse
//! FFT, shifted to zero mean and scaled to the target Sq. This is the random-amplitude
//! variant of the Fourier-filtering method (e.g. Persson et al., *J. Phys.: Condens. Matter* 17
//! (2005) R1), so heights are Gaussian and periodic in both directions.
//!
//! # Determinism
//! Random numbers come from ChaCha8 (`rand_chacha`, value-stable across platforms and versions
//! of the same major release), seeded with the little-endian `seed` in the first 8 key bytes;
//! the row of signed wavenumber `ky` uses ChaCha stream `zigzag(ky)` and mode `kx` its `kx`-th
//! pair of deviates, so the result does not depend on the thread count, and **the same seed gives
//! the same Fourier modes on every grid of the same size**: a surface on a coarse grid is exactly
//! the fine-grid surface without the modes the coarse grid cannot carry. With a
//! `short_wavelength_cutoff` the coarse grid resolves (λs > 2·dx of the coarse grid, so every
//! mode lies strictly inside its Nyquist band), coarse and fine grids sample one and the same
//! surface — what a resolution-convergence study needs.
//! The random stream is bit-identical everywhere; the heights are bit-identical for the same
//! build and platform, and across platforms equal up to floating-point round-off of the
//! platform's `ln`/`sin`/`cos` and FFT SIMD kernels (relative ~1e-15).

use std::f64::consts::{FRAC_1_SQRT_2, PI};

use ndarray::Array2;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use rayon::prelude::*;
use realfft::num_complex::Complex64;

use super::model_psd::ModelPsd;
use super::spectral::{InverseTransform, Periodogram, Window};
use super::{HeightMap, HeightMapError};
use crate::fft2::{inverse_real_2d, FftFailure};

/// Largest grid accepted (`nx·ny`), 16384² points: ~2 GiB of heights plus spectra.
pub const MAX_SYNTHETIC_POINTS: usize = 1 << 28;

/// Directional texture: the correlation (roll-off) length along the lay direction `u` is the
/// spec's `correlation_length`, across it (`v`) it is `correlation_length / aspect_ratio`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anisotropy {
    /// `λ_u / λ_v` (dimensionless, finite, > 0; > 1 means longer correlation along `u`).
    pub aspect_ratio: f64,
    /// Angle θ of the lay direction `u` from the x axis, counter-clockwise, radians (finite).
    pub angle: f64,
}

/// Parameters of a synthetic surface; see the module documentation for the model.
#[derive(Debug, Clone, PartialEq)]
pub struct SyntheticSurfaceSpec {
    /// Points along x (≥ 2).
    pub nx: usize,
    /// Points along y (≥ 2).
    pub ny: usize,
    /// Periodic size along x, m (`dx = lx / nx`).
    pub lx: f64,
    /// Periodic size along y, m (`dy = ly / ny`).
    pub ly: f64,
    /// Target root-mean-square height Sq, m (> 0); exact after normalisation.
    pub sq: f64,
    /// Hurst exponent H in (0, 1]; the PSD decays as `q^−(2+2H)` above the roll-off.
    pub hurst: f64,
    /// Roll-off wavelength `λ_r`, m (> 0): the PSD is flat for `q < 2π/λ_r`. With anisotropy it
    /// is the roll-off wavelength along the lay direction `u`.
    pub correlation_length: f64,
    /// Optional short-wavelength cutoff `λ_s`, m: no power at `|q| > 2π/λ_s`.
    /// Range: `min(dx, dy) ≤ λ_s < min(lx, ly)`.
    pub short_wavelength_cutoff: Option<f64>,
    /// `None` for an isotropic surface.
    pub anisotropy: Option<Anisotropy>,
    /// Seed of the random stream.
    pub seed: u64,
}

/// Smallest Sq of a synthetic surface, m: a picometre, a hundredth of an atom's diameter, below
/// the height resolution of any topography instrument; smaller values describe no surface and
/// only drive squared and fourth-power statistics towards underflow. The largest is the shorter
/// side of the surface: heights beyond the lateral extent give rms slopes far above 1, outside
/// the small-slope assumption of every contact and friction model here, and keep the heights'
/// squares far from f64 overflow.
pub const MIN_SQ: f64 = 1e-12;

/// A synthetic-surface parameter is out of range, or the synthesis failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SyntheticError {
    #[error("synthetic surface: `{name}` = {value} is out of range, expected {expected} ({unit})")]
    InvalidParameter {
        name: &'static str,
        value: String,
        expected: String,
        unit: &'static str,
    },
    #[error("synthetic surface: grid {nx} × {ny} exceeds the limit of {max} points")]
    TooLarge { nx: usize, ny: usize, max: usize },
    #[error("synthetic surface: no Fourier mode has power (cutoff removes the whole spectrum)")]
    NoSpectralContent,
    #[error(
        "synthetic surface: the heights at Sq = {sq:e} m overflow f64 (their squares exceed \
         {max:e}); use an Sq in metres of a real surface, e.g. 1 um",
        max = f64::MAX
    )]
    HeightsOverflow { sq: f64 },
    #[error("synthetic surface: {0}")]
    Fft(#[from] FftFailure),
    #[error("synthetic surface: {0}")]
    HeightMap(#[from] HeightMapError),
}

fn invalid(
    name: &'static str,
    value: impl ToString,
    expected: String,
    unit: &'static str,
) -> SyntheticError {
    SyntheticError::InvalidParameter {
        name,
        value: value.to_string(),
        expected,
        unit,
    }
}

fn positive_finite(
    name: &'static str,
    value: f64,
    unit: &'static str,
) -> Result<(), SyntheticError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(invalid(name, value, "a finite value > 0".into(), unit))
    }
}

/// Range of the sides of a synthetic surface, m: from a nanometre (a few atoms: no topography
/// spans less) to a kilometre (beyond any surface a topography describes; also the largest
/// roll-off wavelength). Outside it the wavenumbers `2π/L` square to values that underflow or
/// overflow f64, and the spectrum vanishes.
pub const LENGTH_RANGE: (f64, f64) = (1e-9, 1e3);

fn in_length_range(name: &'static str, value: f64) -> Result<(), SyntheticError> {
    let (low, high) = LENGTH_RANGE;
    if (low..=high).contains(&value) {
        Ok(())
    } else {
        Err(invalid(
            name,
            format!("{value:e}"),
            format!("{low:e} m to {high:e} m"),
            "m",
        ))
    }
}

impl SyntheticSurfaceSpec {
    /// Checks every parameter; the error names the parameter, its value, range and unit.
    pub fn validate(&self) -> Result<(), SyntheticError> {
        if self.nx < 2 {
            return Err(invalid("nx", self.nx, "an integer ≥ 2".into(), "points"));
        }
        if self.ny < 2 {
            return Err(invalid("ny", self.ny, "an integer ≥ 2".into(), "points"));
        }
        match self.nx.checked_mul(self.ny) {
            Some(n) if n <= MAX_SYNTHETIC_POINTS => {}
            _ => {
                return Err(SyntheticError::TooLarge {
                    nx: self.nx,
                    ny: self.ny,
                    max: MAX_SYNTHETIC_POINTS,
                })
            }
        }
        in_length_range("lx", self.lx)?;
        in_length_range("ly", self.ly)?;
        positive_finite("sq", self.sq, "m")?;
        let max_sq = self.lx.min(self.ly);
        if !(MIN_SQ..=max_sq).contains(&self.sq) {
            return Err(invalid(
                "sq",
                format!("{:e}", self.sq),
                format!("{MIN_SQ:e} m ≤ Sq ≤ min(lx, ly) = {max_sq:e} m"),
                "m",
            ));
        }
        if !(self.hurst > 0.0 && self.hurst <= 1.0) {
            return Err(invalid(
                "hurst",
                self.hurst,
                "0 < H ≤ 1".into(),
                "dimensionless",
            ));
        }
        positive_finite("correlation_length", self.correlation_length, "m")?;
        if self.correlation_length > LENGTH_RANGE.1 {
            return Err(invalid(
                "correlation_length",
                format!("{:e}", self.correlation_length),
                format!("> 0 and ≤ {:e} m", LENGTH_RANGE.1),
                "m",
            ));
        }
        if let Some(cutoff) = self.short_wavelength_cutoff {
            let (dx, dy) = (self.lx / self.nx as f64, self.ly / self.ny as f64);
            let (lo, hi) = (dx.min(dy), self.lx.min(self.ly));
            if !(cutoff.is_finite() && cutoff >= lo && cutoff < hi) {
                return Err(invalid(
                    "short_wavelength_cutoff",
                    cutoff,
                    format!("min(dx, dy) = {lo} ≤ λ_s < min(lx, ly) = {hi}"),
                    "m",
                ));
            }
        }
        if let Some(a) = self.anisotropy {
            positive_finite("anisotropy.aspect_ratio", a.aspect_ratio, "dimensionless")?;
            if !a.angle.is_finite() {
                return Err(invalid(
                    "anisotropy.angle",
                    a.angle,
                    "a finite angle".into(),
                    "rad",
                ));
            }
        }
        Ok(())
    }

    /// Pixel spacings `(dx, dy) = (lx/nx, ly/ny)` in metres.
    pub fn spacing(&self) -> (f64, f64) {
        (self.lx / self.nx as f64, self.ly / self.ny as f64)
    }

    /// Roll-off wavelengths `(λ_u, λ_v)` in metres along and across the lay direction.
    pub fn correlation_lengths(&self) -> (f64, f64) {
        let ratio = self.anisotropy.map_or(1.0, |a| a.aspect_ratio);
        (self.correlation_length, self.correlation_length / ratio)
    }

    /// The model PSD of this surface on its grid.
    fn model_psd(&self) -> ModelPsd {
        ModelPsd::new(
            (self.nx, self.ny),
            (self.lx, self.ly),
            self.short_wavelength_cutoff,
            self.correlation_lengths(),
            self.anisotropy.map_or(0.0, |a| a.angle),
            self.hurst,
        )
    }

    /// Unnormalised model PSD `C(q)/C0` at wavevector `(qx, qy)` in rad/m (see module docs).
    pub fn psd_shape(&self, qx: f64, qy: f64) -> f64 {
        self.model_psd().shape(qx, qy)
    }
}

/// Generates the surface described by `spec` (heights in metres, zero mean, Sq = `spec.sq`).
pub fn generate_synthetic_surface(
    spec: &SyntheticSurfaceSpec,
) -> Result<HeightMap, SyntheticError> {
    Ok(synthesize(spec)?.0)
}

/// [`generate_synthetic_surface`] with the unwindowed periodogram of the surface
/// ([`Periodogram`], `C(q) = A |Z(q)|² / N²`), taken from the synthesized modes instead of a
/// forward transform of the heights: the heights are `s·(F⁻¹Ẑ − mean)` for modes `Ẑ` and the
/// Sq normalisation `s`, and `Ẑ(0) = 0`, so `Z(q) = s N Ẑ(q)` and `C(q) = A s² |Ẑ(q)|²`.
/// A forward FFT of the heights gives the same up to its round-off (relative ~1e-16 of the
/// largest mode); the modes the model gives no power (`q = 0`, beyond the short-wavelength
/// cutoff) are exactly 0 here, where a transform of the heights leaves round-off.
pub fn generate_synthetic_surface_with_periodogram(
    spec: &SyntheticSurfaceSpec,
) -> Result<(HeightMap, Periodogram), SyntheticError> {
    generate_synthetic_surface_with_spectrum(spec).map(|(map, periodogram, _)| (map, periodogram))
}

/// [`generate_synthetic_surface_with_periodogram`] with the inverse transform the heights came
/// from, planned for the surface's grid, for the statistics' own inverse transforms (the
/// periodic autocorrelation: [`super::spectral::periodic_autocorrelation_with`]).
pub fn generate_synthetic_surface_with_spectrum(
    spec: &SyntheticSurfaceSpec,
) -> Result<(HeightMap, Periodogram, InverseTransform), SyntheticError> {
    let (map, half, scale, transform) = synthesize(spec)?;
    let area = spec.lx * spec.ly;
    let factor = area * scale * scale;
    let modes = half
        .as_slice()
        .ok_or_else(|| FftFailure::new("the half spectrum is not contiguous"))?;
    let power = modes
        .par_iter()
        .map(|mode| factor * mode.norm_sqr())
        .collect();
    let periodogram = Periodogram {
        c: Array2::from_shape_vec(half.dim(), power).map_err(|e| FftFailure::new(e.to_string()))?,
        dqx: 2.0 * PI / spec.lx,
        dqy: 2.0 * PI / spec.ly,
        nx: spec.nx,
        window: Window::None,
    };
    Ok((map, periodogram, transform))
}

/// ChaCha words (`u32`) each mode draws: two `u64`, one pair of normal deviates.
const WORDS_PER_MODE: u128 = 4;

/// The surface, its half spectrum of modes `Ẑ` (before normalisation), the normalisation
/// factor `s` (heights = `s·(F⁻¹Ẑ − mean)`) and the inverse transform planned for its grid.
fn synthesize(
    spec: &SyntheticSurfaceSpec,
) -> Result<(HeightMap, Array2<Complex64>, f64, InverseTransform), SyntheticError> {
    spec.validate()?;
    let (nx, ny) = (spec.nx, spec.ny);
    let nxh = nx / 2 + 1;
    let mut key = [0u8; 32];
    key[..8].copy_from_slice(&spec.seed.to_le_bytes());
    let base = ChaCha8Rng::from_seed(key);

    // Collected in parallel straight into the vector (no pass that zeroes it first). A work
    // chunk holds consecutive modes: within a row the stream of its `ky` is read on, and at the
    // start of a row or past modes without power (which stay zero and draw nothing) it is moved
    // to the mode's position, so every mode's deviates are those of its position.
    // The modes beyond the cutoff are not evaluated: their shape is 0.
    let model = spec.model_psd();
    let ends: Vec<usize> = (0..ny)
        .into_par_iter()
        .map(|j| model.modes_within_cutoff(j))
        .collect();
    let modes: Vec<Complex64> = (0..ny * nxh)
        .into_par_iter()
        .with_min_len(nxh)
        .map_init(
            || ModeStream::new(&base),
            |stream, index| {
                let (j, i) = stream.locate(index, nxh);
                let shape = if i < ends[j] { model.mode(i, j) } else { 0.0 };
                if shape == 0.0 {
                    return Complex64::new(0.0, 0.0);
                }
                let (g1, g2) = stream.deviates(j, i, ny);
                let amplitude = shape.sqrt();
                if self_conjugate(i, j, nx, ny) {
                    Complex64::new(amplitude * g1, 0.0)
                } else {
                    Complex64::new(amplitude * g1, amplitude * g2) * FRAC_1_SQRT_2
                }
            },
        )
        .collect();
    let mut half =
        Array2::from_shape_vec((ny, nxh), modes).map_err(|e| FftFailure::new(e.to_string()))?;
    enforce_hermitian_columns(&mut half, nx);

    let mut transform = InverseTransform::new(nx, ny);
    let mut z = transform.complex(&half, Vec::new())?;
    let n = (nx * ny) as f64;
    let mean = z.sum() / n;
    let heights = z
        .as_slice_mut()
        .ok_or_else(|| FftFailure::new("the inverse transform is not contiguous"))?;
    // In the heights' (row-major) order, as over the array's elements.
    let rms = (heights.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt();
    if !(rms > 0.0 && rms.is_finite()) {
        return Err(SyntheticError::NoSpectralContent);
    }
    let scale = spec.sq / rms;
    // The heights and their mean square must be finite, or every statistic of the map is not.
    if !normalise(heights, mean, scale).is_finite() {
        return Err(SyntheticError::HeightsOverflow { sq: spec.sq });
    }
    let (dx, dy) = spec.spacing();
    Ok((HeightMap::new(z, dx, dy)?, half, scale, transform))
}

/// Values per parallel chunk of [`normalise`].
const NORMALISE_CHUNK: usize = 1 << 16;

/// Sets every value `v` of `values` to `h = (v − mean)·scale`, in parallel, and returns `Σ h²`
/// (chunk sums of [`NORMALISE_CHUNK`] values added in chunk order). Each height is one
/// subtraction and one multiplication whatever the thread; the sum only says whether the
/// heights' squares are finite (it is `N·Sq²` when they are).
fn normalise(values: &mut [f64], mean: f64, scale: f64) -> f64 {
    let sums: Vec<f64> = values
        .par_chunks_mut(NORMALISE_CHUNK)
        .map(|chunk| {
            let mut sum_of_squares = 0.0;
            for v in chunk {
                let h = (*v - mean) * scale;
                sum_of_squares += h * h;
                *v = h;
            }
            sum_of_squares
        })
        .collect();
    sums.iter().sum()
}

/// The random stream of one parallel work chunk of modes: `base` moved to the stream of the
/// row and the position of the mode it is asked for, where it is not there already.
struct ModeStream {
    rng: ChaCha8Rng,
    /// The row `j` and the mode `i` the stream is positioned at (`None` before the first).
    next: Option<(usize, usize)>,
    /// The flat index and `(j, i)` of the last mode located.
    last: Option<(usize, usize, usize)>,
}

impl ModeStream {
    fn new(base: &ChaCha8Rng) -> Self {
        Self {
            rng: base.clone(),
            next: None,
            last: None,
        }
    }

    /// `(j, i) = (index / nxh, index % nxh)`: a chunk's modes come in order, so after the first
    /// the next one is one step on (no division per mode).
    fn locate(&mut self, index: usize, nxh: usize) -> (usize, usize) {
        let (j, i) = match self.last {
            Some((last, j, i)) if index == last + 1 && i + 1 < nxh => (j, i + 1),
            Some((last, j, _)) if index == last + 1 => (j + 1, 0),
            _ => (index / nxh, index % nxh),
        };
        self.last = Some((index, j, i));
        (j, i)
    }

    /// The pair of normal deviates of mode `i` of row `j` (of `ny` rows): its ChaCha stream
    /// [`mode_stream`], at word position `WORDS_PER_MODE · i`.
    fn deviates(&mut self, j: usize, i: usize, ny: usize) -> (f64, f64) {
        match self.next {
            Some((row, mode)) if row == j && mode == i => {}
            Some((row, _)) if row == j => self.rng.set_word_pos(WORDS_PER_MODE * i as u128),
            _ => {
                self.rng.set_stream(mode_stream(j, ny));
                self.rng.set_word_pos(WORDS_PER_MODE * i as u128);
            }
        }
        self.next = Some((j, i + 1));
        standard_normal_pair(&mut self.rng)
    }
}

/// Ensemble autocorrelation of the model, `R(τ)/R(0)` on the periodic lag grid `[[jy, ix]]`
/// (`τx = ix·dx` for `ix ≤ nx/2`, `(ix − nx)·dx` above; likewise y): the inverse FFT of the model
/// PSD on the spec's grid (Wiener–Khinchin), including the grid's finite size and resolution.
/// Every realisation's autocorrelation scatters around it.
pub fn model_autocorrelation(spec: &SyntheticSurfaceSpec) -> Result<Array2<f64>, SyntheticError> {
    spec.validate()?;
    let (nx, ny) = (spec.nx, spec.ny);
    let model = spec.model_psd();
    let half = Array2::from_shape_fn((ny, nx / 2 + 1), |(j, i)| {
        Complex64::new(model.mode(i, j), 0.0)
    });
    let acf = inverse_real_2d(&half, nx)?;
    let zero_lag = acf.first().copied().unwrap_or(0.0);
    if !(zero_lag > 0.0 && zero_lag.is_finite()) {
        return Err(SyntheticError::NoSpectralContent);
    }
    Ok(acf / zero_lag)
}

/// The ChaCha stream of spectrum row `j`: the signed wavenumber `ky` (`j` below `ny/2`, `j − ny`
/// above) in zigzag order (0, −1, 1, −2, … → 0, 1, 2, 3, …). Mode `(kx, ky)` thus draws its
/// deviates from stream `ky` at position `kx` whatever the grid, and a coarser grid of the same
/// periodic size carries exactly the modes of a finer one that it can represent.
fn mode_stream(j: usize, ny: usize) -> u64 {
    if 2 * j <= ny {
        2 * j as u64
    } else {
        2 * (ny - j) as u64 - 1
    }
}

/// `true` for the modes equal to their own conjugate: `kx ∈ {0, nx/2}` and `ky ∈ {0, ny/2}`.
fn self_conjugate(i: usize, j: usize, nx: usize, ny: usize) -> bool {
    (i == 0 || 2 * i == nx) && (j == 0 || 2 * j == ny)
}

/// On the `kx = 0` and (even `nx`) `kx = nx/2` columns, sets `Z(−ky) = Z(ky)*` for `0 < ky < ny/2`.
fn enforce_hermitian_columns(half: &mut Array2<Complex64>, nx: usize) {
    let ny = half.nrows();
    let mut columns = vec![0];
    if nx.is_multiple_of(2) {
        columns.push(nx / 2);
    }
    for i in columns {
        for j in 1..ny {
            let partner = ny - j;
            if j < partner {
                half[[partner, i]] = half[[j, i]].conj();
            }
        }
    }
}

/// Two independent standard normal deviates (Box–Muller) from two 53-bit uniforms.
fn standard_normal_pair(rng: &mut ChaCha8Rng) -> (f64, f64) {
    const SCALE: f64 = 1.0 / (1u64 << 53) as f64;
    let u1 = ((rng.next_u64() >> 11) + 1) as f64 * SCALE; // (0, 1]: ln is finite
    let u2 = (rng.next_u64() >> 11) as f64 * SCALE; // [0, 1)
    let radius = (-2.0 * u1.ln()).sqrt();
    let (s, c) = (2.0 * PI * u2).sin_cos();
    (radius * c, radius * s)
}

#[cfg(test)]
#[path = "synthetic_tests.rs"]
mod tests;
