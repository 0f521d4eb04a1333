//! The material pair of a contact: a lower body against an upper body or a rigid counter-body.

use super::body::BodyMaterial;

/// Which body of a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The lower body.
    Lower,
    /// The upper body.
    Upper,
}

impl Side {
    /// The study-file name of the body's material (`lower_material`, `upper_material`).
    pub fn material_field(self) -> &'static str {
        match self {
            Side::Lower => "lower_material",
            Side::Upper => "upper_material",
        }
    }
}

/// A lower body against an upper body, or against a rigid counter-body (`upper` = `None`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialPair {
    lower: BodyMaterial,
    upper: Option<BodyMaterial>,
}

impl MaterialPair {
    /// The lower body against the upper one (`None`: rigid).
    pub fn new(lower: BodyMaterial, upper: Option<BodyMaterial>) -> Self {
        Self { lower, upper }
    }

    /// The lower body against a rigid counter-body.
    pub fn against_rigid(lower: BodyMaterial) -> Self {
        Self::new(lower, None)
    }

    /// The lower body.
    pub fn lower(&self) -> &BodyMaterial {
        &self.lower
    }

    /// The upper body (`None`: rigid).
    pub fn upper(&self) -> Option<&BodyMaterial> {
        self.upper.as_ref()
    }

    /// The half-space compliances (c_lower, c_upper) in 1/Pa, c = (1 − ν²)/E; 0 for a rigid body.
    pub fn compliances(&self) -> (f64, f64) {
        (
            self.lower.compliance(),
            self.upper.map_or(0.0, |u| u.compliance()),
        )
    }

    /// The composite compliance c₁ + c₂ (1/Pa) and modulus E* = 1/(c₁ + c₂) (Pa) (Johnson,
    /// Contact Mechanics, 1985, eq. 4.22): the one place the pair's elasticity is combined.
    pub fn composite(&self) -> Composite {
        let (lower, upper) = self.compliances();
        let compliance = lower + upper;
        Composite {
            compliance,
            modulus: 1.0 / compliance,
            lower_share: lower / compliance,
        }
    }

    /// The softer body, whose H and ν the asperity laws use: the one with the lower hardness; a
    /// body with a hardness is softer than one without; on a tie, and against a rigid
    /// counter-body, the lower one.
    pub fn softer(&self) -> (Side, &BodyMaterial) {
        match (self.lower.hardness(), self.upper.as_ref()) {
            (lower, Some(upper)) => match (lower, upper.hardness()) {
                (None, Some(_)) => (Side::Upper, upper),
                (Some(hl), Some(hu)) if hu < hl => (Side::Upper, upper),
                _ => (Side::Lower, &self.lower),
            },
            (_, None) => (Side::Lower, &self.lower),
        }
    }

    /// The pair's flow pressure p_lim (Pa): the lowest of the bodies' (the first to flow caps the
    /// contact pressure); `None` when neither body has one. With the default p_lim = H it is the
    /// softer body's hardness.
    pub fn flow_pressure(&self) -> Option<f64> {
        let lower = self.lower.flow_pressure();
        match (lower, self.upper.and_then(|u| u.flow_pressure())) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

/// The combined elasticity of a pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Composite {
    /// c₁ + c₂ (1/Pa).
    pub compliance: f64,
    /// E* = 1/(c₁ + c₂) (Pa).
    pub modulus: f64,
    /// c₁/(c₁ + c₂): the share of the composite deformation the lower body carries.
    pub lower_share: f64,
}

#[cfg(test)]
mod tests {
    use super::super::body::BodyConstants;
    use super::*;

    fn body(e: f64, h: Option<f64>) -> BodyMaterial {
        BodyMaterial::new(BodyConstants {
            hardness: h,
            ..BodyConstants::elastic(e, 0.3)
        })
        .unwrap()
    }

    #[test]
    fn steel_on_steel_and_rigid_flat() {
        let steel = body(210e9, Some(2e9));
        let pair = MaterialPair::new(steel, Some(steel)).composite();
        assert!((pair.modulus - 210e9 / (2.0 * 0.91)).abs() < 1e-6 * pair.modulus);
        assert_eq!(pair.lower_share, 0.5);
        let flat = MaterialPair::against_rigid(steel).composite();
        assert_eq!(flat.compliance, 0.91 / 210e9);
        assert_eq!(flat.lower_share, 1.0);
    }

    #[test]
    fn softer_body_is_chosen_by_hardness() {
        let (hard, soft, none) = (
            body(210e9, Some(7e9)),
            body(70e9, Some(1e9)),
            body(3e9, None),
        );
        assert_eq!(MaterialPair::new(hard, Some(soft)).softer().0, Side::Upper);
        assert_eq!(MaterialPair::new(soft, Some(hard)).softer().0, Side::Lower);
        assert_eq!(MaterialPair::new(soft, Some(soft)).softer().0, Side::Lower);
        assert_eq!(MaterialPair::new(none, Some(soft)).softer().0, Side::Upper);
        assert_eq!(MaterialPair::new(soft, Some(none)).softer().0, Side::Lower);
        assert_eq!(MaterialPair::against_rigid(none).softer().0, Side::Lower);
        assert_eq!(
            MaterialPair::new(hard, Some(soft)).flow_pressure(),
            Some(1e9)
        );
        assert_eq!(MaterialPair::new(none, Some(none)).flow_pressure(), None);
    }
}
