//! The single-asperity laws of each interference-driven model in one common form: ratios to the
//! Kogut–Etsion critical values of the asperity (x = ω/ω_c, P/P_c, A/A_c, Q_max/P_c with
//! ω_c = (πKH/(2E'))² R, P_c = (2/3)πKHRω_c, A_c = πRω_c, see [`super::material`]), so the
//! statistical integrals and the per-summit model treat every model alike.
//!
//! * Kogut–Etsion: KE 2002 load and area, KE 2004 Q_max ([`super::asperity_laws`]).
//! * Chang–Etsion–Bogy baseline ([`super::asperity_laws`]).
//! * Full stick: the Brizmer–Kligerman–Etsion stick load fit with the Jackson–Green hand-over
//!   beyond ω* = 110, the Jackson–Green area and Q_max = μ(P*) P ([`super::full_stick`]). Its
//!   laws are ratios to the BKE slip critical values; with r = ω_c,BKE/ω_c,KE (both ∝ R, so r
//!   depends on the material only) and P_c,BKE/P_c,KE = r^{3/2} (both are (4/3)E'R²(ω_c/R)^{3/2}):
//!   P/P_c = r^{3/2} (P/P_c,BKE)(x/r), A/A_c = r (A/A_c,BKE)(x/r), Q/P_c = r^{3/2} (Q/P_c,BKE)(x/r).
//!
//! Each model also states where its friction law leaves its validated range (`fit_limit`, in x):
//! KE 2004 Q_max is fitted up to x = 6 (beyond it the yield-inception criterion gives no
//! tangential load); the CEB baseline lets only elastic asperities (x ≤ 1) carry it; the full-stick
//! load fit ends at ω* = 110.

use super::asperity_laws::{
    ceb_area_ratio, ceb_load_ratio, ceb_static_friction_ratio, ke_area_ratio, ke_load_ratio,
    ke_static_friction_ratio, AsperityModel, KE_STATIC_FRICTION_ZERO,
};
use super::error::FrictionError;
use super::full_stick::{FullStickLaw, STICK_LOAD_FIT_LIMIT};
use super::material::Material;
use super::model_options::ModelOptions;

/// How far a model's constants are confirmed (written to every friction row).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelBasis {
    /// Published finite-element fits restated in the project reference (Kogut–Etsion, CEB).
    PublishedFits,
    /// A textbook law with a stated material parameter (junction shear).
    TextbookLaw,
    /// The law's structure is from the literature but some constants are attributed defaults that
    /// could not be confirmed (full stick: μ(P*) = a coth(a P*^b)); they are parameters.
    ParameterisedUnverified,
}

impl ModelBasis {
    /// The label written to tables.
    pub fn name(self) -> &'static str {
        match self {
            Self::PublishedFits => "published_fits",
            Self::TextbookLaw => "textbook_law",
            Self::ParameterisedUnverified => "parameterised_unverified",
        }
    }
}

/// A model's laws as ratios to the KE critical values (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelLaws {
    model: AsperityModel,
    hardness_factor: f64,
    options: ModelOptions,
    /// The full-stick laws in KE ratios.
    full_stick: Option<ScaledStickLaw>,
}

/// The full-stick laws with r = ω_c,BKE/ω_c,KE and r^{3/2} (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
struct ScaledStickLaw {
    law: FullStickLaw,
    r: f64,
    r_pow_1_5: f64,
}

impl ModelLaws {
    /// The laws of `model` for `material`; the full-stick model validates ν ∈ [0.2, 0.5) and its
    /// options.
    pub fn new(
        model: AsperityModel,
        material: &Material,
        options: ModelOptions,
    ) -> Result<Self, FrictionError> {
        let full_stick = match model {
            AsperityModel::FullStick => {
                let law = options.full_stick.law(material)?;
                let ke = material.critical_values(1.0).interference;
                let r = law.critical_interference_over_radius / ke;
                Some(ScaledStickLaw {
                    law,
                    r,
                    r_pow_1_5: r.powf(1.5),
                })
            }
            AsperityModel::KogutEtsion | AsperityModel::ChangEtsionBogy => None,
        };
        Ok(Self {
            model,
            hardness_factor: material.hardness_factor(),
            options,
            full_stick,
        })
    }

