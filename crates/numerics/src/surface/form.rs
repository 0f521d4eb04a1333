//! Form removal (the F-operator): least-squares plane or full 2-D polynomial of degree `n`, fitted to
//! the valid points only and subtracted.
//!
//! The form is `f(x, y) = Σ_{i+j ≤ n} c_ij P_i(u) P_j(v)` with Legendre polynomials `P_k` of the
//! normalised coordinates `u = 2·ix/(nx−1) − 1`, `v = 2·iy/(ny−1) − 1` (both in `[−1, 1]`). This spans
//! the same space as the monomials `x^i y^j, i + j ≤ n` but keeps the normal equations well conditioned.
//! The coefficients minimise `Σ_valid (z − f)²`; they are found from the normal equations
//! `G c = b`, `G_pq = Σ_valid φ_p φ_q`, `b_p = Σ_valid z φ_p`, solved by Cholesky factorisation.
//! `G` is accumulated row by row using the separable structure `φ = P_i(u) P_j(v)`, at a cost of
//! `O(nx·ny·(n+1)²)`. Degree 1 is the least-squares plane (ISO 25178-2 "F-operator: plane").
//! Missing points stay missing in the result.

use ndarray::Array2;

use super::{HeightMap, HeightMapError};

/// Highest polynomial degree accepted (66 terms); higher degrees are rarely form, and the cost grows
/// with the square of the number of terms.
pub const MAX_FORM_DEGREE: usize = 10;

/// One fitted term `coefficient · P_x_order(u) · P_y_order(v)` (coefficient in metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegendreTerm {
    /// Legendre order in `u` (x direction).
    pub x_order: usize,
    /// Legendre order in `v` (y direction).
    pub y_order: usize,
    /// Coefficient in metres.
    pub coefficient: f64,
}

/// A height map with its polynomial form removed, and the fitted form.
#[derive(Debug, Clone, PartialEq)]
pub struct FormRemoval {
    /// Residual heights `z − f` (m); missing points remain `NaN`.
    pub surface: HeightMap,
    /// Polynomial degree `n`.
    pub degree: usize,
    /// Fitted terms, ordered by total degree `i + j`, then by decreasing `x_order`.
    pub terms: Vec<LegendreTerm>,
    /// Root-mean-square of the residual over the valid points (m), i.e. `Sq` after form removal.
    pub residual_rms: f64,
}

/// Why a form could not be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FormError {
    #[error("polynomial degree {degree} exceeds the maximum {MAX_FORM_DEGREE}")]
    DegreeTooHigh { degree: usize },
    #[error("degree-{degree} form has {terms} terms but only {valid} valid points")]
    TooFewValidPoints {
        degree: usize,
        terms: usize,
        valid: usize,
    },
    #[error("form removal gave an invalid height map: {0}")]
    HeightMap(#[from] HeightMapError),
    #[error("normal equations of the degree-{degree} fit are singular: the valid points do not determine the form (e.g. all on one line)")]
    Singular { degree: usize },
}

/// Removes the least-squares plane (degree-1 form) fitted to the valid points.
pub fn remove_plane(map: &HeightMap) -> Result<FormRemoval, FormError> {
    remove_polynomial_form(map, 1)
}

/// Removes the least-squares full 2-D polynomial of total degree `degree` fitted to the valid points.
pub fn remove_polynomial_form(map: &HeightMap, degree: usize) -> Result<FormRemoval, FormError> {
    if degree > MAX_FORM_DEGREE {
        return Err(FormError::DegreeTooHigh { degree });
    }
    let orders = term_orders(degree);
    let n_terms = orders.len();
    let z = map.heights();
    let valid = map.nx() * map.ny() - map.missing_count();
    if valid < n_terms {
        return Err(FormError::TooFewValidPoints {
            degree,
            terms: n_terms,
            valid,
        });
    }
    let px = legendre_table(map.nx(), degree);
    let py = legendre_table(map.ny(), degree);
    let (mut gram, rhs) = normal_equations(z, &orders, &px, &py);
    let coefficients =
        solve_cholesky(&mut gram, &rhs, n_terms).ok_or(FormError::Singular { degree })?;

    let (residual, sum_sq) = subtract_form(z, &orders, &coefficients, &px, &py);
    let surface = HeightMap::new(residual, map.dx(), map.dy())?;
    Ok(FormRemoval {
        surface,
        degree,
        terms: orders
            .iter()
            .zip(&coefficients)
            .map(|(&(x_order, y_order), &coefficient)| LegendreTerm {
                x_order,
                y_order,
                coefficient,
            })
            .collect(),
        residual_rms: (sum_sq / valid as f64).sqrt(),
    })
}

