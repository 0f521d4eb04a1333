//! `full_stick`: the Brizmer–Kligerman–Etsion full-stick asperity with the Jackson–Green
//! hand-over beyond ω* = 110 and μ(P*) = a coth(a P*^b) (equations and status: [`stick`] and
//! [`jackson_green`]). Parameters: `a`, `b` of μ(P*), attributed defaults that
//! could not be confirmed, hence [`ModelBasis::ParameterisedUnverified`].
//!
//! Its laws are ratios to the BKE slip critical values; in Kogut–Etsion ratios, with
//! r = ω_c,BKE/ω_c,KE (both ∝ R, so r depends on the material only) and
//! P_c,BKE/P_c,KE = r^{3/2} (both are (4/3)E'R²(ω_c/R)^{3/2}):
//! P/P_c = r^{3/2} (P/P_c,BKE)(x/r), A/A_c = r (A/A_c,BKE)(x/r), Q/P_c = r^{3/2} (Q/P_c,BKE)(x/r).

use std::sync::Arc;

pub mod jackson_green;
pub mod stick;

use super::asperity::AsperityLaws;
use super::law::{FrictionLaw, LawDescriptor, LawInputs, Method, ModelBasis};
use super::parameters::{
    NumberRange, ParameterKind, ParameterSpec, ParameterValue, ReportedValue, Unit,
};
use super::spot::{SpotFriction, SpotGeometry, SpotLoad};
use crate::friction::error::FrictionError;
use crate::friction::material::Material;
use stick::{FullStickLaw, StickFrictionLaw, STICK_LOAD_FIT_LIMIT};

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "full_stick",
    summary: "Brizmer–Kligerman–Etsion full-stick asperity (Jackson–Green beyond ω* = 110), \
              Q_max = μ(P*) P with μ(P*) = a coth(a P*^b)",
    basis: ModelBasis::ParameterisedUnverified,
    methods: &[Method::Statistical, Method::PerSummit, Method::PerSpot],
    parameters: &[A, B],
    mu_s_max: super::law::DRY_METAL_MU_S_MAX,
    validated_range: "the full-stick μ(P*) fit ends at ω* = 110, beyond which μ(P*) is \
                      extrapolated",
    build,
};

const A: ParameterSpec = ParameterSpec {
    name: "a",
    column: "stick_law_a",
    description: "a > 0 in μ(P*) = a coth(a P*^b), the large-load limit of μ; default 0.27 \
                  attributed to Brizmer, Kligerman & Etsion (2007), not confirmed",
    kind: ParameterKind::Number {
        default: 0.27,
        range: NumberRange::POSITIVE,
        unit: Unit::Dimensionless,
    },
};

const B: ParameterSpec = ParameterSpec {
    name: "b",
    column: "stick_law_b",
    description: "b in (0, 1) in μ(P*) = a coth(a P*^b), the load exponent (Q_max = μP then \
                  vanishes with the load); default 0.35 attributed to Brizmer, Kligerman & \
                  Etsion (2007), not confirmed",
    kind: ParameterKind::Number {
        default: 0.35,
        range: NumberRange {
            min: 0.0,
            min_inclusive: false,
            max: 1.0,
            max_inclusive: false,
        },
        unit: Unit::Dimensionless,
    },
};

/// Inputs of the full-stick law beyond the [`Material`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FullStickOptions {
    /// Yield strength Y of the softer body (Pa); `None`: Tabor's Y = H/2.8
    /// ([`Material::tabor_yield_strength`]).
    pub yield_strength: Option<f64>,
    /// μ(P*) of a sticking asperity.
    pub friction_law: StickFrictionLaw,
}

/// The full-stick laws of one material, also in Kogut–Etsion ratios (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullStick {
    law: FullStickLaw,
    composite_modulus: f64,
    yield_strength: f64,
    /// r = ω_c,BKE/ω_c,KE.
    r: f64,
    r_pow_1_5: f64,
}

