//! Least-squares fit of a paraboloid `z = c₀ + c₁u + c₂v + c₃u² + c₄uv + c₅v²` to scattered
//! points (the contact spots' radii, `contact_spots`).

/// Normal equations `(Σ φ φᵀ) c = Σ φ z` of the paraboloid, `φ = (1, u, v, u², u v, v²)`.
#[derive(Default)]
pub(crate) struct NormalEquations {
    a: [[f64; 6]; 6],
    b: [f64; 6],
}

impl NormalEquations {
    /// Adds the point `(u, v)` of height `z`.
    pub(crate) fn add(&mut self, u: f64, v: f64, z: f64) {
        let phi = [1.0, u, v, u * u, u * v, v * v];
        for (row, (b, pr)) in self.a.iter_mut().zip(self.b.iter_mut().zip(phi)) {
            for (a, pc) in row.iter_mut().zip(phi) {
                *a += pr * pc;
            }
            *b += pr * z;
        }
    }

    /// Gaussian elimination with partial pivoting; `None` when a pivot is below `1e-12` times the
    /// number of points (`a₀₀`; every entry is at most that since `|u|, |v| ≤ 1`).
    pub(crate) fn solve(mut self) -> Option<[f64; 6]> {
        let tolerance = 1e-12 * self.a[0][0];
        for k in 0..6 {
            let pivot =
                (k..6).max_by(|&r, &s| self.a[r][k].abs().total_cmp(&self.a[s][k].abs()))?;
            if self.a[pivot][k].abs() <= tolerance {
                return None;
            }
            self.a.swap(k, pivot);
            self.b.swap(k, pivot);
            let (upper, lower) = self.a.split_at_mut(k + 1);
            let (b_upper, b_lower) = self.b.split_at_mut(k + 1);
            let (row_k, b_k) = (&upper[k], b_upper[k]);
            for (row, b) in lower.iter_mut().zip(b_lower) {
                let f = row[k] / row_k[k];
                for (x, y) in row.iter_mut().zip(row_k).skip(k) {
                    *x -= f * y;
                }
                *b -= f * b_k;
            }
        }
        let mut c = [0.0; 6];
        for k in (0..6).rev() {
            let tail: f64 = (k + 1..6).map(|j| self.a[k][j] * c[j]).sum();
            c[k] = (self.b[k] - tail) / self.a[k][k];
        }
        Some(c)
    }
}
