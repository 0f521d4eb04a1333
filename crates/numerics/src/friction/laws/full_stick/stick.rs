//! Full-stick single asperity (Brizmer, Kligerman & Etsion 2006–2007): a sphere that sticks to
//! the rigid flat fails in sliding when its tangential stiffness is lost, not at first yield, so it
//! carries tangential load far into the plastic range (unlike the KE 2004 Q_max). Equations and
//! their status as in the project reference `docs/friction-models.md`; Y is the yield strength,
//! ν the Poisson ratio of the softer body, E' the composite modulus.
//!
//! * Slip critical values \[C2\]: C_ν = 1.234 + 1.256 ν, ω_c = (π C_ν Y/(2E'))² R,
//!   P_c = (π³/6) C_ν³ Y (R Y/E')².
//! * Full-stick critical values \[C1\]: ω_c,stick = ω̄_c ω_c with ω̄_c = 6.82 ν − 7.83 (ν² + 0.0586)
//!   and L_c = L̄_c P_c with L̄_c = 8.88 ν − 10.13 (ν² + 0.089). Both → 1 at ν = 0.5 (stick and
//!   slip coincide; 0.994 and 1.006) and turn negative below ν ≈ 0.13: ν < 0.2 is refused.
//!   L̄_c ≈ ω̄_c^{3/2} (Hertz scaling) holds within 4.3 % over [0.2, 0.5) (largest at ν = 0.23).
//! * Normal load under stick \[C1\], ω* = ω/ω_c,stick: P/L_c = ω*^{3/2} (ω* ≤ 1),
//!   ω*^{3/2} [1 − exp(1/(1 − ω*^β))] (1 < ω* ≤ 110), β = 0.174 + 0.08 ν. Continuous at ω* = 1.
//! * **Hand-over beyond ω* = 110** (the fit is not to be extrapolated): the Jackson–Green 2005 load
//!   ([`super::jackson_green`]) at the same interference — the elastic–plastic law with a hardness
//!   that falls as the contact grows, and the natural replacement of a constant-hardness cap. The
//!   load jumps there (−9 % at ν = 0.3, Y/E' = 0.006: the stick fit lies a few per cent above the
//!   slip fits at ω* = 110 and JG below them); tested and reported as the load beyond the fit.
//! * Contact area: no stick fit is confirmed; the Jackson–Green slip area is used throughout.
//! * Static friction coefficient of one asperity \[R — parameterised, unverified\]:
//!   μ(P*) = a coth(a P*^b), P* = P/L_c, with defaults a = 0.27, b = 0.35 attributed to Brizmer,
//!   Kligerman & Etsion, Tribol. Lett. 25 (2007) 61. What is confirmed: μ falls sharply with load at
//!   low loads and tends to a constant of about 0.3. Q_max = μ(P*) P; Q_max/L_c = a P*/tanh(a P*^b)
//!   → P*^{1−b} as P* → 0, so it vanishes with the load.
//!
//! Every law here is a ratio to the slip critical values (ω_c, P_c, A_c = π R ω_c) of the radius
//! at hand; those ratios depend on ν and Y/E' only.

use super::jackson_green::{JacksonGreenLaw, JG_ELASTIC_LIMIT};
use crate::friction::error::{require_positive, FrictionError};
use crate::friction::material::CriticalValues;

/// Upper end of the stick load fit, ω* = ω/ω_c,stick = 110.
pub const STICK_LOAD_FIT_LIMIT: f64 = 110.0;

/// Lowest Poisson ratio the full-stick critical-value fits are used for.
pub const STICK_MIN_POISSON_RATIO: f64 = 0.2;

/// μ(P*) = a coth(a P*^b) of a sticking asperity; a and b are parameters (defaults 0.27, 0.35,
/// attributed to Brizmer, Kligerman & Etsion 2007, not confirmed).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StickFrictionLaw {
    /// a > 0: the large-load limit of μ.
    pub a: f64,
    /// b > 0: the load exponent.
    pub b: f64,
}

