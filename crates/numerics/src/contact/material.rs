//! Elastic and plastic material data of a contact pair.

/// Elastic description of one body of the contact pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BodyElasticity {
    /// Isotropic linear-elastic body: Young's modulus `E` in Pa and Poisson's ratio `ν`.
    ///
    /// An indentation modulus `E_IT` (ISO 14577) is an estimate of Young's modulus of the
    /// specimen and is entered here with the Poisson's ratio used to evaluate it.
    Isotropic {
        /// Young's modulus `E` in Pa (finite, > 0).
        youngs_modulus: f64,
        /// Poisson's ratio `ν`, in `(-1, 0.5]`.
        poisson_ratio: f64,
    },
    /// Body given directly by its plane-strain modulus `E' = E / (1 − ν²)` in Pa.
    PlaneStrain {
        /// Plane-strain modulus `E'` in Pa (finite, > 0).
        modulus: f64,
    },
    /// Rigid body (zero compliance), e.g. a rigid flat counter-face.
    Rigid,
}

impl BodyElasticity {
    /// Half-space compliance `c = (1 − ν²) / E` in 1/Pa (0 for a rigid body).
    fn compliance(self) -> Result<f64, MaterialError> {
        match self {
            BodyElasticity::Isotropic {
                youngs_modulus,
                poisson_ratio,
            } => {
                if !(youngs_modulus.is_finite() && youngs_modulus > 0.0) {
                    return Err(MaterialError::BadModulus {
                        modulus: youngs_modulus,
                    });
                }
                if !(poisson_ratio > -1.0 && poisson_ratio <= 0.5) {
                    return Err(MaterialError::BadPoissonRatio { poisson_ratio });
                }
                Ok(crate::materials::half_space_compliance(
                    youngs_modulus,
                    poisson_ratio,
                ))
            }
            BodyElasticity::PlaneStrain { modulus } => {
                if !(modulus.is_finite() && modulus > 0.0) {
                    return Err(MaterialError::BadModulus { modulus });
                }
                Ok(1.0 / modulus)
            }
            BodyElasticity::Rigid => Ok(0.0),
        }
    }
}

/// Why a [`ContactMaterial`] could not be built.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum MaterialError {
    #[error("elastic modulus must be finite and > 0 Pa, got {modulus} Pa")]
    BadModulus { modulus: f64 },
    #[error("Poisson's ratio must lie in (-1, 0.5], got {poisson_ratio}")]
    BadPoissonRatio { poisson_ratio: f64 },
    #[error("both bodies are rigid: the contact problem has no elastic solution")]
    BothRigid,
    #[error("plastic flow pressure must be > 0 Pa (f64::INFINITY for purely elastic), got {flow_pressure} Pa")]
    BadFlowPressure { flow_pressure: f64 },
}

/// Material data of an elastic–perfectly-plastic contact pair.
///
/// * Composite (effective) modulus `E*` from the two half-space compliances (Johnson 1985, eq. 4.22):
///   `1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ = c₁ + c₂`.
/// * Plastic flow pressure `p_lim` in Pa of the softer body: the local contact pressure cannot exceed
///   it (elastic–perfectly-plastic half-space with pressure saturation, Almqvist et al. 2007,
///   Wear 262). `f64::INFINITY` is a purely elastic contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactMaterial {
    compliance_first: f64,
    compliance_second: f64,
    flow_pressure: f64,
}

impl ContactMaterial {
    /// Builds the pair from the elasticity of both bodies and the flow pressure `p_lim` in Pa.
    pub fn new(
        first: BodyElasticity,
        second: BodyElasticity,
        flow_pressure: f64,
    ) -> Result<Self, MaterialError> {
        let compliance_first = first.compliance()?;
        let compliance_second = second.compliance()?;
        if compliance_first + compliance_second <= 0.0 {
            return Err(MaterialError::BothRigid);
        }
        if flow_pressure.is_nan() || flow_pressure <= 0.0 {
            return Err(MaterialError::BadFlowPressure { flow_pressure });
        }
        Ok(Self {
            compliance_first,
            compliance_second,
            flow_pressure,
        })
    }

