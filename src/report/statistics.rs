//! Replicate statistics: mean and sample standard deviation.

/// Mean ± sample standard deviation of a group of replicates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    pub mean: f64,
    /// Sample standard deviation s = √(Σ(xᵢ − x̄)² / (n − 1)); `None` for a single value.
    pub std: Option<f64>,
    pub n: usize,
}

impl Summary {
    /// The summary of the finite values; `None` when there are none.
    pub fn of(values: &[f64]) -> Option<Self> {
        let finite: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        let n = finite.len();
        if n == 0 {
            return None;
        }
        let mean = finite.iter().sum::<f64>() / n as f64;
        let std = (n > 1).then(|| {
            (finite.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
        });
        Some(Self { mean, std, n })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_standard_deviation_uses_n_minus_one() {
        let s = Summary::of(&[1.0, 2.0, 3.0, f64::NAN]).unwrap();
        assert_eq!((s.mean, s.std, s.n), (2.0, Some(1.0), 3));
        assert_eq!(Summary::of(&[4.0]).unwrap().std, None);
        assert!(Summary::of(&[]).is_none());
    }
}
