//! Bracketed scalar solvers used by the separation solve: Brent's root finder and a golden-section
//! minimiser (for the pull-off load). Both report their iteration counts.

/// A converged root of f on a bracket.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Root {
    pub(crate) x: f64,
    pub(crate) f: f64,
    pub(crate) iterations: usize,
}

/// Stopping rules of [`brent`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BrentTolerances {
    /// Absolute tolerance on x.
    pub(crate) x_tol: f64,
    /// Stop once |f(x)| ≤ f_tol.
    pub(crate) f_tol: f64,
    /// Maximum evaluations of f after the two given.
    pub(crate) max_iterations: usize,
}

/// Brent's method (inverse quadratic interpolation / secant / bisection) on [a, b] with f(a), f(b)
/// of opposite sign (or one zero). Stops when the bracket half-width is ≤ 2·ε_mach·|x| + x_tol/2
/// or |f(x)| ≤ f_tol; at most `max_iterations` evaluations of f after the two given.
pub(crate) fn brent<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    fa: f64,
    fb: f64,
    tolerances: BrentTolerances,
) -> Result<Root, E> {
    let BrentTolerances {
        x_tol,
        f_tol,
        max_iterations,
    } = tolerances;
    let (mut a, mut b, mut fa, mut fb) = (a, b, fa, fb);
    let (mut c, mut fc) = (a, fa);
    let mut step = b - a;
    let mut previous_step = step;
    for iteration in 0..=max_iterations {
        if (fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0) {
            c = a;
            fc = fa;
            step = b - a;
            previous_step = step;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 0.5 * x_tol;
        let half = 0.5 * (c - b);
        if half.abs() <= tol || fb.abs() <= f_tol || iteration == max_iterations {
            return Ok(Root {
                x: b,
                f: fb,
                iterations: iteration,
            });
        }
        (step, previous_step) =
            next_step([a, b, c], [fa, fb, fc], half, tol, (step, previous_step));
        a = b;
        fa = fb;
        b += if step.abs() > tol {
            step
        } else {
            tol.copysign(half)
        };
        fb = f(b)?;
    }
    Ok(Root {
        x: b,
        f: fb,
        iterations: max_iterations,
    })
}

/// Brent's next step from `b` and the step before it: inverse quadratic interpolation through
/// `(a, b, c)` (the secant when `a = c`) where it stays well inside the bracket and shrinks
/// fast enough, else bisection (`half`, half the bracket towards `c`).
fn next_step(
    [a, b, c]: [f64; 3],
    [fa, fb, fc]: [f64; 3],
    half: f64,
    tol: f64,
    (step, previous_step): (f64, f64),
) -> (f64, f64) {
    // Negated as written (not as `<`), so a NaN takes bisection.
    if !(previous_step.abs() >= tol && fa.abs() > fb.abs()) {
        return (half, half);
    }
    let s = fb / fa;
    let (mut p, mut q) = if a == c {
        (2.0 * half * s, 1.0 - s)
    } else {
        let q = fa / fc;
        let r = fb / fc;
        (
            s * (2.0 * half * q * (q - r) - (b - a) * (r - 1.0)),
            (q - 1.0) * (r - 1.0) * (s - 1.0),
        )
    };
    if p > 0.0 {
        q = -q;
    }
    p = p.abs();
    if 2.0 * p < (3.0 * half * q - (tol * q).abs()).min((previous_step * q).abs()) {
        (p / q, step)
    } else {
        (half, half)
    }
}

/// Golden-section minimisation of f on [a, b] until b − a ≤ x_tol; returns (x, f(x), iterations).
pub(crate) fn golden_minimum<E>(
    f: &mut dyn FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    x_tol: f64,
) -> Result<(f64, f64, usize), E> {
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (a, b);
    let mut x1 = b - ratio * (b - a);
    let mut x2 = a + ratio * (b - a);
    let mut f1 = f(x1)?;
    let mut f2 = f(x2)?;
    let mut iterations = 0;
    while b - a > x_tol && iterations < 200 {
        iterations += 1;
        if f1 <= f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - ratio * (b - a);
            f1 = f(x1)?;
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + ratio * (b - a);
            f2 = f(x2)?;
        }
    }
    Ok(if f1 <= f2 {
        (x1, f1, iterations)
    } else {
        (x2, f2, iterations)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Root of x³ − 2 on [0, 2]: exact 2^(1/3); x_tol 1e-14 bounds the error.
    #[test]
    fn brent_finds_cube_root() {
        let mut f = |x: f64| -> Result<f64, ()> { Ok(x * x * x - 2.0) };
        let root = brent(
            &mut f,
            0.0,
            2.0,
            -2.0,
            6.0,
            BrentTolerances {
                x_tol: 1e-14,
                f_tol: 0.0,
                max_iterations: 100,
            },
        )
        .unwrap_or(Root {
            x: 0.0,
            f: 1.0,
            iterations: 0,
        });
        assert!((root.x - 2f64.cbrt()).abs() < 1e-13);
        assert!(root.iterations < 20);
    }

    /// Minimum of (x − 0.3)² on [−1, 2] to 1e-10.
    #[test]
    fn golden_finds_parabola_minimum() {
        let mut f = |x: f64| -> Result<f64, ()> { Ok((x - 0.3) * (x - 0.3)) };
        let (x, _, _) = golden_minimum(&mut f, -1.0, 2.0, 1e-10).unwrap_or((0.0, 0.0, 0));
        assert!((x - 0.3).abs() < 1e-9);
    }
}
