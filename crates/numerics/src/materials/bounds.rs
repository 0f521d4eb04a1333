//! The one set of bounds on a body's material constants, each with its reason. Contact, friction
//! and the study parser all check through these functions, so a value is accepted or refused
//! alike everywhere.
//!
//! | constant | bound | reason |
//! |---|---|---|
//! | Young's modulus E | finite, > 0 | the half-space compliance (1 − ν²)/E must be finite and positive; a rigid counter-body is written by omitting it, not as E = ∞ |
//! | Poisson's ratio ν | in [0, 0.5] | 0.5 is the incompressible limit (rubber), where (1 − ν²)/E stays finite; below 0 (auxetic foams and lattices, not homogeneous half-spaces at asperity scale) neither the handbook data nor the fits of the asperity laws in ν (K = 0.454 + 0.41 ν) exist |
//! | hardness H | finite, > 0, < E | the mean pressure of fully plastic indentation; H ≥ E leaves no elastic regime (metals have H/E ≈ 0.005–0.05, hard ceramics up to ≈ 0.1) |
//! | yield strength Y | finite, > 0, ≤ H | the indentation constraint factor H/Y is at least 1 (≈ 1.1 for low E/Y up to ≈ 3 for metals: Tabor, *The Hardness of Metals*, 1951; Johnson, *Contact Mechanics*, 1985, §6.3) |
//! | shear strength k | finite, > 0, ≤ Y | Tresca gives k = Y/2 and von Mises k = Y/√3: no isotropic yield criterion gives a shear yield strength above the tensile one |
//! | flow pressure p_lim | finite, > 0, < E | the pressure cap of the elastic–perfectly-plastic half-space (≈ H); the same reason as for H |
//!
//! Y and k are compared with the effective values (given, or by the default rules of
//! [`super::BodyMaterial`]). A contact may in addition cap its pressure at a flow pressure of its
//! own, which may be +∞ (purely elastic): [`contact_flow_pressure`]. Friction adds one bound on the
//! pair: the softer body's H below the composite modulus E* (`friction::Material`).

/// A material constant outside its bound; the message names the constant, the bound and the reason.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum MaterialError {
    /// A constant outside its own range.
    #[error("{parameter} = {value} is out of range: must be {bound} ({reason})")]
    OutOfRange {
        /// The constant, as in the study file (`poisson_ratio`).
        parameter: &'static str,
        /// The value given (SI units).
        value: f64,
        /// The accepted range.
        bound: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// A constant not below (or above) the constant it is bounded by.
    #[error("{parameter} = {value} Pa is out of range: must be {relation} {limit_name} = {limit} Pa ({reason})")]
    Relation {
        /// The constant, as in the study file (`hardness`).
        parameter: &'static str,
        /// The value given (Pa).
        value: f64,
        /// `below` or `at most`.
        relation: &'static str,
        /// The constant it is bounded by (`youngs_modulus`).
        limit_name: &'static str,
        /// Its value (Pa).
        limit: f64,
        /// Why.
        reason: &'static str,
    },
}

impl MaterialError {
    /// The constant the error is about, as in the study file.
    pub fn parameter(&self) -> &'static str {
        match self {
            Self::OutOfRange { parameter, .. } | Self::Relation { parameter, .. } => parameter,
        }
    }

    /// The value given (SI units).
    pub fn value(&self) -> f64 {
        match self {
            Self::OutOfRange { value, .. } | Self::Relation { value, .. } => *value,
        }
    }

    /// The message without the constant's name and value: "is out of range: must be … (…)".
    pub fn range_message(&self) -> String {
        match self {
            Self::OutOfRange { bound, reason, .. } => {
                format!("is out of range: must be {bound} ({reason})")
            }
            Self::Relation {
                relation,
                limit_name,
                limit,
                reason,
                ..
            } => {
                format!("is out of range: must be {relation} {limit_name} = {limit} Pa ({reason})")
            }
        }
    }
}

const MODULUS_REASON: &str = "the half-space compliance (1 − ν²)/E must be finite and positive; \
                              omit the counter-body for a rigid one";
const POISSON_REASON: &str = "0.5 is the incompressible limit; the asperity laws and the \
                              handbook data do not cover auxetic (negative) values";
const PLASTIC_REASON: &str = "a pressure of plastic flow at or above E leaves no elastic regime";

/// E: finite and > 0 Pa.
pub fn youngs_modulus(value: f64) -> Result<f64, MaterialError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MaterialError::OutOfRange {
            parameter: "youngs_modulus",
            value,
            bound: "finite and > 0 Pa",
            reason: MODULUS_REASON,
        })
    }
}

/// ν: in [0, 0.5].
pub fn poisson_ratio(value: f64) -> Result<f64, MaterialError> {
    if (0.0..=0.5).contains(&value) {
        Ok(value)
    } else {
        Err(MaterialError::OutOfRange {
            parameter: "poisson_ratio",
            value,
            bound: "in [0, 0.5]",
            reason: POISSON_REASON,
        })
    }
}

/// A strength or pressure (H, Y, k, p_lim) on its own: finite and > 0 Pa.
pub fn strength(parameter: &'static str, value: f64) -> Result<f64, MaterialError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MaterialError::OutOfRange {
            parameter,
            value,
            bound: "finite and > 0 Pa",
            reason: "a strength is a positive pressure",
        })
    }
}

/// A contact's own pressure cap: > 0 Pa, +∞ for a purely elastic contact.
pub fn contact_flow_pressure(value: f64) -> Result<f64, MaterialError> {
    if value > 0.0 {
        Ok(value)
    } else {
        Err(MaterialError::OutOfRange {
            parameter: "flow_pressure",
            value,
            bound: "> 0 Pa (infinite: purely elastic)",
            reason: "the local contact pressure is capped at it",
        })
    }
}

/// H and p_lim below E.
pub(super) fn below_modulus(
    parameter: &'static str,
    value: f64,
    modulus: f64,
) -> Result<(), MaterialError> {
    if value < modulus {
        Ok(())
    } else {
        Err(MaterialError::Relation {
            parameter,
            value,
            relation: "below",
            limit_name: "youngs_modulus",
            limit: modulus,
            reason: PLASTIC_REASON,
        })
    }
}

/// Y at most H.
pub(super) fn yield_within_hardness(
    yield_strength: f64,
    hardness: f64,
) -> Result<(), MaterialError> {
    if yield_strength <= hardness {
        Ok(())
    } else {
        Err(MaterialError::Relation {
            parameter: "yield_strength",
            value: yield_strength,
            relation: "at most",
            limit_name: "hardness",
            limit: hardness,
            reason: "the indentation constraint factor H/Y is at least 1 (Tabor 1951)",
        })
    }
}

/// k at most Y (the effective one).
pub(super) fn shear_within_yield(
    shear_strength: f64,
    yield_strength: f64,
) -> Result<(), MaterialError> {
    if shear_strength <= yield_strength {
        Ok(())
    } else {
        Err(MaterialError::Relation {
            parameter: "shear_strength",
            value: shear_strength,
            relation: "at most",
            limit_name: "yield_strength",
            limit: yield_strength,
            reason: "Tresca k = Y/2, von Mises k = Y/√3: no isotropic yield criterion gives more",
        })
    }
}
