//! The deformation (ploughing) part of friction of one junction: textbook laws of a hard
//! asperity on a rigid–perfectly-plastic flat and of an inclined junction
//! (docs/friction-models.md, "Deformation part", with the sources and what was confirmed).
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
//!
//! **Inclined junction** (the inclined plane of statics). A junction whose plane rises by θ in
//! the sliding direction, with local friction `μ_a = tan φ`, slides when the horizontal force
//! reaches **`μ = tan(φ + θ) = (μ_a + tan θ)/(1 − μ_a tan θ)`** per unit vertical load; on a
//! down-slope junction (θ < 0) this is `tan(φ − |θ|)`. It has no finite value for
//! `φ + θ ≥ 90°`, where the junction locks ([`tilted_junction`]). θ = 0 gives `μ_a`.

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

/// Friction `tan(φ + θ) = (μ_a + tan θ)/(1 − μ_a tan θ)` of a junction with local friction
/// `μ_a` whose plane rises by `tan θ` in the sliding direction (negative down-slope); `None` when
/// `μ_a tan θ ≥ 1` (φ + θ ≥ 90°: the junction locks).
pub fn tilted_junction(local_friction: f64, tilt: f64) -> Option<f64> {
    let denominator = 1.0 - local_friction * tilt;
    (denominator > 0.0).then(|| (local_friction + tilt) / denominator)
}
