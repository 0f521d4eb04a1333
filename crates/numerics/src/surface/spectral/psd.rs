//! Power spectral density: 2-D periodogram, radially averaged PSD and 1-D profile PSDs.
//!
//! Convention (Jacobs, Junge & Pastewka, *Surf. Topogr.: Metrol. Prop.* 5 (2017) 013001): for a
//! map of `nx × ny` points, size `Lx = nx·dx`, `Ly = ny·dy`, area `A = Lx·Ly`, `N = nx·ny`, and
//! `Z(q) = Σ_r w(r) (z(r) − z̄) e^{−i q·r}`,
//!
//! * 2-D PSD `C(q) = A |Z(q)|² / (N² ⟨w²⟩)` in m⁴, so `Sq² = (1/A) Σ_q C(q)` (exact with
//!   [`Window::None`]);
//! * profile PSD along x `C¹ₓ(qx) = (1/Ly) Σ_qy C(qx, qy)` in m³ — the row-averaged
//!   `dx |Z_row(qx)|² / nx` — so that `Sq² = (1/Lx) Σ_qx C¹ₓ(qx)` over both signs of `qx`;
//!   likewise along y. Both are two-sided densities reported for `q > 0`; the omitted `q = 0`
//!   term is the variance of the profile means, so `(1/Lx) Σ_{qx ≠ 0} C¹ₓ` is the mean over
//!   profiles of each profile's variance about its own mean.
//!
//! `q` is the angular wavenumber `2π/λ` in rad/m. Without a window the surface is treated as
//! periodic; a measured, non-periodic surface leaks power from its edge discontinuity (a
//! spurious `q^−4` tail in 2-D), which the 2-D separable Hann window suppresses.

use ndarray::Array2;
use rayon::prelude::*;
use std::f64::consts::PI;

use super::error::{require_complete, SpectralError};
use crate::fft2::forward_real_2d;
use crate::surface::HeightMap;

/// Window applied to the mean-removed heights before the transform.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Window {
    /// No window: exact for periodic surfaces (synthetic ones).
    None,
    /// Separable periodic Hann window `w = w(x)·w(y)`, `w(x) = sin²(π i / nx)`; the PSD is divided
    /// by `⟨w²⟩` so the total power still estimates Sq². Recommended for measured surfaces.
    #[default]
    Hann,
}

/// Axis of a profile statistic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
}

/// The 2-D periodogram on the real-FFT half grid (`[ny, nx/2 + 1]`, rows as in the FFT).
#[derive(Debug, Clone, PartialEq)]
pub struct Periodogram {
    /// `C(q)` in m⁴ (see module docs).
    pub c: Array2<f64>,
    /// Wavenumber spacing along x, `2π/Lx`, rad/m.
    pub dqx: f64,
    /// Wavenumber spacing along y, `2π/Ly`, rad/m.
    pub dqy: f64,
    /// Points along x of the height map (the half grid has `nx/2 + 1` columns).
    pub nx: usize,
    /// The window the heights were weighted with.
    pub window: Window,
}

impl Periodogram {
    /// Wavevector `(qx, qy)` in rad/m of half-grid cell `(j, i)`.
    pub fn wavevector(&self, j: usize, i: usize) -> (f64, f64) {
        let ny = self.c.nrows();
        let ky = if 2 * j <= ny {
            j as f64
        } else {
            j as f64 - ny as f64
        };
        (i as f64 * self.dqx, ky * self.dqy)
    }

    /// The row of `|ky|` for half-grid row `j`: `j` up to `ny/2`, `ny − j` above (the rows of
    /// `ky` and `−ky` hold wavevectors of equal magnitude).
    pub fn mirrored_row(&self, j: usize) -> usize {
        let ny = self.c.nrows();
        if 2 * j <= ny {
            j
        } else {
            ny - j
        }
    }

    /// `|q| = hypot(qx, qy)` (rad/m) of the half-grid cells of rows `0 ..= ny/2`, computed in
    /// parallel: cell `(j, i)` has `wavenumbers[self.mirrored_row(j)][i]`, the same bits as
    /// `hypot` of [`Periodogram::wavevector`] (`qy` of row `ny − j` is exactly `−qy` of row `j`,
    /// and `hypot` is even in each argument).
    pub fn wavenumbers(&self) -> Vec<Vec<f64>> {
        (0..=self.c.nrows() / 2)
            .into_par_iter()
            .map(|j| {
                (0..self.c.ncols())
                    .map(|i| {
                        let (qx, qy) = self.wavevector(j, i);
                        qx.hypot(qy)
                    })
                    .collect()
            })
            .collect()
    }

    /// Multiplicity of half-grid column `i` in the full spectrum: 2 for the columns whose
    /// conjugate (`−kx`) is not stored, 1 for `kx = 0` and (even `nx`) `kx = nx/2`.
    pub fn multiplicity(&self, i: usize) -> f64 {
        if i == 0 || 2 * i == self.nx {
            1.0
        } else {
            2.0
        }
    }
}

