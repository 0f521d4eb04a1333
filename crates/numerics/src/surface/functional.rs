//! Functional (material ratio) and volume parameters of ISO 25178-2:2012 §4.4–4.5, with the
//! Sk family of ISO 13565-2:1996 applied to the areal material ratio curve.
//!
//! Over the `N` valid points, heights taken from their mean (missing `NaN` points excluded):
//!
//! * **Areal material ratio** `Smr(c)`: the share of the points at or above the height `c`; its
//!   inverse `Smc(mr)`, the height at material ratio `mr`, is the material ratio (Abbott–Firestone)
//!   curve. Discretely the heights sorted in descending order, `z₍₁₎ ≥ … ≥ z₍N₎`, each carry the
//!   share `1/N`, and `Smc` interpolates linearly between the points' mid-ratios `(k − ½)/N`
//!   (held constant outside them).
//! * **Equivalent straight line** (ISO 13565-2 §4.2, ISO 25178-2 Annex B): the central region
//!   is the 40 % of the curve where the secant spanning ΔMr = 40 % (`m = round(0.4 N)` points)
//!   has the least gradient, `z₍k₎ − z₍k+m₎` minimal (the first one on ties); the line is the
//!   least-squares fit (in height) of the curve's points `k … k+m` in that region. `Sk` = its
//!   height difference between `mr = 0` and `mr = 100 %`; its heights there are `c_top` and
//!   `c_bottom`.
//! * `Smr1 = Smr` strictly above `c_top` (the peaks above the core), `Smr2 = Smr(c_bottom)`
//!   (the curve's last ratio at or above the core's bottom).
//! * `Spk = 2 A1 / Smr1`, `A1 = (1/N) Σ (z − c_top)⁺` (the triangle of equal area over the
//!   peaks); `Svk = 2 A2 / (1 − Smr2)`, `A2 = (1/N) Σ (c_bottom − z)⁺`; each 0 when its share is 0.
//! * `Sxp = Smc(p) − Smc(q)`, default `p = 2.5 %`, `q = 50 %` (peak extreme height).
//! * `Vm(p) = (1/N) Σ (z − Smc(p))⁺` and `Vv(p) = (1/N) Σ (Smc(p) − z)⁺`: material and void
//!   volume per unit area (m³/m² = m), i.e. `∫₀ᵖ (Smc(mr) − Smc(p)) dmr` and
//!   `∫ₚ¹ (Smc(p) − Smc(mr)) dmr` on the step curve. `Vmp = Vm(p)`, `Vmc = Vm(q) − Vm(p)`,
//!   `Vvc = Vv(p) − Vv(q)`, `Vvv = Vv(q)` with the defaults `p = 10 %`, `q = 80 %`.

use super::order::deviations_descending;
use super::HeightMap;

/// Material ratio span of the equivalent straight line (ISO 13565-2: 40 %).
pub const EQUIVALENT_LINE_SPAN: f64 = 0.4;

/// The material ratios of `Sxp`, `Vm`/`Vv` (ISO 25178-3 defaults).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FunctionalOptions {
    /// `p` of `Sxp` (default 0.025).
    pub sxp_p: f64,
    /// `q` of `Sxp` (default 0.5).
    pub sxp_q: f64,
    /// `p` of `Vmp`, `Vmc`, `Vvc` (default 0.1).
    pub volume_p: f64,
    /// `q` of `Vmc`, `Vvc`, `Vvv` (default 0.8).
    pub volume_q: f64,
}

impl Default for FunctionalOptions {
    fn default() -> Self {
        Self {
            sxp_p: 0.025,
            sxp_q: 0.5,
            volume_p: 0.1,
            volume_q: 0.8,
        }
    }
}

/// The functional and volume parameters (lengths and volumes per area in m, ratios in [0, 1]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FunctionalParameters {
    /// Core height `Sk`.
    pub sk: f64,
    /// Reduced peak height `Spk`.
    pub spk: f64,
    /// Reduced dale depth `Svk`.
    pub svk: f64,
    /// Material ratio at the top of the core `Smr1`.
    pub smr1: f64,
    /// Material ratio at the bottom of the core `Smr2`.
    pub smr2: f64,
    /// Peak extreme height `Sxp`.
    pub sxp: f64,
    /// Peak material volume `Vmp`.
    pub vmp: f64,
    /// Core material volume `Vmc`.
    pub vmc: f64,
    /// Core void volume `Vvc`.
    pub vvc: f64,
    /// Dale void volume `Vvv`.
    pub vvv: f64,
    /// Height of the equivalent straight line at `mr = 0` (from the mean, m).
    pub core_top: f64,
    /// Height of the equivalent straight line at `mr = 1` (from the mean, m).
    pub core_bottom: f64,
}

