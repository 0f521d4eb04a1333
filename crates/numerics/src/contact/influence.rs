//! Elastic half-space influence operators: pressure → composite normal displacement.

use std::f64::consts::PI;

use super::transforms::{single_transforms, Precision, Transforms};
use crate::fft2::{fast_even_length, FftFailure, RealFft2d, RowSink, RowSource};

/// Lateral boundary condition of the contact domain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Boundary {
    /// The grid is one period of a doubly periodic surface. Spectral kernel
    /// `û(q) = 2 p̂(q) / (E* |q|)` (Johnson 1985; Stanley & Kato 1997); the mean (`q = 0`) term of
    /// the displacement is undetermined on a periodic half-space and set to zero: displacements
    /// are measured from the mean displaced surface and the load is fixed by load control.
    Periodic,
    /// An isolated patch on an infinite half-space, outside of which the pressure is zero.
    /// Discrete convolution–FFT (DC-FFT, Liu, Wang & Liu 2000, Wear 243) on a grid zero-padded to
    /// at least `2nx × 2ny` (the next even lengths with prime factors 2, 3, 5 and 7 only, see
    /// [`fast_even_length`]: `2n − 1` suffice for the linear convolution of `n` points, so the
    /// padding changes nothing but the speed) with the influence coefficients of uniform pressure
    /// on one `dx × dy` pixel
    /// (Love 1929; Johnson 1985, eq. 3.25):
    /// `K(x, y) = 1/(π E*) Σ± G(x ± dx/2, y ± dy/2)`,
    /// `G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)`. Displacements are absolute (zero at infinity).
    NonPeriodic,
}

/// `G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)`, an antiderivative of `1/√(X² + Y²)` in `X` and
/// `Y` valid in all four quadrants (`∂G/∂Y = asinh(X/|Y|)`; each term vanishes with its factor).
fn love_antiderivative(x: f64, y: f64) -> f64 {
    let first = if x == 0.0 {
        0.0
    } else {
        x * (y / x.abs()).asinh()
    };
    let second = if y == 0.0 {
        0.0
    } else {
        y * (x / y.abs()).asinh()
    };
    first + second
}

/// Displacement in metres at `(x, y)` from the centre of a `dx × dy` pixel loaded by a uniform
/// pressure of 1 Pa, on a half-space of composite modulus `E* = 1 Pa` (Love's solution).
pub(crate) fn pixel_influence(x: f64, y: f64, dx: f64, dy: f64) -> f64 {
    let (a, b) = (0.5 * dx, 0.5 * dy);
    (love_antiderivative(x + a, y + b)
        - love_antiderivative(x + a, y - b)
        - love_antiderivative(x - a, y + b)
        + love_antiderivative(x - a, y - b))
        / PI
}

/// Linear operator `u = K p` from pressures (Pa) on the `ny × nx` grid to the composite normal
/// displacement `u = u₁ + u₂` (m) of the two surfaces, evaluated with one real FFT pair, in
/// double precision or (where the kernels fit, see `transforms.rs`) in single precision, as
/// the caller sets ([`Self::set_precision`]).
#[derive(Debug)]
pub(crate) struct InfluenceOperator {
    double: Transforms<f64>,
    single: Option<Transforms<f32>>,
    /// The precision of the next transforms.
    precision: Precision,
    /// The precision of the last forward transform kept for a `finish_*`.
    kept: Precision,
    nx: usize,
    ny: usize,
    boundary: Boundary,
    /// The influence coefficient `K(x, y)` of every offset magnitude `(|x|, |y|)` in pixels
    /// (`K` is even in `x` and in `y`), rows of `coefficient_stride` values: the displacement
    /// under a unit pressure on pixel `(0, 0)` for offsets `0..nx` × `0..ny`, on a periodic grid
    /// only up to half the period (the shorter way round).
    coefficients: Vec<f64>,
    coefficient_stride: usize,
    /// Real 2-D FFTs run so far (forward or inverse; a full convolution is two).
    transforms: usize,
}

/// `norm² / k` where `k > 0` (a spectral kernel with normalisation `norm` included), else 0.
fn reciprocal_kernel(kernel: &[f64], norm: f64) -> Vec<f64> {
    let floor = kernel.iter().fold(0.0f64, |a, &b| a.max(b)) * 1e-12;
    kernel
        .iter()
        .map(|&k| if k > floor { norm * norm / k } else { 0.0 })
        .collect()
}