impl FullStick {
    /// The laws for `material` with `options`; the softer body's ν must lie in [0.2, 0.5).
    pub fn new(material: &Material, options: FullStickOptions) -> Result<Self, FrictionError> {
        let yield_strength = options
            .yield_strength
            .unwrap_or_else(|| material.tabor_yield_strength());
        let law = FullStickLaw::new(
            yield_strength,
            material.composite_modulus,
            material.poisson_ratio,
            options.friction_law,
        )?;
        let ke = material.critical_values(1.0).interference;
        let r = law.critical_interference_over_radius / ke;
        Ok(Self {
            law,
            composite_modulus: material.composite_modulus,
            yield_strength,
            r,
            r_pow_1_5: r.powf(1.5),
        })
    }

    /// The BKE laws in their own (slip critical value) units.
    pub fn law(&self) -> &FullStickLaw {
        &self.law
    }
}

fn build(inputs: &LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError> {
    let friction_law = StickFrictionLaw::new(
        inputs.parameters.number(A.name)?,
        inputs.parameters.number(B.name)?,
    )?;
    let options = FullStickOptions {
        yield_strength: Some(inputs.yield_strength),
        friction_law,
    };
    Ok(Box::new(FullStick::new(&inputs.material, options)?))
}

impl FrictionLaw for FullStick {
    fn descriptor(&self) -> &'static LawDescriptor {
        &LAW
    }

    fn asperity_laws(self: Arc<Self>) -> Option<Arc<dyn AsperityLaws>> {
        Some(self)
    }

    /// Q_i = μ(P_i*) P_i with P_i* = P_i/L_c(R_i), L_c = L̄_c P_c(R_i); beyond the fit when P_i*
    /// exceeds the stick load fit at ω* = 110.
    fn spot_friction(&self, spot: &SpotLoad, _: Option<&SpotGeometry>) -> Option<SpotFriction> {
        let radius = spot.radius?;
        let law = &self.law;
        let stick_load =
            law.stick_load_factor * law.critical_values(radius, self.composite_modulus).load;
        let p_star = spot.load / stick_load;
        Some(SpotFriction {
            friction_force: stick_load * law.friction_law.friction_ratio(p_star),
            load_measure: Some(p_star),
            beyond_fit: p_star > law.load_at_fit_limit(),
            radius_based: true,
            ..SpotFriction::default()
        })
    }

    fn reported_values(&self) -> Vec<ReportedValue> {
        let number = |spec: &ParameterSpec, v: f64, unit: Unit| ReportedValue {
            column: spec.column,
            value: ParameterValue::Number(v),
            unit,
        };
        let StickFrictionLaw { a, b } = self.law.friction_law;
        vec![
            number(&A, a, Unit::Dimensionless),
            number(&B, b, Unit::Dimensionless),
            ReportedValue {
                column: "yield_strength",
                value: ParameterValue::Number(self.yield_strength),
                unit: Unit::Pressure,
            },
        ]
    }
}

impl AsperityLaws for FullStick {
    fn load_ratio(&self, x: f64) -> f64 {
        self.r_pow_1_5 * self.law.load_ratio(x / self.r)
    }

    fn area_ratio(&self, x: f64) -> f64 {
        self.r * self.law.area_ratio(x / self.r)
    }

    fn friction_ratio(&self, x: f64) -> f64 {
        self.r_pow_1_5 * self.law.friction_ratio(x / self.r)
    }

    fn load_breaks(&self) -> Vec<f64> {
        self.law.breakpoints().iter().map(|w| w * self.r).collect()
    }

    fn friction_breaks(&self) -> Vec<f64> {
        self.load_breaks()
    }

    /// μ(P*) P never vanishes.
    fn friction_support(&self) -> f64 {
        f64::INFINITY
    }

    /// The stick load fit ends at ω* = 110.
    fn fit_limit(&self) -> f64 {
        self.r * self.law.stick_interference_factor * STICK_LOAD_FIT_LIMIT
    }
}