/// Why the parameters could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FunctionalError {
    #[error("the height map has fewer than 3 valid (non-NaN) points")]
    TooFewPoints,
    #[error("material ratio `{name}` = {value} is out of range: expected 0 ≤ ratio ≤ 1{order}")]
    InvalidRatio {
        name: &'static str,
        value: f64,
        order: &'static str,
    },
}

/// The areal material ratio curve of a map: its valid heights from their mean, descending.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialRatioCurve {
    heights: Vec<f64>,
}

impl MaterialRatioCurve {
    /// The curve of the valid points of `map`.
    pub fn of(map: &HeightMap) -> Result<Self, FunctionalError> {
        match map.heights().as_slice() {
            Some(heights) => Self::from_slice(heights),
            None => Self::from_heights(map.heights().iter().copied()),
        }
    }

    /// The curve of the non-`NaN` values of `heights`.
    pub fn from_heights(heights: impl Iterator<Item = f64>) -> Result<Self, FunctionalError> {
        Self::from_slice(&heights.collect::<Vec<f64>>())
    }

    /// The curve of the non-`NaN` values of `heights` (sorted by `order::deviations_descending`).
    fn from_slice(heights: &[f64]) -> Result<Self, FunctionalError> {
        let z = deviations_descending(heights);
        if z.len() < 3 {
            return Err(FunctionalError::TooFewPoints);
        }
        Ok(Self { heights: z })
    }

    /// The curve's heights (descending), e.g. to reuse their memory once the curve is done with.
    pub fn into_heights(self) -> Vec<f64> {
        self.heights
    }

    /// Number of valid points `N`.
    pub fn len(&self) -> usize {
        self.heights.len()
    }

    /// Always `false`: a curve has at least 3 points.
    pub fn is_empty(&self) -> bool {
        self.heights.is_empty()
    }