/// An operator's FFT, kernel and optional preconditioner kernel.
type Kernels = (RealFft2d, Vec<f64>, Option<Vec<f64>>);

/// The FFT, the spectral kernel and (with `preconditioner`) the preconditioner's kernel of a
/// periodic grid: `2/(E* |q|)` with `q` the wavevector, zero at `q = 0` (the mean pressure
/// moves the body, not the gap).
fn periodic_kernels(
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    composite_modulus: f64,
    preconditioner: bool,
) -> Result<Kernels, FftFailure> {
    let fft = RealFft2d::for_convolution(nx, ny);
    let nxc = nx / 2 + 1;
    let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
    let norm = 1.0 / (nx as f64 * ny as f64);
    let mut kernel = vec![0.0; nxc * ny];
    for kx in 0..nxc {
        for ky in 0..ny {
            let ky_signed = if ky <= ny / 2 {
                ky as f64
            } else {
                ky as f64 - ny as f64
            };
            let q = 2.0 * PI * ((kx as f64 / lx).powi(2) + (ky_signed / ly).powi(2)).sqrt();
            if q > 0.0 {
                kernel[kx * ny + ky] = 2.0 / (composite_modulus * q) * norm;
            }
        }
    }
    let inverse = preconditioner
        .then(|| fft.convolution_kernel(reciprocal_kernel(&kernel, norm)))
        .transpose()?;
    let kernel = fft.convolution_kernel(kernel)?;
    Ok((fft, kernel, inverse))
}

/// The FFT, the spectral kernel and (with `preconditioner`) the preconditioner's kernel of a
/// non-periodic grid: Love's pixel influence on a grid zero-padded to at least twice the size
/// (DC-FFT).
fn non_periodic_kernels(
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    composite_modulus: f64,
    preconditioner: bool,
) -> Result<Kernels, FftFailure> {
    let (mx, my) = (fast_even_length(2 * nx), fast_even_length(2 * ny));
    let mut stencil = vec![0.0; mx * my];
    // Pixel offset of padded index `j` on a circle of even length `m`: the stencil is
    // even (`j` and `m − j` hold opposite offsets), so its spectrum is real.
    let offset = |j: usize, m: usize| -> f64 {
        if j < m / 2 {
            j as f64
        } else {
            j as f64 - m as f64
        }
    };
    for jy in 0..my {
        let y = offset(jy, my) * dy;
        for jx in 0..mx {
            let x = offset(jx, mx) * dx;
            stencil[jy * mx + jx] = pixel_influence(x, y, dx, dy) / composite_modulus;
        }
    }
    let mut fft = RealFft2d::for_convolution(mx, my);
    let norm = 1.0 / (mx as f64 * my as f64);
    let spectral: Vec<f64> = fft.forward(&stencil)?.iter().map(|c| c.re * norm).collect();
    let inverse = preconditioner
        .then(|| fft.convolution_kernel(reciprocal_kernel(&spectral, norm)))
        .transpose()?;
    let kernel = fft.convolution_kernel(spectral)?;
    Ok((fft, kernel, inverse))
}

/// Runs `$body` with `$t` bound to the operator's transforms of precision `$precision`
/// (`Transforms<f64>` or `Transforms<f32>`); single precision falls back to double where the
/// operator has none.
macro_rules! in_precision {
    ($self:ident, $precision:expr, |$t:ident| $body:expr) => {
        match ($precision, $self.single.as_mut()) {
            (Precision::Single, Some($t)) => $body,
            _ => {
                let $t = &mut $self.double;
                $body
            }
        }
    };
}

