//! The material of a contact problem: a [`MaterialPair`] and the pressure cap it is solved with.

use crate::materials::{bounds, BodyConstants, BodyMaterial, MaterialError, MaterialPair};

/// Material data of an elastic–perfectly-plastic contact pair.
///
/// * Composite (effective) modulus `E*` of the pair ([`MaterialPair::composite`], Johnson 1985,
///   eq. 4.22): `1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂`, a rigid counter-body adding 0.
/// * Plastic flow pressure `p_lim` in Pa: the local contact pressure cannot exceed it
///   (elastic–perfectly-plastic half-space with pressure saturation, Almqvist et al. 2007,
///   Wear 262). The pair's own (the lowest of the bodies') unless the contact gives one;
///   `f64::INFINITY` is a purely elastic contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactMaterial {
    pair: MaterialPair,
    flow_pressure: f64,
}

impl ContactMaterial {
    /// The pair with its own flow pressure ([`MaterialPair::flow_pressure`]); purely elastic when
    /// neither body has one.
    pub fn new(pair: MaterialPair) -> Self {
        Self {
            pair,
            flow_pressure: pair.flow_pressure().unwrap_or(f64::INFINITY),
        }
    }

    /// The pair capped at a flow pressure `p_lim` (Pa, > 0; `f64::INFINITY`: purely elastic) of
    /// the contact's own, in place of the pair's.
    pub fn with_flow_pressure(
        pair: MaterialPair,
        flow_pressure: f64,
    ) -> Result<Self, MaterialError> {
        Ok(Self {
            pair,
            flow_pressure: bounds::contact_flow_pressure(flow_pressure)?,
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
        let pair = MaterialPair::new(
            BodyMaterial::elastic(youngs_first, poisson_first)?,
            Some(BodyMaterial::elastic(youngs_second, poisson_second)?),
        );
        Self::with_flow_pressure(pair, flow_pressure)
    }

    /// An elastic body of composite modulus `E*` (Pa) against a rigid flat, flow pressure in Pa:
    /// a body of E = E* and ν = 0, whose compliance is 1/E*.
    pub fn against_rigid_flat(
        composite_modulus: f64,
        flow_pressure: f64,
    ) -> Result<Self, MaterialError> {
        let body = BodyMaterial::new(BodyConstants::elastic(composite_modulus, 0.0))?;
        Self::with_flow_pressure(MaterialPair::against_rigid(body), flow_pressure)
    }

    /// The material pair.
    pub fn pair(&self) -> &MaterialPair {
        &self.pair
    }

    /// Composite modulus `E*` in Pa.
    pub fn composite_modulus(&self) -> f64 {
        self.pair.composite().modulus
    }

    /// Plastic flow pressure `p_lim` in Pa (`f64::INFINITY` for purely elastic).
    pub fn flow_pressure(&self) -> f64 {
        self.flow_pressure
    }

    /// Whether the contact is purely elastic: no flow pressure caps its pressure.
    pub fn is_elastic(&self) -> bool {
        self.flow_pressure() == f64::INFINITY
    }

    /// Share `c₁ / (c₁ + c₂)` of the composite elastic deformation carried by the lower body.
    pub fn first_body_share(&self) -> f64 {
        self.pair.composite().lower_share
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
        assert!(m.is_elastic());
    }

    #[test]
    fn the_pair_gives_its_lowest_flow_pressure() {
        let body = |h| BodyMaterial::new(BodyConstants::with_hardness(210e9, 0.3, h)).unwrap();
        let m = ContactMaterial::new(MaterialPair::new(body(3e9), Some(body(2e9))));
        assert_eq!(m.flow_pressure(), 2e9);
        let elastic = BodyMaterial::elastic(210e9, 0.3).unwrap();
        assert!(ContactMaterial::new(MaterialPair::against_rigid(elastic)).is_elastic());
    }

    #[test]
    fn rejects_bad_input() {
        let parameter = |m: Result<ContactMaterial, MaterialError>| m.map_err(|e| e.parameter());
        assert_eq!(
            parameter(ContactMaterial::from_young_poisson(
                -1.0, 0.3, 1e9, 0.3, 1e9
            ))
            .err(),
            Some("youngs_modulus")
        );
        assert_eq!(
            parameter(ContactMaterial::from_young_poisson(1e9, 0.7, 1e9, 0.3, 1e9)).err(),
            Some("poisson_ratio")
        );
        assert_eq!(
            parameter(ContactMaterial::against_rigid_flat(1e9, f64::NAN)).err(),
            Some("flow_pressure")
        );
        assert_eq!(
            parameter(ContactMaterial::against_rigid_flat(f64::INFINITY, 1e9)).err(),
            Some("youngs_modulus")
        );
    }
}
