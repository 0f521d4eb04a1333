//! `kogut_etsion`: the Kogut–Etsion 2002 load and area fits of a sphere pressed by a rigid flat
//! with the KE 2004 static friction force, as ratios to the critical values at the
//! dimensionless interference x = ω/ω_c ([`super::asperity`]). Its one parameter is the form of
//! the KE 2004 Q_max polynomial on 1 < x ≤ 6.
//!
//! The breakpoints are exactly x = 1, 6, 110 with the convention that a breakpoint belongs to
//! the range below it (x = 1 is Hertz, x = 6 uses the 1–6 fit, x = 110 the 6–110 fit). The fits
//! are NOT continuous there; the jumps are kept as published (for ν = 0.3: P/P_c at x = 1:
//! 1 → 1.03; at 6: 13.23 → 13.46; at 110: 530.2 → 571.9; A/A_c at 1: 1 → 0.93; at 6:
//! 7.12 → 7.33; at 110: 205.4 → 220).
//!
//! # Sources and what was confirmed
//! * KE 2002 load fits (Kogut & Etsion, J. Appl. Mech. 69 (2002) 657): P/P_c = x^1.5,
//!   1.03 x^1.425, 1.40 x^1.263, (3/K) x. The two elastic-plastic load fits and the fully plastic
//!   branch P = 2πRHω (= (3/K) x · P_c) were confirmed against an independent public re-statement
//!   in dimensional form (a MATLAB asperity-force routine in the repository TaoYang1999/SCHC-framework,
//!   found with the search tool: 1.37 = 1.03·4/3 and 1.87 ≈ 1.40·4/3, same exponents and
//!   breakpoints 6ω_c, 110ω_c). The three-stage structure (elastic → elastic-plastic → fully
//!   plastic) was confirmed from the KE 2002 abstract.
//! * KE 2002 area fits A/A_c = 0.93 x^1.136 (1 < x ≤ 6), 0.94 x^1.146 (6 < x ≤ 110), 2x (x > 110):
//!   NOT confirmed by the search tool (no primary or secondary text found); taken from the
//!   project's reference notes, which mark them unchecked (status: docs/friction-models.md).
//! * KE 2004 static friction (J. Tribol. 126 (2004) 34, restated by Lee & Polycarpou, J. Tribol.
//!   129 (2007) 754): Q_max/P_c = 0.52 x^0.982 (x ≤ 1),
//!   −0.01x^4.425 + 0.09x^3.425 − 0.4x^2.425 + 0.85x^1.425 (1 < x ≤ 6), 0 beyond: NOT confirmed by the search tool; from the project
//!   reference. The polynomial is 0.53 at x = 1, peaks near x ≈ 2.6 and is zero near x ≈ 4.29;
//!   [`StaticFrictionForm::Literal`] keeps the negative 4.29–6 band (the published integral),
//!   [`StaticFrictionForm::Clipped`] uses max(0, ·). At high ψ most contacting summits have
//!   x > 4.29, so the literal form can give a negative Q_max (and μ_s); this is reported as is
//!   (a sign that KE 2004 is outside its range — the Li–Etsion–Talke regime), not hidden.

use super::asperity::{AsperityLaws, ELASTIC_LIMIT};
use super::interference::InterferenceLaw;
use super::law::{FrictionLaw, LawDescriptor, LawInputs, Method, ModelBasis};
use super::parameters::{ParameterKind, ParameterSpec, ParameterValue, ReportedValue, Unit};
use crate::friction::error::FrictionError;
use crate::friction::material::Material;

/// The registry entry.
pub(super) const LAW: LawDescriptor = LawDescriptor {
    name: "kogut_etsion",
    summary: "Kogut–Etsion 2002 load/area fits with the KE 2004 static friction force",
    basis: ModelBasis::PublishedFits,
    methods: &[Method::Statistical, Method::PerSummit, Method::PerSpot],
    parameters: &[FORM],
    mu_s_max: super::asperity::YIELD_INCEPTION_MU_S_MAX,
    validated_range: "Kogut–Etsion's static friction fit ends at x = ω/ω_c = 6, beyond which an \
                      asperity carries no tangential load",
    build,
};

const FORM: ParameterSpec = ParameterSpec {
    name: "static_friction_form",
    column: "static_friction_form",
    description: "KE 2004 Q_max polynomial on 1 < x ≤ 6: `literal` (as published, negative for \
                  4.29 < x ≤ 6) or `clipped` (max(0, ·))",
    kind: ParameterKind::Choice {
        options: &["literal", "clipped"],
        default: "literal",
    },
};

/// x = 6: the break between the two elastic–plastic Kogut–Etsion fits, and where the KE 2004
/// Q_max fit ends.
pub const KE_SECOND_FIT_START: f64 = 6.0;

/// x = 110: the onset of the fully plastic Kogut–Etsion branch (and of the last adhesion fit's
/// end).
pub const KE_FULLY_PLASTIC_ONSET: f64 = 110.0;

/// The breaks of the KE 2002 load and area fits and of the KE 2003 adhesion fits.
pub const KE_BREAKPOINTS: [f64; 3] = [ELASTIC_LIMIT, KE_SECOND_FIT_START, KE_FULLY_PLASTIC_ONSET];

