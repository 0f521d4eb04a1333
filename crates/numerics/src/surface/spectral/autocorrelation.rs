//! Areal autocorrelation function (ACF), its radial average, and the ISO 25178-2 spatial
//! parameters Sal and Str; correlation lengths along x and y.
//!
//! `f(τ) = ⟨z(r) z(r + τ)⟩ / ⟨z²⟩` for mean-removed heights, computed by FFT
//! (Wiener–Khinchin). Two boundary treatments:
//! * [`AcfBoundary::Periodic`] — circular correlation, for periodic (synthetic) surfaces;
//! * [`AcfBoundary::ZeroPadded`] — the map is zero-padded to (at least) twice its size so no lag
//!   wraps around, and each lag is averaged over its overlap `(nx − |ix|)(ny − |iy|)` points
//!   (the unbiased estimator used by e.g. Gwyddion). For measured surfaces.
//!
//! Lags are kept up to half the map, `|ix| ≤ nx/2`, `|iy| ≤ ny/2`, beyond which fewer than half
//! of the points contribute.
//!
//! Decay lengths (ISO 25178-2:2012, §4.2 and Sal/Str definitions, threshold `s`, default 0.2):
//! along a direction, the lag distance at which `f` first drops to `s`, found by walking the ray
//! with bilinear interpolation of `f` and linear interpolation of the crossing, in steps of
//! [`ray_step`]: `min(dx, dy)/4`, but never shorter than 1/16 of the distance `g` the ray needs to
//! cross one grid cell, so a ray takes at most `16·max(hx, hy) + 16` steps whatever the spacings
//! (a 1e6 m × 0.125 mm map would otherwise need ~10¹³ steps of `dy/4` along x). Sal is the minimum over directions (1° steps over 180°, the ACF being point
//! symmetric), Str = Sal / (maximum over directions), undefined (`None`) when some direction does
//! not decay within the lag range. The correlation lengths along x and y use the same threshold on
//! the lag axes (grid points, linear interpolation), so `Sal ≤ min(ξx, ξy)` up to interpolation.

use ndarray::Array2;
use rayon::prelude::*;
use realfft::num_complex::Complex64;

use super::error::{require_complete, SpectralError};
use super::inverse::InverseTransform;
use super::psd::{Axis, Periodogram, Window};
use crate::fft2::{fast_even_length, forward_real_2d, inverse_real_2d, inverse_real_spectrum_2d};
use crate::surface::HeightMap;

/// ISO 25178-2 default threshold `s` for Sal and Str.
pub const ISO_ACF_THRESHOLD: f64 = 0.2;

/// Boundary treatment of the ACF (see module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AcfBoundary {
    Periodic,
    ZeroPadded,
}

/// Normalised areal ACF on a periodic lag grid of `rows × cols` values: the lag `(ix, iy)`,
/// `|ix| ≤ hx`, `|iy| ≤ hy`, is at `values[[iy mod rows, ix mod cols]]` (negative lags wrapped,
/// as a circular correlation leaves them), so the periodic ACF is kept as the transform gives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Autocorrelation {
    values: Array2<f64>,
    dx: f64,
    dy: f64,
    hx: usize,
    hy: usize,
}

/// Radially averaged ACF: `acf[k]` is the mean over lags with `|τ|` in bin `k` of width
/// `max(dx, dy)` centred on `r[k]` (m), up to the largest full circle of lags.
#[derive(Debug, Clone, PartialEq)]
pub struct RadialAcf {
    pub r: Vec<f64>,
    pub acf: Vec<f64>,
}

/// Sal, Str and the directions of fastest and slowest decay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AcfTexture {
    /// Autocorrelation length Sal, m: shortest decay distance to `threshold`.
    pub sal: f64,
    /// Texture aspect ratio Str = Sal / longest decay distance, in (0, 1]; `None` when some
    /// direction does not decay within the lag range (strongly directional or too small map).
    pub str_ratio: Option<f64>,
    /// Direction of fastest decay (of Sal), degrees from x in [0, 180).
    pub fastest_decay_deg: f64,
    /// Longest decay distance, m, when every direction decays.
    pub longest_decay: Option<f64>,
    /// Threshold `s` used.
    pub threshold: f64,
}

/// Correlation lengths along the x and y lag axes (`None`: no decay within half the map).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CorrelationLengths {
    /// m
    pub x: Option<f64>,
    /// m
    pub y: Option<f64>,
    /// Threshold `s` used.
    pub threshold: f64,
}

