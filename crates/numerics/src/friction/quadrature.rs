//! Globally adaptive Gauss–Kronrod (7/15-point) quadrature with a relative tolerance.
//!
//! The integral is the sum over caller-given pieces (the pieces carry the breakpoints of the
//! asperity laws and of the Gaussian). Every piece starts as one interval; the interval with the
//! largest error estimate (see [`kronrod_15`]) is bisected until the summed estimate satisfies
//! `Σ err ≤ rel_tol · |Σ value|` (or `Σ err ≤ abs_floor`, which only matters for an integral that
//! is zero to within underflow).
//! A piece may be *graded at its left end*: x = a + (b − a) u^k (k = 3), which turns an endpoint
//! behaviour x^b (b > −1) into u^{k(b+1)−1}, smooth enough for Gauss rules.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Kronrod abscissae on [−1, 1] (non-negative half, descending; the last is the centre).
const KRONROD_NODES: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];
/// Kronrod weights matching [`KRONROD_NODES`].
const KRONROD_WEIGHTS: [f64; 8] = [
    0.022_935_322_010_529_22,
    0.063_092_092_629_978_55,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];
/// Gauss weights of the 7-point rule living on the odd Kronrod nodes (indices 1, 3, 5, 7).
const GAUSS_WEIGHTS: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// Exponent of the left-end grading x = a + (b − a) u^k.
const GRADING_POWER: i32 = 3;

/// How a piece maps onto its interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Grading {
    /// Plain linear map.
    Uniform,
    /// x = a + (b − a) u³, for an integrable endpoint singularity/kink at `a`.
    LeftEnd,
}

/// One piece of an integral: ∫_a^b f(x) dx.
pub(crate) struct Piece<'a> {
    pub(crate) a: f64,
    pub(crate) b: f64,
    pub(crate) grading: Grading,
    pub(crate) f: &'a dyn Fn(f64) -> f64,
}

/// The pieces between consecutive `points`, all integrating `f`; the first is graded towards its
/// left end, where integrands x^b with b < 1 (or the start of a Gaussian tail) are not smooth.
pub(crate) fn pieces_graded_at_start<'a>(
    points: &[f64],
    f: &'a dyn Fn(f64) -> f64,
) -> Vec<Piece<'a>> {
    points
        .windows(2)
        .enumerate()
        .map(|(i, w)| Piece {
            a: w[0],
            b: w[1],
            grading: if i == 0 {
                Grading::LeftEnd
            } else {
                Grading::Uniform
            },
            f,
        })
        .collect()
}

/// Outcome of an adaptive integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuadratureOutcome {
    /// Integral value.
    pub value: f64,
    /// Summed Kronrod–Gauss error estimate (absolute).
    pub error: f64,
    /// Number of integrand evaluations.
    pub evaluations: usize,
    /// Whether the relative tolerance was met within the interval budget.
    pub converged: bool,
}

/// Maximum number of live subintervals before giving up.
const MAX_INTERVALS: usize = 4000;

struct Interval {
    piece: usize,
    lo: f64,
    hi: f64,
    value: f64,
    error: f64,
}