    /// The model.
    pub fn model(&self) -> AsperityModel {
        self.model
    }

    /// The full-stick laws, for that model.
    pub fn full_stick(&self) -> Option<&FullStickLaw> {
        self.full_stick.as_ref().map(|s| &s.law)
    }

    /// How far the model's constants are confirmed.
    pub fn basis(&self) -> ModelBasis {
        match self.model {
            AsperityModel::KogutEtsion | AsperityModel::ChangEtsionBogy => {
                ModelBasis::PublishedFits
            }
            AsperityModel::FullStick => ModelBasis::ParameterisedUnverified,
        }
    }

    /// P/P_c at x.
    pub fn load_ratio(&self, x: f64) -> f64 {
        match (self.model, self.full_stick) {
            (AsperityModel::FullStick, Some(s)) => s.r_pow_1_5 * s.law.load_ratio(x / s.r),
            (AsperityModel::ChangEtsionBogy, _) => ceb_load_ratio(x),
            _ => ke_load_ratio(x, self.hardness_factor),
        }
    }

    /// A/A_c at x.
    pub fn area_ratio(&self, x: f64) -> f64 {
        match (self.model, self.full_stick) {
            (AsperityModel::FullStick, Some(s)) => s.r * s.law.area_ratio(x / s.r),
            (AsperityModel::ChangEtsionBogy, _) => ceb_area_ratio(x),
            _ => ke_area_ratio(x),
        }
    }

    /// Q_max/P_c at x.
    pub fn friction_ratio(&self, x: f64) -> f64 {
        match (self.model, self.full_stick) {
            (AsperityModel::FullStick, Some(s)) => s.r_pow_1_5 * s.law.friction_ratio(x / s.r),
            (AsperityModel::ChangEtsionBogy, _) => ceb_static_friction_ratio(x),
            _ => ke_static_friction_ratio(x, self.options.static_friction_form),
        }
    }

    /// Breaks in x of the load and area laws (smooth between them).
    pub fn load_breaks(&self) -> Vec<f64> {
        match (self.model, self.full_stick) {
            (AsperityModel::FullStick, Some(s)) => {
                s.law.breakpoints().iter().map(|w| w * s.r).collect()
            }
            (AsperityModel::ChangEtsionBogy, _) => vec![1.0],
            _ => vec![1.0, 6.0, 110.0],
        }
    }

    /// κ ∈ (0, 1] with P/P_c(x′) ≤ P/P_c(x)/κ for every x′ ≤ x: the load laws increase between
    /// their breaks, so κ is the product of the drops at the breaks (1 when the law never drops;
    /// the full-stick hand-over to Jackson–Green at ω* = 110 drops by a few per cent).
    pub fn load_drop_bound(&self) -> f64 {
        self.load_breaks()
            .iter()
            .map(|&b| {
                let before = self.load_ratio(b);
                let after = self.load_ratio(b * (1.0 + 1e-12));
                if before > 0.0 {
                    (after / before).min(1.0)
                } else {
                    1.0
                }
            })
            .product()
    }

    /// Breaks in x of the friction law below [`Self::friction_support`].
    pub fn friction_breaks(&self) -> Vec<f64> {
        match self.model {
            AsperityModel::FullStick => self.load_breaks(),
            AsperityModel::ChangEtsionBogy => Vec::new(),
            AsperityModel::KogutEtsion => vec![1.0, KE_STATIC_FRICTION_ZERO],
        }
    }

    /// The x beyond which Q_max/P_c is zero (+∞ when it never is).
    pub fn friction_support(&self) -> f64 {
        match self.model {
            AsperityModel::KogutEtsion => 6.0,
            AsperityModel::ChangEtsionBogy => 1.0,
            AsperityModel::FullStick => f64::INFINITY,
        }
    }

    /// The x beyond which the friction law is outside its validated range (see the module docs).
    pub fn fit_limit(&self) -> f64 {
        match (self.model, self.full_stick) {
            (AsperityModel::FullStick, Some(s)) => {
                s.r * s.law.stick_interference_factor * STICK_LOAD_FIT_LIMIT
            }
            (AsperityModel::ChangEtsionBogy, _) => 1.0,
            _ => 6.0,
        }
    }
}