/// Computes the normalised ACF of a complete height map. The zero-padded grid is at least twice
/// the map along each axis (the next even FFT length with prime factors 2, 3, 5 and 7 only,
/// [`fast_even_length`]: `2n − 1` points keep every lag from wrapping).
pub fn autocorrelation(
    map: &HeightMap,
    boundary: AcfBoundary,
) -> Result<Autocorrelation, SpectralError> {
    require_complete(map)?;
    let (nx, ny) = (map.nx(), map.ny());
    let z = map.heights();
    let mean = z.sum() / (nx * ny) as f64;
    let (px, py) = match boundary {
        AcfBoundary::Periodic => (nx, ny),
        AcfBoundary::ZeroPadded => (fast_even_length(2 * nx), fast_even_length(2 * ny)),
    };
    let mut padded = Array2::<f64>::zeros((py, px));
    padded
        .slice_mut(ndarray::s![..ny, ..nx])
        .assign(&z.mapv(|v| v - mean));
    let mut power = forward_real_2d(&padded)?;
    drop(padded);
    power.mapv_inplace(|v| Complex64::new(v.norm_sqr(), 0.0));
    let circular = inverse_real_2d(&power, px)?;
    drop(power);
    match boundary {
        AcfBoundary::Periodic => normalised(circular, map),
        AcfBoundary::ZeroPadded => normalised(overlap_averaged_lags(&circular, map), map),
    }
}

/// The periodic ACF ([`AcfBoundary::Periodic`]) of `map` from its unwindowed periodogram: by
/// Wiener–Khinchin the circular autocorrelation is the inverse transform of `|Z(q)|²`, and the
/// periodogram's constant factor cancels in the normalisation. One inverse FFT instead of a
/// forward and an inverse one; equal to [`autocorrelation`] up to round-off.
pub fn periodic_autocorrelation_of(
    p: &Periodogram,
    map: &HeightMap,
) -> Result<Autocorrelation, SpectralError> {
    require_unwindowed_complete(p, map)?;
    normalised(inverse_real_spectrum_2d(&p.c, map.nx())?, map)
}

/// [`periodic_autocorrelation_of`] through a transform already planned for `map`'s grid (a
/// synthetic surface's), its lags written into `buffer`'s memory where it holds `nx·ny` values
/// (a grid a statistic no longer needs): the same values, without a new plan or new pages.
pub fn periodic_autocorrelation_with(
    p: &Periodogram,
    map: &HeightMap,
    transform: &mut InverseTransform,
    buffer: Vec<f64>,
) -> Result<Autocorrelation, SpectralError> {
    require_unwindowed_complete(p, map)?;
    normalised(transform.real(&p.c, buffer)?, map)
}

/// The periodic ACF needs an unwindowed periodogram of a complete map.
fn require_unwindowed_complete(p: &Periodogram, map: &HeightMap) -> Result<(), SpectralError> {
    if p.window != Window::None {
        return Err(SpectralError::Windowed {
            what: "the periodic autocorrelation",
        });
    }
    require_complete(map)
}

/// The lags `|ix| ≤ nx/2`, `|iy| ≤ ny/2` of the circular correlation `circular` of the
/// zero-padded grid, each averaged over its overlap `(nx − |ix|)(ny − |iy|)`, on the periodic
/// lag grid of `(2·hy + 1) × (2·hx + 1)` values.
fn overlap_averaged_lags(circular: &Array2<f64>, map: &HeightMap) -> Array2<f64> {
    let (nx, ny) = (map.nx(), map.ny());
    let (py, px) = circular.dim();
    let (hx, hy) = (nx / 2, ny / 2);
    let (rows, cols) = (2 * hy + 1, 2 * hx + 1);
    let signed = |index: usize, half: usize, len: usize| {
        if index <= half {
            index as isize
        } else {
            index as isize - len as isize
        }
    };
    Array2::from_shape_fn((rows, cols), |(row, col)| {
        let (iy, ix) = (signed(row, hy, rows), signed(col, hx, cols));
        let source = [
            iy.rem_euclid(py as isize) as usize,
            ix.rem_euclid(px as isize) as usize,
        ];
        circular[source] / ((nx - ix.unsigned_abs()) * (ny - iy.unsigned_abs())) as f64
    })
}