impl PartialEq for Interval {
    fn eq(&self, other: &Self) -> bool {
        self.error.total_cmp(&other.error) == Ordering::Equal
    }
}
impl Eq for Interval {}
impl PartialOrd for Interval {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Interval {
    fn cmp(&self, other: &Self) -> Ordering {
        self.error.total_cmp(&other.error)
    }
}

/// Evaluate the integrand of a piece at its internal coordinate (u for graded pieces).
fn mapped(piece: &Piece<'_>, t: f64) -> f64 {
    match piece.grading {
        Grading::Uniform => (piece.f)(t),
        Grading::LeftEnd => {
            let width = piece.b - piece.a;
            let k = f64::from(GRADING_POWER);
            let x = piece.a + width * t.powi(GRADING_POWER);
            (piece.f)(x) * width * k * t.powi(GRADING_POWER - 1)
        }
    }
}

/// Apply the 7/15 rule on [lo, hi] of a piece's internal coordinate; returns (K15, error).
///
/// Error estimate (the QUADPACK QK15 heuristic): with e = |K15 − G7| and the spread
/// r = ∫|f − mean f| by the Kronrod rule, err = r · min(1, (200 e / r)^1.5), floored at
/// 50 ε_mach ∫|f| (rounding). For smooth integrands this tracks the true error of K15, which is far
/// smaller than e; correctness at 1e-8 is verified against independent Simpson quadrature in the
/// test suite.
fn kronrod_15(piece: &Piece<'_>, lo: f64, hi: f64) -> (f64, f64) {
    let centre = 0.5 * (lo + hi);
    let half = 0.5 * (hi - lo);
    let f_centre = mapped(piece, centre);
    let mut pairs = [(0.0, 0.0); 7];
    let mut kronrod = KRONROD_WEIGHTS[7] * f_centre;
    let mut gauss = GAUSS_WEIGHTS[3] * f_centre;
    let mut absolute = KRONROD_WEIGHTS[7] * f_centre.abs();
    for (j, ((&node, &weight), pair)) in KRONROD_NODES
        .iter()
        .zip(KRONROD_WEIGHTS.iter())
        .zip(pairs.iter_mut())
        .enumerate()
    {
        let dx = half * node;
        let (left, right) = (mapped(piece, centre - dx), mapped(piece, centre + dx));
        *pair = (left, right);
        kronrod += weight * (left + right);
        absolute += weight * (left.abs() + right.abs());
        if j % 2 == 1 {
            gauss += GAUSS_WEIGHTS[j / 2] * (left + right);
        }
    }
    let mean = 0.5 * kronrod;
    let mut spread = KRONROD_WEIGHTS[7] * (f_centre - mean).abs();
    for (&weight, &(left, right)) in KRONROD_WEIGHTS.iter().zip(pairs.iter()) {
        spread += weight * ((left - mean).abs() + (right - mean).abs());
    }
    let value = kronrod * half;
    let raw = ((kronrod - gauss) * half).abs();
    let spread = spread * half.abs();
    let mut error = raw;
    if spread != 0.0 && raw != 0.0 {
        error = spread * (200.0 * raw / spread).powf(1.5).min(1.0);
    }
    let rounding = 50.0 * f64::EPSILON * absolute * half.abs();
    (value, error.max(rounding))
}

/// Integrate the sum of `pieces` to relative tolerance `rel_tol` (absolute floor `abs_floor`).
pub(crate) fn integrate(pieces: &[Piece<'_>], rel_tol: f64, abs_floor: f64) -> QuadratureOutcome {
    let mut heap = BinaryHeap::new();
    let mut evaluations = 0usize;
    for (index, piece) in pieces.iter().enumerate() {
        if piece.b <= piece.a {
            continue;
        }
        let (lo, hi) = match piece.grading {
            Grading::Uniform => (piece.a, piece.b),
            Grading::LeftEnd => (0.0, 1.0),
        };
        let (value, error) = kronrod_15(piece, lo, hi);
        evaluations += 15;
        heap.push(Interval {
            piece: index,
            lo,
            hi,
            value,
            error,
        });
    }
    loop {
        let total: f64 = heap.iter().map(|iv| iv.value).sum();
        let error: f64 = heap.iter().map(|iv| iv.error).sum();
        let done = error <= rel_tol * total.abs() || error <= abs_floor;
        if done || heap.len() >= MAX_INTERVALS {
            return QuadratureOutcome {
                value: total,
                error,
                evaluations,
                converged: done,
            };
        }
        let Some(worst) = heap.pop() else {
            return QuadratureOutcome {
                value: 0.0,
                error: 0.0,
                evaluations,
                converged: true,
            };
        };
        let Some(piece) = pieces.get(worst.piece) else {
            return QuadratureOutcome {
                value: total,
                error,
                evaluations,
                converged: false,
            };
        };
        let mid = 0.5 * (worst.lo + worst.hi);
        if mid <= worst.lo || mid >= worst.hi {
            // The interval cannot be split further in floating point: keep its estimate and stop.
            heap.push(worst);
            let total: f64 = heap.iter().map(|iv| iv.value).sum();
            let error: f64 = heap.iter().map(|iv| iv.error).sum();
            return QuadratureOutcome {
                value: total,
                error,
                evaluations,
                converged: false,
            };
        }
        for (lo, hi) in [(worst.lo, mid), (mid, worst.hi)] {
            let (value, error) = kronrod_15(piece, lo, hi);
            evaluations += 15;
            heap.push(Interval {
                piece: worst.piece,
                lo,
                hi,
                value,
                error,
            });
        }
    }
}

/// Sorted, de-duplicated breakpoints of (lo, hi) drawn from `candidates` (end points included).
pub(crate) fn breakpoints(lo: f64, hi: f64, candidates: &[f64]) -> Vec<f64> {
    if hi.partial_cmp(&lo) != Some(Ordering::Greater) {
        return Vec::new();
    }
    let mut points: Vec<f64> = candidates
        .iter()
        .copied()
        .filter(|p| p.is_finite() && *p > lo && *p < hi)
        .collect();
    points.push(lo);
    points.push(hi);
    points.sort_by(f64::total_cmp);
    points.dedup_by(|a, b| (*a - *b).abs() <= 1e-14 * b.abs().max(1e-300));
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 15-point Kronrod rule is exact for polynomials of degree ≤ 22 and the 7-point Gauss
    /// rule for degree ≤ 13; x^12 is integrated exactly by both (to rounding, hence 1e-14).
    #[test]
    fn rules_integrate_polynomials_exactly() {
        let f = |x: f64| x.powi(12);
        let piece = Piece {
            a: 0.0,
            b: 2.0,
            grading: Grading::Uniform,
            f: &f,
        };
        let (value, error) = kronrod_15(&piece, 0.0, 2.0);
        let exact = 2f64.powi(13) / 13.0;
        assert!((value - exact).abs() <= 1e-14 * exact);
        assert!(error <= 1e-12 * exact);
    }

    /// An x^0.3 endpoint singularity on a graded piece reaches 1e-10 relative
    /// (exact value 1/1.3; the slack 1e-10 is the requested tolerance).
    #[test]
    fn graded_piece_handles_endpoint_power() {
        let f = |x: f64| x.powf(0.3);
        let pieces = [Piece {
            a: 0.0,
            b: 1.0,
            grading: Grading::LeftEnd,
            f: &f,
        }];
        let out = integrate(&pieces, 1e-10, 0.0);
        assert!(out.converged);
        assert!((out.value - 1.0 / 1.3).abs() <= 1e-10 / 1.3);
    }
}