/// Computes the 2-D periodogram of a complete height map.
pub fn periodogram(map: &HeightMap, window: Window) -> Result<Periodogram, SpectralError> {
    require_complete(map)?;
    let (nx, ny) = (map.nx(), map.ny());
    let z = map.heights();
    let mean = z.sum() / (nx * ny) as f64;
    let (wx, wy) = (window_weights(window, nx), window_weights(window, ny));
    let windowed = Array2::from_shape_fn((ny, nx), |(j, i)| (z[[j, i]] - mean) * wx[i] * wy[j]);
    let mean_w2 = mean_square(&wx) * mean_square(&wy);
    let half = forward_real_2d(&windowed)?;
    let (lx, ly) = map.size();
    let n = (nx * ny) as f64;
    let scale = lx * ly / (n * n * mean_w2);
    Ok(Periodogram {
        c: half.mapv(|v| v.norm_sqr() * scale),
        dqx: 2.0 * PI / lx,
        dqy: 2.0 * PI / ly,
        nx,
        window,
    })
}

fn window_weights(window: Window, n: usize) -> Vec<f64> {
    match window {
        Window::None => vec![1.0; n],
        Window::Hann => (0..n)
            .map(|i| (PI * i as f64 / n as f64).sin().powi(2))
            .collect(),
    }
}

fn mean_square(w: &[f64]) -> f64 {
    w.iter().map(|v| v * v).sum::<f64>() / w.len() as f64
}

/// A PSD as a table: `q[k]` (rad/m) and `c[k]`; `modes[k]` Fourier modes were averaged.
#[derive(Debug, Clone, PartialEq)]
pub struct PsdTable {
    /// Wavenumber, rad/m (for the radial PSD: the mean `|q|` of the modes in the bin).
    pub q: Vec<f64>,
    /// PSD: m⁴ for the radially averaged 2-D PSD, m³ for a profile PSD.
    pub c: Vec<f64>,
    /// Number of Fourier modes averaged into each row.
    pub modes: Vec<usize>,
}

/// Radially averaged 2-D PSD: the mean of `C(q)` over annuli `|q| ∈ [(k − ½)Δq, (k + ½)Δq)`,
/// `k = 1, 2, …`, with `Δq = max(2π/Lx, 2π/Ly)`, up to the smaller Nyquist wavenumber
/// `min(π/dx, π/dy)` (annuli beyond are incomplete). Empty annuli are skipped.
pub fn radial_psd(map: &HeightMap, window: Window) -> Result<PsdTable, SpectralError> {
    Ok(radial_psd_of(&periodogram(map, window)?, map))
}

/// [`radial_psd`] of a periodogram already computed from `map` (one FFT shared by several
/// statistics). The modes are summed in the periodogram's row-major order; their `|q|` come
/// from [`Periodogram::wavenumbers`].
pub fn radial_psd_of(p: &Periodogram, map: &HeightMap) -> PsdTable {
    let dq = p.dqx.max(p.dqy);
    let q_max = (PI / map.dx()).min(PI / map.dy());
    let bins = (q_max / dq + 0.5).floor() as usize + 1;
    let mut sum_q = vec![0.0; bins];
    let mut sum_c = vec![0.0; bins];
    let mut weight = vec![0.0; bins];
    let mut modes = vec![0usize; bins];
    let wavenumbers = p.wavenumbers();
    // The annulus of each |q| (`u32::MAX`: outside 0 < |q| ≤ q_max), in parallel.
    let annuli: Vec<Vec<u32>> = wavenumbers
        .par_iter()
        .map(|row| {
            row.iter()
                .map(|&q| {
                    if q == 0.0 || q > q_max {
                        u32::MAX
                    } else {
                        (q / dq + 0.5).floor() as u32
                    }
                })
                .collect()
        })
        .collect();
    for (j, power) in p.c.rows().into_iter().enumerate() {
        let mirrored = p.mirrored_row(j);
        let cells = power
            .iter()
            .zip(&wavenumbers[mirrored])
            .zip(&annuli[mirrored]);
        for (i, ((&c, &q), &k)) in cells.enumerate() {
            let k = k as usize;
            if k >= bins {
                continue;
            }
            let mult = p.multiplicity(i);
            sum_q[k] += mult * q;
            sum_c[k] += mult * c;
            weight[k] += mult;
            modes[k] += mult as usize;
        }
    }
    let mut table = PsdTable {
        q: Vec::new(),
        c: Vec::new(),
        modes: Vec::new(),
    };
    for k in 1..bins {
        if weight[k] > 0.0 {
            table.q.push(sum_q[k] / weight[k]);
            table.c.push(sum_c[k] / weight[k]);
            table.modes.push(modes[k]);
        }
    }
    table
}

/// Profile PSD along `axis`, averaged over all profiles (see module docs), for `q > 0` up to
/// that axis' Nyquist wavenumber.
pub fn profile_psd(map: &HeightMap, axis: Axis, window: Window) -> Result<PsdTable, SpectralError> {
    let p = periodogram(map, window)?;
    let (lx, ly) = map.size();
    let (ny, nxh) = p.c.dim();
    let mut table = PsdTable {
        q: Vec::new(),
        c: Vec::new(),
        modes: Vec::new(),
    };
    match axis {
        Axis::X => {
            for i in 1..nxh {
                table.q.push(i as f64 * p.dqx);
                table.c.push(p.c.column(i).sum() / ly);
                table.modes.push(ny);
            }
        }
        Axis::Y => {
            for j in 1..=ny / 2 {
                // C(−qx, qy) = C(qx, −qy): the negative-qx half of row j is row ny − j.
                let mirror = (ny - j) % ny;
                let sum: f64 = (0..nxh)
                    .map(|i| p.c[[j, i]] + (p.multiplicity(i) - 1.0) * p.c[[mirror, i]])
                    .sum();
                table.q.push(j as f64 * p.dqy);
                table.c.push(sum / lx);
                table.modes.push(map.nx());
            }
        }
    }
    Ok(table)
}