impl Default for StickFrictionLaw {
    fn default() -> Self {
        Self { a: 0.27, b: 0.35 }
    }
}

impl StickFrictionLaw {
    /// A validated law (finite a > 0, 0 < b < 1 so that Q_max = μ P vanishes with the load).
    pub fn new(a: f64, b: f64) -> Result<Self, FrictionError> {
        let a = require_positive("stick_law.a", a)?;
        if !(b.is_finite() && b > 0.0 && b < 1.0) {
            return Err(FrictionError::InvalidParameter {
                name: "stick_law.b",
                value: b,
                expected: "an exponent in (0, 1)",
            });
        }
        Ok(Self { a, b })
    }

    /// μ at P* > 0 (+∞ at P* = 0).
    pub fn mu(&self, p_star: f64) -> f64 {
        self.a / (self.a * p_star.max(0.0).powf(self.b)).tanh()
    }

    /// Q_max/L_c = μ(P*) P* (0 for P* ≤ 0).
    pub fn friction_ratio(&self, p_star: f64) -> f64 {
        if p_star <= 0.0 {
            return 0.0;
        }
        let t = self.a * p_star.powf(self.b);
        if t == 0.0 {
            p_star.powf(1.0 - self.b)
        } else {
            self.a * p_star / t.tanh()
        }
    }
}

/// BKE full-stick critical-value factors (ω̄_c, L̄_c) at ν; ν outside [0.2, 0.5) is refused.
pub fn stick_factors(poisson_ratio: f64) -> Result<(f64, f64), FrictionError> {
    let nu = poisson_ratio;
    if !(nu.is_finite() && (STICK_MIN_POISSON_RATIO..0.5).contains(&nu)) {
        return Err(FrictionError::InvalidParameter {
            name: "poisson_ratio",
            value: nu,
            expected: "a Poisson ratio in [0.2, 0.5): the full-stick critical values are fits that turn negative below 0.13",
        });
    }
    Ok((
        6.82 * nu - 7.83 * (nu * nu + 0.0586),
        8.88 * nu - 10.13 * (nu * nu + 0.089),
    ))
}

/// The full-stick asperity laws of one material pair (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullStickLaw {
    /// C_ν = 1.234 + 1.256 ν.
    pub critical_factor: f64,
    /// ω̄_c = ω_c,stick/ω_c.
    pub stick_interference_factor: f64,
    /// L̄_c = L_c/P_c.
    pub stick_load_factor: f64,
    /// β = 0.174 + 0.08 ν.
    pub stick_exponent: f64,
    /// ω_c/R = (π C_ν Y/(2E'))².
    pub critical_interference_over_radius: f64,
    /// The Jackson–Green laws beyond the stick fit and for the area.
    pub jackson_green: JacksonGreenLaw,
    /// P_c,JG/P_c = (ω_c,JG/ω_c)^{3/2}, the scale of the Jackson–Green load in slip units.
    pub jackson_green_load_scale: f64,
    /// μ(P*) of a sticking asperity.
    pub friction_law: StickFrictionLaw,
}

impl FullStickLaw {
    /// Laws for yield strength Y (Pa), composite modulus E' (Pa), the softer body's ν ∈ [0.2, 0.5)
    /// and the μ(P*) parameters.
    pub fn new(
        yield_strength: f64,
        composite_modulus: f64,
        poisson_ratio: f64,
        friction_law: StickFrictionLaw,
    ) -> Result<Self, FrictionError> {
        let (omega_bar, load_bar) = stick_factors(poisson_ratio)?;
        let jackson_green = JacksonGreenLaw::new(yield_strength, composite_modulus, poisson_ratio)?;
        let friction_law = StickFrictionLaw::new(friction_law.a, friction_law.b)?;
        let critical_factor = 1.234 + 1.256 * poisson_ratio;
        let ratio =
            std::f64::consts::PI * critical_factor * yield_strength / (2.0 * composite_modulus);
        let critical_interference_over_radius = ratio * ratio;
        let jackson_green_load_scale = (jackson_green.critical_interference_over_radius
            / critical_interference_over_radius)
            .powf(1.5);
        Ok(Self {
            critical_factor,
            stick_interference_factor: omega_bar,
            stick_load_factor: load_bar,
            stick_exponent: 0.174 + 0.08 * poisson_ratio,
            critical_interference_over_radius,
            jackson_green,
            jackson_green_load_scale,
            friction_law,
        })
    }