/// The normal equations `G c = r` of the least-squares fit of the Legendre products
/// `P_i(x) P_j(y)` (`orders`) to the valid heights of `z`, accumulated row by row: `G` is
/// symmetric, both triangles filled.
fn normal_equations(
    z: &Array2<f64>,
    orders: &[(usize, usize)],
    px: &[Vec<f64>],
    py: &[Vec<f64>],
) -> (Vec<f64>, Vec<f64>) {
    let n_terms = orders.len();
    let k = px.first().map_or(1, Vec::len);
    let mut gram = vec![0.0; n_terms * n_terms];
    let mut rhs = vec![0.0; n_terms];
    let mut row_moments = vec![0.0; k * k];
    let mut row_projection = vec![0.0; k];
    for (iy, row) in z.rows().into_iter().enumerate() {
        row_moments.fill(0.0);
        row_projection.fill(0.0);
        for (ix, &h) in row.iter().enumerate() {
            if h.is_nan() {
                continue;
            }
            let values = &px[ix];
            for (a, &pa) in values.iter().enumerate() {
                row_projection[a] += h * pa;
                for (b, &pb) in values.iter().enumerate().skip(a) {
                    row_moments[a * k + b] += pa * pb;
                }
            }
        }
        for (p, &(ip, jp)) in orders.iter().enumerate() {
            rhs[p] += py[iy][jp] * row_projection[ip];
            for (q, &(iq, jq)) in orders.iter().enumerate().skip(p) {
                let m = row_moments[ip.min(iq) * k + ip.max(iq)];
                gram[p * n_terms + q] += py[iy][jp] * py[iy][jq] * m;
            }
        }
    }
    for p in 0..n_terms {
        for q in 0..p {
            gram[p * n_terms + q] = gram[q * n_terms + p];
        }
    }
    (gram, rhs)
}

/// `z` minus the fitted form (missing points stay missing) and the sum of squared residuals.
fn subtract_form(
    z: &Array2<f64>,
    orders: &[(usize, usize)],
    coefficients: &[f64],
    px: &[Vec<f64>],
    py: &[Vec<f64>],
) -> (Array2<f64>, f64) {
    let k = px.first().map_or(1, Vec::len);
    let mut residual = z.clone();
    let mut sum_sq = 0.0;
    let mut row_coefficients = vec![0.0; k];
    for (iy, mut row) in residual.rows_mut().into_iter().enumerate() {
        row_coefficients.fill(0.0);
        for (&(i, j), &c) in orders.iter().zip(coefficients) {
            row_coefficients[i] += c * py[iy][j];
        }
        let mut row_sum_sq = 0.0;
        for (ix, h) in row.iter_mut().enumerate() {
            if h.is_nan() {
                continue;
            }
            let form: f64 = row_coefficients
                .iter()
                .zip(&px[ix])
                .map(|(c, p)| c * p)
                .sum();
            *h -= form;
            row_sum_sq += *h * *h;
        }
        sum_sq += row_sum_sq;
    }
    (residual, sum_sq)
}

/// `(x_order, y_order)` of every term with `x_order + y_order ≤ degree`, by total degree, then by
/// decreasing x order.
fn term_orders(degree: usize) -> Vec<(usize, usize)> {
    (0..=degree)
        .flat_map(|d| (0..=d).rev().map(move |i| (i, d - i)))
        .collect()
}

/// `table[i][k] = P_k(2 i/(n−1) − 1)` for `i = 0..n`, `k = 0..=degree` (Bonnet's recurrence
/// `(k+1) P_{k+1} = (2k+1) u P_k − k P_{k−1}`). `n ≥ 2` is guaranteed by [`HeightMap`].
fn legendre_table(n: usize, degree: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            let u = 2.0 * i as f64 / (n - 1) as f64 - 1.0;
            let mut values = Vec::with_capacity(degree + 1);
            values.push(1.0);
            if degree >= 1 {
                values.push(u);
            }
            for k in 1..degree {
                let kf = k as f64;
                values.push(((2.0 * kf + 1.0) * u * values[k] - kf * values[k - 1]) / (kf + 1.0));
            }
            values
        })
        .collect()
}

/// Solves the symmetric positive-definite system `a x = b` (`a` row-major `n×n`, overwritten by its
/// Cholesky factor). Returns `None` if a pivot is not positive relative to the diagonal scale
/// (`≤ 1e-12 · max diag`), i.e. the system is singular to working precision.
fn solve_cholesky(a: &mut [f64], b: &[f64], n: usize) -> Option<Vec<f64>> {
    let scale = (0..n).map(|i| a[i * n + i]).fold(0.0, f64::max);
    if scale <= 0.0 {
        return None;
    }
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if d <= 1e-12 * scale {
            return None;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    let mut y = vec![0.0; n];
    for i in 0..n {
        let s: f64 = (0..i).map(|k| a[i * n + k] * y[k]).sum();
        y[i] = (b[i] - s) / a[i * n + i];
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|k| a[k * n + i] * x[k]).sum();
        x[i] = (y[i] - s) / a[i * n + i];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ndarray::Array2;

    #[test]
    fn term_order_and_legendre_values() {
        assert_eq!(
            term_orders(2),
            vec![(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)]
        );
        let t = legendre_table(3, 2);
        // P2(u) = (3u² − 1)/2 at u = −1, 0, 1.
        let p2: Vec<f64> = t.iter().map(|v| v[2]).collect();
        assert_eq!(p2, vec![1.0, -0.5, 1.0]);
    }

    #[test]
    fn singular_when_valid_points_are_collinear() {
        let mut z = Array2::from_elem((4, 4), f64::NAN);
        for i in 0..4 {
            z[[1, i]] = i as f64;
        }
        let map = HeightMap::new(z, 1.0, 1.0).unwrap();
        assert_eq!(remove_plane(&map), Err(FormError::Singular { degree: 1 }));
    }
}
