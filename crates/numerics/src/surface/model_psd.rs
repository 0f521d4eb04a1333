//! The model PSD shape of a synthetic surface (`super::synthetic`, module docs: roll-off plateau,
//! self-affine decay `κ^−(2+2H)`, short-wavelength cutoff) with what every mode shares — the
//! texture frame's `sin θ`, `cos θ`, the roll-off wavelengths, the cutoff and the exponent —
//! computed once instead of at every mode: the same operations on the same values, so the same
//! bits.

use std::f64::consts::PI;

/// The PSD shape `C(q)/C0` of one synthetic surface on its grid.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ModelPsd {
    nx: usize,
    ny: usize,
    lx: f64,
    ly: f64,
    /// `2π/λ_s`, where there is a short-wavelength cutoff.
    cutoff_q: Option<f64>,
    /// Roll-off wavelengths along and across the lay, m.
    lu: f64,
    lv: f64,
    /// `sin θ`, `cos θ` of the lay direction.
    sin: f64,
    cos: f64,
    /// `−(1 + H)`.
    exponent: f64,
}

impl ModelPsd {
    /// The model of an `nx × ny` grid of size `lx × ly` (m), short-wavelength cutoff `λ_s` (m),
    /// roll-off wavelengths `(λ_u, λ_v)` (m) along and across the lay at `angle` (rad) from x
    /// and Hurst exponent `hurst`.
    pub(crate) fn new(
        (nx, ny): (usize, usize),
        (lx, ly): (f64, f64),
        cutoff: Option<f64>,
        (lu, lv): (f64, f64),
        angle: f64,
        hurst: f64,
    ) -> Self {
        let (sin, cos) = angle.sin_cos();
        Self {
            nx,
            ny,
            lx,
            ly,
            cutoff_q: cutoff.map(|cutoff| 2.0 * PI / cutoff),
            lu,
            lv,
            sin,
            cos,
            exponent: -(1.0 + hurst),
        }
    }

    /// `C(q)/C0` at wavevector `(qx, qy)` in rad/m.
    pub(crate) fn shape(&self, qx: f64, qy: f64) -> f64 {
        let q2 = qx * qx + qy * qy;
        if q2 == 0.0 || self.beyond_cutoff(q2) {
            return 0.0;
        }
        let (s, c) = (self.sin, self.cos);
        let ku = (qx * c + qy * s) * self.lu / (2.0 * PI);
        let kv = (-qx * s + qy * c) * self.lv / (2.0 * PI);
        let kappa2 = ku * ku + kv * kv;
        if kappa2 < 1.0 {
            1.0
        } else {
            kappa2.powf(self.exponent)
        }
    }

    /// `|q|² > (2π/λ_s)²`: no power there.
    fn beyond_cutoff(&self, q2: f64) -> bool {
        self.cutoff_q.is_some_and(|qs| q2 > qs * qs)
    }

    /// The wavevector `(qx, qy)` of half-spectrum mode `(i, j)` (`kx = i`, row `j` as in the
    /// FFT: `ky = j` up to `ny/2`, `j − ny` above).
    fn wavevector(&self, i: usize, j: usize) -> (f64, f64) {
        let qx = 2.0 * PI * i as f64 / self.lx;
        let ky = if 2 * j <= self.ny {
            j as f64
        } else {
            j as f64 - self.ny as f64
        };
        (qx, 2.0 * PI * ky / self.ly)
    }

    /// The shape of half-spectrum mode `(i, j)`. On the Nyquist row the aliased `±qy` are one
    /// mode: mean of both.
    pub(crate) fn mode(&self, i: usize, j: usize) -> f64 {
        let (qx, qy) = self.wavevector(i, j);
        if 2 * j == self.ny {
            0.5 * (self.shape(qx, qy) + self.shape(qx, -qy))
        } else {
            self.shape(qx, qy)
        }
    }

    /// The end of the modes of row `j` the cutoff leaves: every mode `(i, j)` with `i` at or
    /// above it is beyond the cutoff (shape 0), found by bisection, since `|q|²` grows with `i`
    /// (`qx = 2π·i/Lx ≥ 0`; rounding keeps each step monotone). `nx/2 + 1` without a cutoff.
    pub(crate) fn modes_within_cutoff(&self, j: usize) -> usize {
        let (mut low, mut high) = (0, self.nx / 2 + 1);
        if self.cutoff_q.is_none() {
            return high;
        }
        while low < high {
            let middle = low + (high - low) / 2;
            let (qx, qy) = self.wavevector(middle, j);
            if self.beyond_cutoff(qx * qx + qy * qy) {
                high = middle;
            } else {
                low = middle + 1;
            }
        }
        low
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parameters of one test model: cutoff, roll-off wavelengths, angle, Hurst exponent.
    struct Model {
        cutoff: Option<f64>,
        lengths: (f64, f64),
        angle: f64,
        hurst: f64,
    }

    /// The shape as it was computed at every mode, every constant recomputed.
    fn shape_reference(m: &Model, qx: f64, qy: f64) -> f64 {
        let q2 = qx * qx + qy * qy;
        if q2 == 0.0 {
            return 0.0;
        }
        if let Some(cutoff) = m.cutoff {
            let qs = 2.0 * PI / cutoff;
            if q2 > qs * qs {
                return 0.0;
            }
        }
        let (lu, lv) = m.lengths;
        let (s, c) = m.angle.sin_cos();
        let ku = (qx * c + qy * s) * lu / (2.0 * PI);
        let kv = (-qx * s + qy * c) * lv / (2.0 * PI);
        let kappa2 = ku * ku + kv * kv;
        if kappa2 < 1.0 {
            1.0
        } else {
            kappa2.powf(-(1.0 + m.hurst))
        }
    }

    /// Every mode's shape has the bits of the per-mode computation, and every mode at or
    /// beyond a row's end is beyond the cutoff while the one before is not: isotropic and
    /// rotated textures, even and odd grids, with and without a cutoff (one that cuts every row,
    /// one that cuts none).
    #[test]
    fn shapes_and_cutoff_ends_equal_the_per_mode_computation() {
        for (nx, ny) in [(64, 48), (63, 65), (2, 2)] {
            for cutoff in [None, Some(3e-6), Some(1e-5), Some(0.9e-4)] {
                for (lengths, angle) in [
                    ((2e-5, 2e-5), 0.0),
                    ((2e-5, 2e-5 / 3.0), 0.4),
                    ((2e-5, 5e-6), -2.0),
                ] {
                    let m = Model {
                        cutoff,
                        lengths,
                        angle,
                        hurst: 0.73,
                    };
                    let model =
                        ModelPsd::new((nx, ny), (1e-4, 0.7e-4), cutoff, lengths, angle, 0.73);
                    for j in 0..ny {
                        let end = model.modes_within_cutoff(j);
                        for i in 0..nx / 2 + 1 {
                            let (qx, qy) = model.wavevector(i, j);
                            let expected = if 2 * j == ny {
                                0.5 * (shape_reference(&m, qx, qy) + shape_reference(&m, qx, -qy))
                            } else {
                                shape_reference(&m, qx, qy)
                            };
                            assert_eq!(model.mode(i, j).to_bits(), expected.to_bits());
                            let beyond = model.beyond_cutoff(qx * qx + qy * qy);
                            assert_eq!(beyond, i >= end, "{nx} {ny} {cutoff:?} ({i}, {j})");
                        }
                    }
                }
            }
        }
    }
}