impl InfluenceOperator {
    /// Builds the kernel for a grid `nx × ny` of pixel size `dx × dy` (m) and composite modulus
    /// `E*` (Pa); with `preconditioner`, also the kernel of [`Self::precondition_rows_into`]
    /// (one more kernel array, and with padded columns one more padded transform of it, which
    /// only elastic contacts use). The single-precision transforms are planned beside the
    /// double-precision ones (see [`Self::set_precision`]); the operator starts in double
    /// precision.
    pub(crate) fn new(
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        composite_modulus: f64,
        boundary: Boundary,
        preconditioner: bool,
    ) -> Result<Self, FftFailure> {
        let mut operator =
            Self::double_only(nx, ny, dx, dy, composite_modulus, boundary, preconditioner)?;
        operator.single = single_transforms(
            &operator.double.fft,
            &operator.double.kernel,
            operator.double.inverse_kernel.as_deref(),
        );
        let mut impulse = vec![0.0; nx * ny];
        let mut response = vec![0.0; nx * ny];
        impulse[0] = 1.0;
        operator.apply(&impulse, &mut response)?;
        let (stride, rows) = match boundary {
            Boundary::Periodic => (nx / 2 + 1, ny / 2 + 1),
            Boundary::NonPeriodic => (nx, ny),
        };
        operator.coefficients = response
            .chunks(nx)
            .take(rows)
            .flat_map(|row| &row[..stride])
            .copied()
            .collect();
        operator.coefficient_stride = stride;
        Ok(operator)
    }

    /// [`Self::new`]'s operator in double precision only and without the coefficients: what
    /// [`Self::apply`] needs (`derived::DisplacementOperator`), without the single-precision
    /// transforms and the impulse response.
    pub(crate) fn double_only(
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        composite_modulus: f64,
        boundary: Boundary,
        preconditioner: bool,
    ) -> Result<Self, FftFailure> {
        let (fft, kernel, inverse_kernel) = match boundary {
            Boundary::Periodic => {
                periodic_kernels(nx, ny, dx, dy, composite_modulus, preconditioner)?
            }
            Boundary::NonPeriodic => {
                non_periodic_kernels(nx, ny, dx, dy, composite_modulus, preconditioner)?
            }
        };
        Ok(Self {
            double: Transforms {
                fft,
                kernel,
                inverse_kernel,
            },
            single: None,
            precision: Precision::Double,
            kept: Precision::Double,
            nx,
            ny,
            boundary,
            coefficients: Vec::new(),
            coefficient_stride: 0,
            transforms: 0,
        })
    }

    /// Whether the operator has single-precision transforms (its kernels fit their range,
    /// `transforms.rs`).
    pub(crate) fn has_single(&self) -> bool {
        self.single.is_some()
    }

    /// The precision of the transforms from now on (single precision only where
    /// [`Self::has_single`]; otherwise double). A `finish_*` still uses the precision of the
    /// `start_*` it finishes, which must come after the last switch: a switch gives back the
    /// row and column buffers of the precision left (`RealFft2d::release_buffers`, the bulk of
    /// a plan's memory), so that one contact never holds both precisions' buffers at once, and
    /// finishing a transform started before it is an error.
    pub(crate) fn set_precision(&mut self, precision: Precision) {
        let precision = if self.single.is_some() {
            precision
        } else {
            Precision::Double
        };
        if precision != self.precision {
            match self.precision {
                Precision::Double => self.double.fft.release_buffers(),
                Precision::Single => {
                    if let Some(single) = self.single.as_mut() {
                        single.fft.release_buffers();
                    }
                }
            }
        }
        self.precision = precision;
    }

    /// `displacement = K pressure`, both `ny × nx` row-major, in double precision.
    pub(crate) fn apply(
        &mut self,
        pressure: &[f64],
        displacement: &mut [f64],
    ) -> Result<(), FftFailure> {
        let t = &mut self.double;
        t.fft
            .convolve(pressure, &t.kernel, displacement, self.nx, self.ny)?;
        self.transforms += 2;
        Ok(())
    }

    /// `out = M r`, `M` the convolution with the reciprocal of the kernel's spectrum (zero where it
    /// vanishes), rows of `r` from `fill`, output rows through `sink`. An operator built without
    /// its preconditioner fails.
    pub(crate) fn precondition_rows_into<F: RowSource, S: RowSink>(
        &mut self,
        fill: &F,
        out: &mut [f64],
        sink: &S,
    ) -> Result<&[f64], FftFailure> {
        self.transforms += 2;
        let block = (self.nx, self.ny);
        in_precision!(self, self.precision, |t| t
            .precondition_rows_into(fill, out, block, sink))
    }