/// The ACF of `map` from its unnormalised periodic lag grid `values` (lag 0 at `[0, 0]`):
/// every lag divided by lag 0 (rows in parallel).
fn normalised(mut values: Array2<f64>, map: &HeightMap) -> Result<Autocorrelation, SpectralError> {
    let zero = values[[0, 0]];
    if !(zero > 0.0 && zero.is_finite()) {
        return Err(SpectralError::FlatSurface);
    }
    let cols = values.ncols().max(1);
    match values.as_slice_mut() {
        Some(lags) => lags
            .par_chunks_mut(cols)
            .for_each(|row| row.iter_mut().for_each(|v| *v /= zero)),
        None => values /= zero,
    }
    Ok(Autocorrelation {
        values,
        dx: map.dx(),
        dy: map.dy(),
        hx: map.nx() / 2,
        hy: map.ny() / 2,
    })
}

impl Autocorrelation {
    /// Wraps a normalised ACF given on the periodic lag grid of an `[ny, nx]` map (lag `(0, 0)` at
    /// `[0, 0]`, negative lags wrapped), e.g. a model ACF; spacings in metres.
    pub fn from_periodic_lags(periodic: &Array2<f64>, dx: f64, dy: f64) -> Self {
        let (ny, nx) = periodic.dim();
        Self {
            values: periodic.to_owned(),
            dx,
            dy,
            hx: nx / 2,
            hy: ny / 2,
        }
    }

    /// The periodic lag grid (see [`Autocorrelation`]): lag `(ix, iy)` at
    /// `[iy mod rows, ix mod cols]`.
    pub fn values(&self) -> &Array2<f64> {
        &self.values
    }

    /// Lag spacings `(dx, dy)` in metres.
    pub fn spacing(&self) -> (f64, f64) {
        (self.dx, self.dy)
    }

    /// Largest lags `(hx·dx, hy·dy)` in metres.
    pub fn max_lag(&self) -> (f64, f64) {
        (self.hx as f64 * self.dx, self.hy as f64 * self.dy)
    }

    /// ACF at lag index `(ix, iy)`, `None` outside the lag range.
    pub fn at(&self, ix: isize, iy: isize) -> Option<f64> {
        if ix.unsigned_abs() > self.hx || iy.unsigned_abs() > self.hy {
            return None;
        }
        let (rows, cols) = self.values.dim();
        let row = iy.rem_euclid(rows as isize) as usize;
        let col = ix.rem_euclid(cols as isize) as usize;
        Some(self.values[[row, col]])
    }

    /// Bilinear interpolation at lag `(tx, ty)` in metres, `None` outside the lag range.
    pub fn interpolate(&self, tx: f64, ty: f64) -> Option<f64> {
        let (fx, fy) = (tx / self.dx, ty / self.dy);
        let (x0, y0) = (fx.floor(), fy.floor());
        let (ax, ay) = (fx - x0, fy - y0);
        let (ix, iy) = (x0 as isize, y0 as isize);
        let f00 = self.at(ix, iy)?;
        let f10 = if ax > 0.0 { self.at(ix + 1, iy)? } else { f00 };
        let f01 = if ay > 0.0 { self.at(ix, iy + 1)? } else { f00 };
        let f11 = if ax > 0.0 && ay > 0.0 {
            self.at(ix + 1, iy + 1)?
        } else if ax > 0.0 {
            f10
        } else {
            f01
        };
        Some((1.0 - ay) * ((1.0 - ax) * f00 + ax * f10) + ay * ((1.0 - ax) * f01 + ax * f11))
    }

    /// Decay distance (m) to `threshold` along the direction at `angle_deg` from x.
    pub fn decay_length(
        &self,
        angle_deg: f64,
        threshold: f64,
    ) -> Result<Option<f64>, SpectralError> {
        check_threshold(threshold)?;
        if !angle_deg.is_finite() {
            return Err(SpectralError::InvalidOption {
                name: "angle_deg",
                value: angle_deg.to_string(),
                expected: "a finite angle in degrees".into(),
            });
        }
        let (s, c) = angle_deg.to_radians().sin_cos();
        let step = ray_step(self.dx, self.dy, c, s);
        let mut previous = 1.0;
        let mut k = 1usize;
        loop {
            let r = k as f64 * step;
            let Some(value) = self.interpolate(r * c, r * s) else {
                return Ok(None);
            };
            if value <= threshold {
                return Ok(Some(r - step * (threshold - value) / (previous - value)));
            }
            previous = value;
            k += 1;
        }
    }

