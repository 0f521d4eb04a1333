//! One body's material: elastic constants, the strengths given, and the default rules for those
//! not given.

use super::bounds::{self, MaterialError};

/// Tabor's constraint factor: hardness H ≈ 2.8 × yield strength Y of a metal (Tabor, The Hardness
/// of Metals, 1951), the rule for Y when a material gives only H.
pub const TABOR_FACTOR: f64 = 2.8;

/// The constants of one body as given (SI units); `None`: not given, the default rule of
/// [`BodyMaterial`] applies. Unchecked: [`BodyMaterial::new`] checks them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyConstants {
    /// Young's modulus E (Pa); an indentation modulus E_IT (ISO 14577) is an estimate of it.
    pub youngs_modulus: f64,
    /// Poisson's ratio ν.
    pub poisson_ratio: f64,
    /// Hardness H (Pa), the Vickers hardness as a pressure.
    pub hardness: Option<f64>,
    /// Yield strength Y (Pa).
    pub yield_strength: Option<f64>,
    /// Shear strength k (Pa).
    pub shear_strength: Option<f64>,
    /// Plastic flow pressure p_lim (Pa) of the elastic–perfectly-plastic half-space.
    pub flow_pressure: Option<f64>,
}

impl BodyConstants {
    /// A purely elastic body: E (Pa) and ν, no strengths.
    pub const fn elastic(youngs_modulus: f64, poisson_ratio: f64) -> Self {
        Self {
            youngs_modulus,
            poisson_ratio,
            hardness: None,
            yield_strength: None,
            shear_strength: None,
            flow_pressure: None,
        }
    }

    /// An elastic body with a hardness H (Pa), every other strength by its default rule.
    pub const fn with_hardness(youngs_modulus: f64, poisson_ratio: f64, hardness: f64) -> Self {
        Self {
            hardness: Some(hardness),
            ..Self::elastic(youngs_modulus, poisson_ratio)
        }
    }
}

/// One body's checked material (SI units), the description contact and friction share.
///
/// Default rules for the strengths not given:
/// * yield strength, Tabor: Y = H / 2.8 ([`TABOR_FACTOR`]);
/// * shear strength, von Mises: k = Y / √3;
/// * flow pressure: p_lim = H (the mean pressure under a fully plastic indenter is the hardness,
///   Tabor 1951; the elastic–perfectly-plastic half-space caps the local pressure there).
///
/// Bounds: [`super::bounds`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMaterial {
    constants: BodyConstants,
}

impl BodyMaterial {
    /// Checks the constants against [`super::bounds`]: each on its own, then H and p_lim below E,
    /// Y at most H, k at most the (effective) Y.
    pub fn new(constants: BodyConstants) -> Result<Self, MaterialError> {
        let e = bounds::youngs_modulus(constants.youngs_modulus)?;
        bounds::poisson_ratio(constants.poisson_ratio)?;
        let checked =
            |name, value: Option<f64>| value.map(|v| bounds::strength(name, v)).transpose();
        let hardness = checked("hardness", constants.hardness)?;
        let yield_strength = checked("yield_strength", constants.yield_strength)?;
        let shear_strength = checked("shear_strength", constants.shear_strength)?;
        let flow_pressure = checked("flow_pressure", constants.flow_pressure)?;
        if let Some(h) = hardness {
            bounds::below_modulus("hardness", h, e)?;
        }
        if let Some(p) = flow_pressure {
            bounds::below_modulus("flow_pressure", p, e)?;
        }
        if let (Some(y), Some(h)) = (yield_strength, hardness) {
            bounds::yield_within_hardness(y, h)?;
        }
        let material = Self { constants };
        if let (Some(k), Some(y)) = (shear_strength, material.yield_strength()) {
            bounds::shear_within_yield(k, y)?;
        }
        Ok(material)
    }

    /// A purely elastic body: E (Pa) and ν.
    pub fn elastic(youngs_modulus: f64, poisson_ratio: f64) -> Result<Self, MaterialError> {
        Self::new(BodyConstants::elastic(youngs_modulus, poisson_ratio))
    }

    /// The constants as given.
    pub fn constants(&self) -> &BodyConstants {
        &self.constants
    }

    /// Young's modulus E (Pa).
    pub fn youngs_modulus(&self) -> f64 {
        self.constants.youngs_modulus
    }

    /// Poisson's ratio ν.
    pub fn poisson_ratio(&self) -> f64 {
        self.constants.poisson_ratio
    }