/// Zero of the KE 2004 polynomial x^1.425 (0.85 − 0.4x + 0.09x² − 0.01x³) in (1, 6): where the
/// clipped form has its kink (a quadrature breakpoint). Obtained by bisection to rounding.
pub const KE_STATIC_FRICTION_ZERO: f64 = 4.294_625_761_688_716_5;

/// Deformation state of an asperity by its dimensionless interference x = ω/ω_c.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DeformationState {
    /// ω ≤ 0: not touching (adhesion only through the Lennard-Jones gap force).
    NotInContact,
    /// 0 < x ≤ 1.
    Elastic,
    /// 1 < x ≤ 110.
    ElasticPlastic,
    /// x > 110.
    FullyPlastic,
}

impl DeformationState {
    /// State for a dimensionless interference x.
    pub fn from_interference_ratio(x: f64) -> Self {
        if x <= 0.0 {
            Self::NotInContact
        } else if x <= ELASTIC_LIMIT {
            Self::Elastic
        } else if x <= KE_FULLY_PLASTIC_ONSET {
            Self::ElasticPlastic
        } else {
            Self::FullyPlastic
        }
    }
}

/// Form of the KE 2004 Q_max polynomial on 1 < x ≤ 6.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum StaticFrictionForm {
    /// As published: the polynomial is used over the whole band, negative on 4.29 < x ≤ 6.
    #[default]
    Literal,
    /// max(0, polynomial).
    Clipped,
}

/// KE 2002 P/P_c at dimensionless interference x (0 for x ≤ 0); `k` is the hardness factor K.
pub fn ke_load_ratio(x: f64, k: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else if x <= ELASTIC_LIMIT {
        x.powf(1.5)
    } else if x <= KE_SECOND_FIT_START {
        1.03 * x.powf(1.425)
    } else if x <= KE_FULLY_PLASTIC_ONSET {
        1.40 * x.powf(1.263)
    } else {
        3.0 / k * x
    }
}

/// KE 2002 A/A_c at dimensionless interference x (0 for x ≤ 0).
pub fn ke_area_ratio(x: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else if x <= ELASTIC_LIMIT {
        x
    } else if x <= KE_SECOND_FIT_START {
        0.93 * x.powf(1.136)
    } else if x <= KE_FULLY_PLASTIC_ONSET {
        0.94 * x.powf(1.146)
    } else {
        2.0 * x
    }
}

/// KE 2004 Q_max/P_c at dimensionless interference x.
pub fn ke_static_friction_ratio(x: f64, form: StaticFrictionForm) -> f64 {
    if x <= 0.0 {
        0.0
    } else if x <= ELASTIC_LIMIT {
        0.52 * x.powf(0.982)
    } else if x <= KE_SECOND_FIT_START {
        let base = x.powf(1.425);
        let poly = base * (0.85 + x * (-0.4 + x * (0.09 - 0.01 * x)));
        match form {
            StaticFrictionForm::Literal => poly,
            StaticFrictionForm::Clipped => poly.max(0.0),
        }
    } else {
        0.0
    }
}

/// The Kogut–Etsion laws of one material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KogutEtsion {
    material: Material,
    form: StaticFrictionForm,
}

impl KogutEtsion {
    /// The laws of `material` with the Q_max polynomial in `form`.
    pub fn new(material: Material, form: StaticFrictionForm) -> Self {
        Self { material, form }
    }
}

fn build(inputs: &LawInputs) -> Result<Box<dyn FrictionLaw>, FrictionError> {
    let form = match inputs.parameters.choice(FORM.name)? {
        "literal" => StaticFrictionForm::Literal,
        "clipped" => StaticFrictionForm::Clipped,
        _ => {
            return Err(FrictionError::InvalidParameter {
                name: FORM.name,
                value: f64::NAN,
                expected: "`literal` or `clipped`",
            })
        }
    };
    Ok(Box::new(KogutEtsion::new(inputs.material, form)))
}

impl InterferenceLaw for KogutEtsion {
    const DESCRIPTOR: &'static LawDescriptor = &LAW;

    fn material(&self) -> &Material {
        &self.material
    }

    fn parameter_values(&self) -> Vec<ReportedValue> {
        let form = match self.form {
            StaticFrictionForm::Literal => "literal",
            StaticFrictionForm::Clipped => "clipped",
        };
        vec![ReportedValue {
            column: FORM.column,
            value: ParameterValue::Choice(form),
            unit: Unit::Dimensionless,
        }]
    }
}

impl AsperityLaws for KogutEtsion {
    fn load_ratio(&self, x: f64) -> f64 {
        ke_load_ratio(x, self.material.hardness_factor())
    }

    fn area_ratio(&self, x: f64) -> f64 {
        ke_area_ratio(x)
    }

    fn friction_ratio(&self, x: f64) -> f64 {
        ke_static_friction_ratio(x, self.form)
    }

    fn load_breaks(&self) -> Vec<f64> {
        KE_BREAKPOINTS.to_vec()
    }

    fn friction_breaks(&self) -> Vec<f64> {
        vec![ELASTIC_LIMIT, KE_STATIC_FRICTION_ZERO]
    }

    /// KE 2004 Q_max is fitted up to x = 6 and zero beyond.
    fn friction_support(&self) -> f64 {
        KE_SECOND_FIT_START
    }

    /// Beyond x = 6 the yield-inception criterion gives no tangential load.
    fn fit_limit(&self) -> f64 {
        KE_SECOND_FIT_START
    }
}