    /// Sal and Str (ISO 25178-2) for threshold `s` ([`ISO_ACF_THRESHOLD`] by default).
    pub fn texture(&self, threshold: f64) -> Result<AcfTexture, SpectralError> {
        let mut shortest: Option<(f64, f64)> = None;
        let mut longest: Option<f64> = Some(0.0);
        for degree in 0..180 {
            let angle = degree as f64;
            match self.decay_length(angle, threshold)? {
                Some(r) => {
                    if shortest.is_none_or(|(best, _)| r < best) {
                        shortest = Some((r, angle));
                    }
                    longest = longest.map(|l| l.max(r));
                }
                None => longest = None,
            }
        }
        let (sal, fastest_decay_deg) = shortest.ok_or_else(|| {
            let (mx, my) = self.max_lag();
            SpectralError::NoDecay {
                threshold,
                max_lag: mx.max(my),
            }
        })?;
        Ok(AcfTexture {
            sal,
            str_ratio: longest.map(|l| sal / l),
            fastest_decay_deg,
            longest_decay: longest,
            threshold,
        })
    }

    /// Correlation lengths along the x and y lag axes for threshold `s` (linear interpolation
    /// between grid lags).
    pub fn correlation_lengths(&self, threshold: f64) -> Result<CorrelationLengths, SpectralError> {
        check_threshold(threshold)?;
        Ok(CorrelationLengths {
            x: self.axis_decay(Axis::X, threshold),
            y: self.axis_decay(Axis::Y, threshold),
            threshold,
        })
    }

    fn axis_decay(&self, axis: Axis, threshold: f64) -> Option<f64> {
        let (count, spacing) = match axis {
            Axis::X => (self.hx, self.dx),
            Axis::Y => (self.hy, self.dy),
        };
        let mut previous = 1.0;
        for k in 1..=count as isize {
            let value = match axis {
                Axis::X => self.at(k, 0)?,
                Axis::Y => self.at(0, k)?,
            };
            if value <= threshold {
                let fraction = (previous - threshold) / (previous - value);
                return Some(((k - 1) as f64 + fraction) * spacing);
            }
            previous = value;
        }
        None
    }

    /// Radially averaged ACF (see [`RadialAcf`]). The lags are summed row by row from
    /// `(−hx, −hy)`, the order of the centred lag grid; the bin of a lag depends on `|ix|` and
    /// `|iy|` only (`|τ|` is `hypot` of the lag's components, even in each), so the bins of one
    /// quadrant are computed first, in parallel, and serve all four.
    pub fn radial(&self) -> RadialAcf {
        let width = self.dx.max(self.dy);
        let (mx, my) = self.max_lag();
        let r_max = mx.min(my);
        let bins = (r_max / width + 0.5).floor() as usize + 1;
        let (hx, hy) = (self.hx, self.hy);
        let quadrant: Vec<Vec<usize>> = (0..=hy)
            .into_par_iter()
            .map(|ay| {
                let ty = ay as f64 * self.dy;
                (0..=hx)
                    .map(|ax| ((ax as f64 * self.dx).hypot(ty) / width + 0.5).floor() as usize)
                    .collect()
            })
            .collect();
        let mut sum = vec![0.0; bins];
        let mut count = vec![0usize; bins];
        let (rows, cols) = self.values.dim();
        for iy in -(hy as isize)..=hy as isize {
            let stored = self.values.row(iy.rem_euclid(rows as isize) as usize);
            let bins_of = &quadrant[iy.unsigned_abs()];
            // Lags −hx … −1 are the last hx values of the stored row, then 0 … hx its first.
            let negative = (cols - hx..cols).zip((1..=hx).rev());
            for (col, ax) in negative.chain((0..=hx).map(|ax| (ax, ax))) {
                let k = bins_of[ax];
                if k < bins {
                    sum[k] += stored[col];
                    count[k] += 1;
                }
            }
        }
        let mut radial = RadialAcf {
            r: Vec::new(),
            acf: Vec::new(),
        };
        for (k, (s, c)) in sum.iter().zip(&count).enumerate() {
            if *c > 0 {
                radial.r.push(k as f64 * width);
                radial.acf.push(s / *c as f64);
            }
        }
        radial
    }
}