    /// [`Self::apply`] to the pressure whose rows `fill` supplies, the displacement rows going
    /// through `sink`; returns the sink's value of every row.
    pub(crate) fn apply_rows_into<F: RowSource, S: RowSink>(
        &mut self,
        fill: &F,
        displacement: &mut [f64],
        sink: &S,
    ) -> Result<&[f64], FftFailure> {
        self.transforms += 2;
        let (nx, ny) = (self.nx, self.ny);
        in_precision!(self, self.precision, |t| t.fft.convolve_rows_into(
            fill,
            &t.kernel,
            displacement,
            nx,
            ny,
            sink
        ))
    }

    /// First half of `displacement = K pressure`: transforms `pressure` (kept for
    /// [`Self::finish_apply`]) and returns the quadratic form `pressureᵀ K pressure` in Pa·m
    /// (Parseval; one forward FFT).
    pub(crate) fn start_apply(&mut self, pressure: &[f64]) -> Result<f64, FftFailure> {
        self.transforms += 1;
        self.kept = self.precision;
        let (nx, ny) = (self.nx, self.ny);
        in_precision!(self, self.precision, |t| t
            .fft
            .start_convolve(pressure, &t.kernel, nx, ny))
    }

    /// [`Self::start_apply`] to the pressure whose rows `fill` supplies.
    pub(crate) fn start_apply_rows<F: RowSource>(&mut self, fill: &F) -> Result<f64, FftFailure> {
        self.transforms += 1;
        self.kept = self.precision;
        let (nx, ny) = (self.nx, self.ny);
        in_precision!(self, self.precision, |t| t
            .fft
            .start_convolve_rows(fill, &t.kernel, nx, ny))
    }

    /// Second half of `displacement = K pressure` for the pressure of the last
    /// [`Self::start_apply`], in its precision (one inverse FFT; bit-identical to
    /// [`Self::apply`] in double precision).
    pub(crate) fn finish_apply(&mut self, displacement: &mut [f64]) -> Result<(), FftFailure> {
        self.transforms += 1;
        let (nx, ny) = (self.nx, self.ny);
        in_precision!(self, self.kept, |t| t.fft.finish_convolve(
            &t.kernel,
            displacement,
            nx,
            ny
        ))
    }

    /// [`Self::finish_apply`] with the displacement rows going through `sink`; returns the
    /// sink's value of every row.
    pub(crate) fn finish_apply_into<S: RowSink>(
        &mut self,
        displacement: &mut [f64],
        sink: &S,
    ) -> Result<&[f64], FftFailure> {
        self.transforms += 1;
        let (nx, ny) = (self.nx, self.ny);
        in_precision!(self, self.kept, |t| t.fft.finish_convolve_into(
            &t.kernel,
            displacement,
            nx,
            ny,
            sink
        ))
    }

    /// Real 2-D FFTs (forward or inverse; a full convolution is two) this operator has run,
    /// its construction included: the solver counts its work as differences of this counter,
    /// so no caller counts transforms by hand.
    pub(crate) fn transforms(&self) -> usize {
        self.transforms
    }

    /// Displacement of a pixel under a unit pressure on itself, `K₀₀` in m/Pa (> 0).
    pub(crate) fn self_influence(&self) -> f64 {
        self.coefficients[0]
    }

    /// `K(r_a − r_b)` in m/Pa for the grid points `a = (ix, iy)` and `b`, read from the
    /// coefficients at the offset's magnitude (on a periodic grid the shorter way round: `K` is
    /// even, so both ways hold the same coefficient up to round-off, and taking one makes
    /// `K(r_a − r_b)` and `K(r_b − r_a)` the same number). It equals the FFT operator's
    /// coefficient up to round-off.
    #[inline]
    pub(crate) fn coefficient_between(&self, a: (usize, usize), b: (usize, usize)) -> f64 {
        let offset = |p: usize, q: usize, n: usize| {
            let d = p.abs_diff(q);
            match self.boundary {
                Boundary::Periodic => d.min(n - d),
                Boundary::NonPeriodic => d,
            }
        };
        let (x, y) = (offset(a.0, b.0, self.nx), offset(a.1, b.1, self.ny));
        self.coefficients[y * self.coefficient_stride + x]
    }

    /// Grid points per row.
    pub(crate) fn nx(&self) -> usize {
        self.nx
    }
}

#[cfg(test)]
#[path = "influence_tests.rs"]
mod tests;