    /// Hardness H (Pa), if given.
    pub fn hardness(&self) -> Option<f64> {
        self.constants.hardness
    }

    /// Yield strength Y (Pa): given, else Tabor's H / 2.8; `None` without either.
    pub fn yield_strength(&self) -> Option<f64> {
        self.constants
            .yield_strength
            .or(self.constants.hardness.map(|h| h / TABOR_FACTOR))
    }

    /// Shear strength k (Pa): given, else von Mises Y / √3; `None` without either.
    pub fn shear_strength(&self) -> Option<f64> {
        self.constants
            .shear_strength
            .or(self.yield_strength().map(|y| y / 3f64.sqrt()))
    }

    /// Flow pressure p_lim (Pa): given, else H; `None` without either.
    pub fn flow_pressure(&self) -> Option<f64> {
        self.constants.flow_pressure.or(self.constants.hardness)
    }

    /// Half-space compliance c = (1 − ν²)/E (1/Pa) of the isotropic elastic body (Johnson,
    /// Contact Mechanics, 1985, eq. 4.22; the pair's composite modulus is 1/(c₁ + c₂)).
    pub fn compliance(&self) -> f64 {
        let nu = self.constants.poisson_ratio;
        (1.0 - nu * nu) / self.constants.youngs_modulus
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_rules_follow_tabor_and_von_mises() {
        let body = BodyMaterial::new(BodyConstants::with_hardness(210e9, 0.3, 2.8e9)).unwrap();
        let near = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() < 1e-12 * b);
        assert!(near(body.yield_strength(), 1e9));
        assert!(near(body.shear_strength(), 1e9 / 3f64.sqrt()));
        assert_eq!(body.flow_pressure(), Some(2.8e9));
        let elastic = BodyMaterial::elastic(210e9, 0.3).unwrap();
        assert_eq!(elastic.yield_strength(), None);
        assert_eq!(elastic.flow_pressure(), None);
        assert_eq!(elastic.compliance(), 0.91 / 210e9);
    }

    #[test]
    fn refuses_each_bound() {
        let parameter =
            |c: BodyConstants| BodyMaterial::new(c).map(|_| ()).map_err(|e| e.parameter());
        let steel = BodyConstants::with_hardness(210e9, 0.3, 2e9);
        assert_eq!(
            parameter(BodyConstants {
                youngs_modulus: f64::INFINITY,
                ..steel
            }),
            Err("youngs_modulus")
        );
        assert_eq!(
            parameter(BodyConstants {
                youngs_modulus: 0.0,
                ..steel
            }),
            Err("youngs_modulus")
        );
        assert_eq!(
            parameter(BodyConstants {
                poisson_ratio: -0.1,
                ..steel
            }),
            Err("poisson_ratio")
        );
        assert_eq!(
            parameter(BodyConstants {
                poisson_ratio: f64::NAN,
                ..steel
            }),
            Err("poisson_ratio")
        );
        assert_eq!(
            parameter(BodyConstants {
                poisson_ratio: 0.5,
                ..steel
            }),
            Ok(())
        );
        assert_eq!(
            parameter(BodyConstants {
                hardness: Some(210e9),
                ..steel
            }),
            Err("hardness")
        );
        assert_eq!(
            parameter(BodyConstants {
                hardness: Some(f64::NAN),
                ..steel
            }),
            Err("hardness")
        );
        assert_eq!(
            parameter(BodyConstants {
                flow_pressure: Some(300e9),
                ..steel
            }),
            Err("flow_pressure")
        );
        assert_eq!(
            parameter(BodyConstants {
                yield_strength: Some(2.1e9),
                ..steel
            }),
            Err("yield_strength")
        );
        assert_eq!(
            parameter(BodyConstants {
                yield_strength: Some(2e9),
                ..steel
            }),
            Ok(())
        );
        // k against Tabor's Y = H/2.8 when Y is not given.
        assert_eq!(
            parameter(BodyConstants {
                shear_strength: Some(0.8e9),
                ..steel
            }),
            Err("shear_strength")
        );
        assert_eq!(
            parameter(BodyConstants {
                shear_strength: Some(0.7e9),
                ..steel
            }),
            Ok(())
        );
        assert_eq!(
            parameter(BodyConstants {
                shear_strength: Some(-1.0),
                ..steel
            }),
            Err("shear_strength")
        );
    }
}
