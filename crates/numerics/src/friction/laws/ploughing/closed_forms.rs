//! The deformation (ploughing) part of friction of one junction: textbook laws of a hard
//! asperity on a rigid–perfectly-plastic flat (docs/friction-models.md, "Deformation part",
//! with the sources and what was confirmed).
//!
//! **Ploughing** (Bowden & Tabor 1950). A hard asperity slid over a rigid–perfectly-plastic flat
//! is carried by the flat's flow pressure on the front half of its projected contact and pushed
//! back by the same pressure on the groove's cross-section, so
//! `μ_p = A_side / A_front`, the groove cross-section over half the projected area.
//!
//! * cone of attack angle α (semi-angle 90° − α): `A_side = a h`, `A_front = π a²/2`,
//!   `h = a tan α`: **`μ_p = (2/π) tan α`** ([`cone_ploughing`]);
//! * sphere of radius R at contact radius a: the cross-section is the circular segment
//!   `R² arcsin(a/R) − a √(R² − a²)`, so
//!   **`μ_p = (2/π) [(R/a)² arcsin(a/R) − √((R/a)² − 1)]`**, which tends to `4a/(3πR)` for
//!   `a ≪ R` ([`sphere_ploughing`]); defined for `a ≤ R` (at most a hemisphere, `μ_p = 1`).

use std::f64::consts::FRAC_2_PI;

/// Below this `a/R` [`sphere_ploughing`] uses its series (the closed form loses about
/// `1e-16/(a/R)²` to cancellation there, the series' first omitted term is `(a/R)⁷`).
const SPHERE_SERIES_BELOW: f64 = 1e-2;

/// Ploughing friction `μ_p = (2/π) tan α` of a cone of attack slope `tan α` (≥ 0).
pub fn cone_ploughing(attack_slope: f64) -> f64 {
    FRAC_2_PI * attack_slope
}

/// Ploughing friction of a sphere at `a/R` in `[0, 1]`:
/// `(2/π) [(R/a)² arcsin(a/R) − √((R/a)² − 1)]`, by its series
/// `(2/π) (2x/3 + x³/5 + 3x⁵/28)` below `x = a/R = 0.01`; `None` outside `[0, 1]`.
pub fn sphere_ploughing(a_over_r: f64) -> Option<f64> {
    let x = a_over_r;
    if !(0.0..=1.0).contains(&x) {
        return None;
    }
    if x < SPHERE_SERIES_BELOW {
        let x2 = x * x;
        return Some(FRAC_2_PI * x * (2.0 / 3.0 + x2 * (1.0 / 5.0 + x2 * 3.0 / 28.0)));
    }
    let r = 1.0 / x;
    Some(FRAC_2_PI * (r * r * x.asin() - (r * r - 1.0).max(0.0).sqrt()))
}