    /// Slip critical values ω_c, P_c = (4/3) E' R² (ω_c/R)^{3/2}, A_c = π R ω_c of radius R (m).
    pub fn critical_values(&self, radius: f64, composite_modulus: f64) -> CriticalValues {
        let interference = self.critical_interference_over_radius * radius;
        CriticalValues {
            interference,
            load: 4.0 / 3.0
                * composite_modulus
                * radius
                * radius
                * self.critical_interference_over_radius.powf(1.5),
            area: std::f64::consts::PI * radius * interference,
        }
    }

    /// ω* = ω/ω_c,stick at w = ω/ω_c.
    pub fn stick_interference(&self, w: f64) -> f64 {
        w / self.stick_interference_factor
    }

    /// P/L_c of the stick load fit at ω* (no hand-over; 0 for ω* ≤ 0).
    pub fn stick_load_fit(&self, w_stick: f64) -> f64 {
        if w_stick <= 0.0 {
            0.0
        } else if w_stick <= 1.0 {
            w_stick.powf(1.5)
        } else {
            let decay = (1.0 / (1.0 - w_stick.powf(self.stick_exponent))).exp();
            w_stick.powf(1.5) * (1.0 - decay)
        }
    }

    /// P*(ω* = 110): the largest P/L_c inside the stick load fit.
    pub fn load_at_fit_limit(&self) -> f64 {
        self.stick_load_fit(STICK_LOAD_FIT_LIMIT)
    }

    /// w = ω/ω_c in Jackson–Green units, ω/ω_c,JG.
    fn jackson_green_interference(&self, w: f64) -> f64 {
        w * self.critical_interference_over_radius
            / self.jackson_green.critical_interference_over_radius
    }

    /// P/P_c at w = ω/ω_c: the stick fit up to ω* = 110, Jackson–Green beyond.
    pub fn load_ratio(&self, w: f64) -> f64 {
        let w_stick = self.stick_interference(w);
        if w_stick <= STICK_LOAD_FIT_LIMIT {
            self.stick_load_factor * self.stick_load_fit(w_stick)
        } else {
            self.jackson_green_load_scale
                * self
                    .jackson_green
                    .load_ratio(self.jackson_green_interference(w))
        }
    }

    /// A/A_c at w = ω/ω_c (the Jackson–Green slip area).
    pub fn area_ratio(&self, w: f64) -> f64 {
        self.jackson_green.critical_interference_over_radius
            / self.critical_interference_over_radius
            * self
                .jackson_green
                .area_ratio(self.jackson_green_interference(w))
    }

    /// Q_max/P_c at w = ω/ω_c: L̄_c μ(P*) P* with P* = P/L_c.
    pub fn friction_ratio(&self, w: f64) -> f64 {
        let p_star = self.load_ratio(w) / self.stick_load_factor;
        self.stick_load_factor * self.friction_law.friction_ratio(p_star)
    }

    /// w = ω/ω_c at the breaks of the laws: ω* = 1 and 110 of the stick fit, ω*_JG = 1.9.
    pub fn breakpoints(&self) -> [f64; 3] {
        [
            self.stick_interference_factor,
            self.stick_interference_factor * STICK_LOAD_FIT_LIMIT,
            JG_ELASTIC_LIMIT * self.jackson_green.critical_interference_over_radius
                / self.critical_interference_over_radius,
        ]
    }
}