/// Step (m) of the decay search along the direction `(cos, sin)`: `min(dx, dy)/4`, or
/// `g/16` when that is longer, where `g = min(dx/|cos|, dy/|sin|)` is the length of the ray
/// inside one grid cell. The ACF is known only on the lag grid, so the walk ends after at most
/// `16·max(hx, hy) + 16` steps: work bounded by the map's grid, not by the ratio of its
/// spacings. For spacings within a factor √15 ≈ 3.9 of each other (`g ≤ √(dx² + dy²) ≤
/// 4·min(dx, dy)`) the step is `min(dx, dy)/4` in every direction.
fn ray_step(dx: f64, dy: f64, cos: f64, sin: f64) -> f64 {
    let cell = (dx / cos.abs()).min(dy / sin.abs());
    (dx.min(dy) / 4.0).max(cell / 16.0)
}

fn check_threshold(threshold: f64) -> Result<(), SpectralError> {
    if threshold > 0.0 && threshold < 1.0 {
        Ok(())
    } else {
        Err(SpectralError::InvalidOption {
            name: "threshold",
            value: threshold.to_string(),
            expected: "0 < s < 1 (ISO 25178-2 default 0.2)".into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A model ACF `exp(−|τ|/ξ)` with correlation length `xi` (m) on an `n × n` periodic grid.
    fn exponential_acf(n: usize, dx: f64, dy: f64, xi: f64) -> Autocorrelation {
        let lag = |i: usize| i.min(n - i) as f64;
        let periodic = Array2::from_shape_fn((n, n), |(iy, ix)| {
            (-(lag(ix) * dx).hypot(lag(iy) * dy) / xi).exp()
        });
        Autocorrelation::from_periodic_lags(&periodic, dx, dy)
    }

    fn bits(values: &[f64]) -> Vec<u64> {
        values.iter().map(|v| v.to_bits()).collect()
    }

    /// The normalisation divides every lag by lag 0, as `values / zero` does.
    #[test]
    fn normalisation_divides_every_lag_by_lag_zero() {
        let values = Array2::from_shape_fn((7, 5), |(j, i)| 3.0 - (j * 5 + i) as f64 * 0.1);
        let map = HeightMap::new(Array2::zeros((7, 5)), 1.0, 1.0).unwrap();
        let acf = normalised(values.clone(), &map).unwrap();
        let expected = &values / values[[0, 0]];
        assert_eq!(
            bits(acf.values().as_slice().unwrap()),
            bits(expected.as_slice().unwrap())
        );
    }

    /// A 1e6 m × 0.125 mm map at 64² (the spacings 10¹¹ apart) decays along y within the lag
    /// range and never along x, in a bounded number of steps.
    #[test]
    fn extreme_spacing_ratio_is_searched_in_bounded_time() {
        let (dx, dy) = (1e6 / 64.0, 0.125e-3 / 64.0);
        let acf = exponential_acf(64, dx, dy, 10.0 * dy);
        let start = std::time::Instant::now();
        let texture = acf.texture(ISO_ACF_THRESHOLD).unwrap();
        assert!(start.elapsed().as_secs_f64() < 0.5, "{:?}", start.elapsed());
        let expected = 10.0 * dy * (1.0 / ISO_ACF_THRESHOLD).ln();
        assert!(
            (texture.sal - expected).abs() < 0.05 * expected,
            "{texture:?}"
        );
        assert_eq!(texture.fastest_decay_deg, 90.0, "{texture:?}");
    }

    /// For spacings within a factor √15 of each other the step is `min(dx, dy)/4` in every
    /// direction, so decay lengths are those of a fixed-step walk.
    #[test]
    fn comparable_spacings_keep_the_quarter_cell_step() {
        for (dx, dy) in [(1.0, 1.0), (1.0, 3.8), (2.5e-7, 1e-7)] {
            for degree in 0..180 {
                let (s, c) = f64::from(degree).to_radians().sin_cos();
                assert_eq!(
                    ray_step(dx, dy, c, s),
                    dx.min(dy) / 4.0,
                    "{dx} {dy} {degree}"
                );
            }
        }
        let diagonal = 4f64.atan();
        assert!(ray_step(1.0, 4.0, diagonal.cos(), diagonal.sin()) > 0.25);
    }
}