    /// `Smc(mr)`: the height (m, from the mean) at material ratio `mr` ∈ [0, 1] (module docs).
    pub fn height_at(&self, mr: f64) -> f64 {
        let n = self.heights.len();
        let position = (mr * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
        let k = position.floor() as usize;
        let t = position - k as f64;
        match self.heights.get(k + 1) {
            Some(next) if t > 0.0 => self.heights[k] + t * (next - self.heights[k]),
            _ => self.heights[k],
        }
    }

    /// Share of the points strictly above `c`.
    pub fn ratio_above(&self, c: f64) -> f64 {
        self.heights.partition_point(|&z| z > c) as f64 / self.heights.len() as f64
    }

    /// `Smr(c)`: share of the points at or above `c`.
    pub fn ratio_at_or_above(&self, c: f64) -> f64 {
        self.heights.partition_point(|&z| z >= c) as f64 / self.heights.len() as f64
    }

    /// `Vm(p)`: material volume per unit area above `Smc(p)` (m³/m²).
    pub fn material_volume(&self, p: f64) -> f64 {
        self.mean_excess_above(self.height_at(p))
    }

    /// `Vv(p)`: void volume per unit area below `Smc(p)` (m³/m²).
    pub fn void_volume(&self, p: f64) -> f64 {
        self.mean_deficit_below(self.height_at(p))
    }

    /// `(1/N) Σ (z − c)⁺`: the points above `c` are a prefix of the descending heights, the
    /// only terms that are not zero (summed in the curve's order, from `+0`).
    fn mean_excess_above(&self, c: f64) -> f64 {
        let above = self.heights.partition_point(|&z| z > c);
        let sum = self.heights[..above]
            .iter()
            .fold(0.0, |sum, &z| sum + (z - c));
        sum / self.heights.len() as f64
    }

    /// `(1/N) Σ (c − z)⁺`: the points below `c` are a suffix of the descending heights.
    fn mean_deficit_below(&self, c: f64) -> f64 {
        let below = self.heights.partition_point(|&z| z >= c);
        let sum = self.heights[below..]
            .iter()
            .fold(0.0, |sum, &z| sum + (c - z));
        sum / self.heights.len() as f64
    }

    /// `(c_top, c_bottom)`: the equivalent straight line at `mr = 0` and `mr = 1` (module docs).
    pub fn equivalent_line(&self) -> (f64, f64) {
        let n = self.heights.len();
        let m = ((EQUIVALENT_LINE_SPAN * n as f64).round() as usize).clamp(1, n - 1);
        let (k, _) = (0..n - m)
            .map(|k| (k, self.heights[k] - self.heights[k + m]))
            .fold(
                (0, f64::INFINITY),
                |best, (k, d)| {
                    if d < best.1 {
                        (k, d)
                    } else {
                        best
                    }
                },
            );
        let (top, slope) = self.least_squares_line(k, k + m);
        (top, top + slope)
    }

    /// `(c(0), dc/dmr)` of the least-squares line through the curve points `first ..= last` at
    /// their mid-ratios. Heights are taken from the first point's and the line through the
    /// centroid, so the sums stay well conditioned and a flat region gives its height exactly.
    fn least_squares_line(&self, first: usize, last: usize) -> (f64, f64) {
        let n = self.heights.len() as f64;
        let base = self.heights[first];
        let points = || (first..=last).map(|k| ((k as f64 + 0.5) / n, self.heights[k] - base));
        let count = (last - first + 1) as f64;
        let (mr_sum, z_sum) = points().fold((0.0, 0.0), |(a, b), (mr, z)| (a + mr, b + z));
        let (mr_mean, z_mean) = (mr_sum / count, z_sum / count);
        let (sxy, sxx) = points().fold((0.0, 0.0), |(sxy, sxx), (mr, z)| {
            let d = mr - mr_mean;
            (sxy + d * (z - z_mean), sxx + d * d)
        });
        let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
        (base + (z_mean - slope * mr_mean), slope)
    }

    /// `points` samples `(mr, Smc(mr))` at `mr = i/(points − 1)`, for a table or figure.
    pub fn sampled(&self, points: usize) -> (Vec<f64>, Vec<f64>) {
        let last = points.max(2) - 1;
        (0..=last)
            .map(|i| {
                let mr = i as f64 / last as f64;
                (mr, self.height_at(mr))
            })
            .unzip()
    }
}

/// Every functional and volume parameter of `map` (module docs).
pub fn functional_parameters(
    map: &HeightMap,
    options: FunctionalOptions,
) -> Result<FunctionalParameters, FunctionalError> {
    functional_parameters_of(&MaterialRatioCurve::of(map)?, options)
}

/// [`functional_parameters`] of a curve already built.
pub fn functional_parameters_of(
    curve: &MaterialRatioCurve,
    options: FunctionalOptions,
) -> Result<FunctionalParameters, FunctionalError> {
    check_ratios(&options)?;
    let FunctionalOptions {
        sxp_p,
        sxp_q,
        volume_p,
        volume_q,
    } = options;
    // The core and the volumes are independent passes over the curve: one thread each.
    let ((core_top, core_bottom, peaks, dales), [vm_p, vm_q, vv_p, vv_q]) = rayon::join(
        || {
            let (top, bottom) = curve.equivalent_line();
            let (peaks, dales) = rayon::join(
                || curve.mean_excess_above(top),
                || curve.mean_deficit_below(bottom),
            );
            (top, bottom, peaks, dales)
        },
        || {
            let ((vm_p, vm_q), (vv_p, vv_q)) = rayon::join(
                || {
                    rayon::join(
                        || curve.material_volume(volume_p),
                        || curve.material_volume(volume_q),
                    )
                },
                || {
                    rayon::join(
                        || curve.void_volume(volume_p),
                        || curve.void_volume(volume_q),
                    )
                },
            );
            [vm_p, vm_q, vv_p, vv_q]
        },
    );
    let smr1 = curve.ratio_above(core_top);
    let smr2 = curve.ratio_at_or_above(core_bottom);
    let triangle = |area: f64, base: f64| if base > 0.0 { 2.0 * area / base } else { 0.0 };
    Ok(FunctionalParameters {
        sk: core_top - core_bottom,
        spk: triangle(peaks, smr1),
        svk: triangle(dales, 1.0 - smr2),
        smr1,
        smr2,
        sxp: curve.height_at(sxp_p) - curve.height_at(sxp_q),
        vmp: vm_p,
        vmc: vm_q - vm_p,
        vvc: vv_p - vv_q,
        vvv: vv_q,
        core_top,
        core_bottom,
    })
}

/// Each ratio in [0, 1], `p ≤ q` for both pairs.
fn check_ratios(o: &FunctionalOptions) -> Result<(), FunctionalError> {
    let pairs = [
        ("sxp_p", o.sxp_p, "sxp_q", o.sxp_q),
        ("volume_p", o.volume_p, "volume_q", o.volume_q),
    ];
    for (p_name, p, q_name, q) in pairs {
        for (name, value) in [(p_name, p), (q_name, q)] {
            if !(0.0..=1.0).contains(&value) {
                return Err(FunctionalError::InvalidRatio {
                    name,
                    value,
                    order: "",
                });
            }
        }
        if p > q {
            return Err(FunctionalError::InvalidRatio {
                name: p_name,
                value: p,
                order: " and p ≤ q",
            });
        }
    }
    Ok(())
}