    /// Two isotropic bodies `(E₁, ν₁)`, `(E₂, ν₂)` in Pa and the flow pressure `p_lim` in Pa.
    pub fn from_young_poisson(
        youngs_first: f64,
        poisson_first: f64,
        youngs_second: f64,
        poisson_second: f64,
        flow_pressure: f64,
    ) -> Result<Self, MaterialError> {
        Self::new(
            BodyElasticity::Isotropic {
                youngs_modulus: youngs_first,
                poisson_ratio: poisson_first,
            },
            BodyElasticity::Isotropic {
                youngs_modulus: youngs_second,
                poisson_ratio: poisson_second,
            },
            flow_pressure,
        )
    }

    /// An elastic body of composite modulus `E*` (Pa) against a rigid flat, flow pressure in Pa.
    pub fn against_rigid_flat(
        composite_modulus: f64,
        flow_pressure: f64,
    ) -> Result<Self, MaterialError> {
        Self::new(
            BodyElasticity::PlaneStrain {
                modulus: composite_modulus,
            },
            BodyElasticity::Rigid,
            flow_pressure,
        )
    }

    /// Composite modulus `E*` in Pa.
    pub fn composite_modulus(&self) -> f64 {
        1.0 / (self.compliance_first + self.compliance_second)
    }

    /// Plastic flow pressure `p_lim` in Pa (`f64::INFINITY` for purely elastic).
    pub fn flow_pressure(&self) -> f64 {
        self.flow_pressure
    }

    /// Whether the contact is purely elastic: no flow pressure caps its pressure.
    pub fn is_elastic(&self) -> bool {
        self.flow_pressure() == f64::INFINITY
    }

    /// Share `c₁ / (c₁ + c₂)` of the composite elastic deformation carried by the first body.
    pub fn first_body_share(&self) -> f64 {
        self.compliance_first / (self.compliance_first + self.compliance_second)
    }

    /// The same pair with the two bodies swapped.
    pub fn swapped(&self) -> Self {
        Self {
            compliance_first: self.compliance_second,
            compliance_second: self.compliance_first,
            flow_pressure: self.flow_pressure,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steel_on_steel_composite_modulus() {
        // 1/E* = 2 (1 − 0.3²) / 210 GPa ⇒ E* = 115.38 GPa.
        let m = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 4e9).unwrap();
        let expected = 210e9 / (2.0 * (1.0 - 0.09));
        assert!((m.composite_modulus() - expected).abs() < 1e-6 * expected);
        assert!((m.first_body_share() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn rigid_flat_takes_no_deformation() {
        let m = ContactMaterial::against_rigid_flat(100e9, f64::INFINITY).unwrap();
        assert_eq!(m.composite_modulus(), 100e9);
        assert_eq!(m.first_body_share(), 1.0);
        assert_eq!(m.swapped().first_body_share(), 0.0);
    }

    #[test]
    fn rejects_bad_input() {
        assert_eq!(
            ContactMaterial::new(BodyElasticity::Rigid, BodyElasticity::Rigid, 1e9),
            Err(MaterialError::BothRigid)
        );
        assert!(matches!(
            ContactMaterial::from_young_poisson(-1.0, 0.3, 1e9, 0.3, 1e9),
            Err(MaterialError::BadModulus { .. })
        ));
        assert!(matches!(
            ContactMaterial::from_young_poisson(1e9, 0.7, 1e9, 0.3, 1e9),
            Err(MaterialError::BadPoissonRatio { .. })
        ));
        assert!(matches!(
            ContactMaterial::against_rigid_flat(1e9, f64::NAN),
            Err(MaterialError::BadFlowPressure { .. })
        ));
        assert!(matches!(
            ContactMaterial::against_rigid_flat(f64::INFINITY, 1e9),
            Err(MaterialError::BadModulus { .. })
        ));
    }
}
