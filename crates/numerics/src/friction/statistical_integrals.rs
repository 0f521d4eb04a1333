//! Greenwood–Williamson statistical integrals of any interference-driven law ([`AsperityLaws`]):
//! contact load P(d*), real contact area A(d*), adhesion force F_s(d*) (contacting and
//! non-contacting summits), static friction force Q_max(d*) and the number of contacts N(d*).
//!
//! With summit heights z* (in σ units, from the summit mean plane) Gaussian with std s = σ_s/σ,
//! d* the dimensionless separation of the flat from the summit mean plane, ω_c* = ω_c/σ and
//! x = (z* − d*)/ω_c*:
//!
//! ```text
//! P   = η A_n P_c   ∫_{d*}^∞ (P/P_c)(x) φ*(z*) dz*        (= (2/3)π β A_n H K ω_c* ∫ … , KE 2003)
//! A   = η A_n A_c   ∫_{d*}^∞ (A/A_c)(x) φ*(z*) dz*
//! Q   = η A_n P_c   ∫_{d*}^∞ (Q/P_c)(x) φ*(z*) dz*        (KE 2004 eq. 8)
//! F_s = η A_n 2πRΔγ [ ∫_{d*}^∞ (F_s/2πRΔγ)(x) φ* dz* + ∫_{−∞}^{d*} f(h)/(2πRΔγ) φ* dz* ]
//! N   = η A_n ∫_{d*}^∞ φ* dz*
//! ```
//!
//! with h = ε + σ(d* − z*) the gap of a non-contacting summit. Numerics (docs/friction-models.md): contact
//! integrals are taken in x, split at x = 1, 6, 110 and at the Gaussian peak and flanks
//! (z* = 0, ±s, ±2s, ±4s, ±8s), graded at x = 0 (x = x₁u³, so x^b with b < 1 is smooth in u), cut
//! at z* = max(d*, 0) + 40s (φ* < 1e-300 beyond); the non-contacting integral uses h = ε(1 + t)
//! in the variable v = ln(1 + t) (decades of t equally spaced, the (ε/h)² decay becomes e⁻ᵛ),
//! split at the Gaussian features, cut at z* = min(d*, 0) − 40s. Every
//! integral is adaptive Gauss–Kronrod 7/15 to relative tolerance [`INTEGRAL_REL_TOL`] (1e-10)
//! with no absolute tolerance (only an exactly-zero integrand stops on error = 0).

use std::sync::Arc;

use super::adhesion::{
    contacting_adhesion_ratio, contacting_adhesion_ratio_max, lennard_jones_adhesion_ratio,
    AdhesionBeyondFits,
};
use super::error::{require_positive, FrictionError};
use super::gw_functions::{
    normal_pdf, upper_tail_probability, GAUSSIAN_CUT, GAUSSIAN_FEATURES, INTEGRAL_REL_TOL,
};
use super::laws::asperity::AsperityLaws;
use super::laws::kogut_etsion::KE_BREAKPOINTS;
use super::material::{AdhesionParameters, CriticalValues, Material};
use super::quadrature::{
    breakpoints, integrate, pieces_graded_at_start, Grading, Piece, QuadratureOutcome,
};
use super::summit_statistics::SummitStatistics;

/// A statistical static-friction model ready to evaluate its integrals.
#[derive(Debug, Clone)]
pub struct StatisticalModel {
    /// Summit statistics of the equivalent surface.
    pub summits: SummitStatistics,
    /// Material of the pair.
    pub material: Material,
    /// Adhesion energy and LJ distance.
    pub adhesion: AdhesionParameters,
    /// Nominal area A_n (m²).
    pub nominal_area: f64,
    /// Contacting adhesion beyond x = 110 (no published fit there).
    pub adhesion_beyond_fits: AdhesionBeyondFits,
    /// Critical values at the mean summit radius.
    pub critical: CriticalValues,
    /// Plasticity index ψ (with σ_s).
    pub plasticity_index: f64,
    /// The single-asperity laws.
    pub laws: Arc<dyn AsperityLaws>,
}

/// An integral in SI units with its quadrature diagnostics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegralValue {
    /// Value (N, m² or count).
    pub value: f64,
    /// Estimated absolute error (same unit).
    pub error: f64,
    /// Integrand evaluations spent.
    pub evaluations: usize,
}

/// Adhesion force split into its contacting and non-contacting parts (N, attractive positive).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdhesionForce {
    /// Summits in contact (KE 2003 fits).
    pub contacting: IntegralValue,
    /// Summits not in contact (DMT / Lennard-Jones).
    pub non_contacting: IntegralValue,
}

impl AdhesionForce {
    /// Total adhesion force F_s (N).
    pub fn total(&self) -> f64 {
        self.contacting.value + self.non_contacting.value
    }
}

fn finished(
    outcome: QuadratureOutcome,
    scale: f64,
    what: &'static str,
) -> Result<IntegralValue, FrictionError> {
    if outcome.converged && outcome.value.is_finite() {
        Ok(IntegralValue {
            value: scale * outcome.value,
            error: scale * outcome.error,
            evaluations: outcome.evaluations,
        })
    } else {
        Err(FrictionError::QuadratureNotConverged {
            what,
            value: outcome.value,
            error: outcome.error,
        })
    }
}

impl StatisticalModel {
    /// Build a model; validates the nominal area (> 0). ψ and the critical values use σ_s and R.
    pub fn new(
        laws: Arc<dyn AsperityLaws>,
        summits: SummitStatistics,
        material: Material,
        adhesion: AdhesionParameters,
        nominal_area: f64,
        adhesion_beyond_fits: AdhesionBeyondFits,
    ) -> Result<Self, FrictionError> {
        let nominal_area = require_positive("nominal_area", nominal_area)?;
        // The component types have public fields: re-validate them here.
        let material = Material::new(
            material.composite_modulus,
            material.hardness,
            material.poisson_ratio,
        )?;
        let adhesion = AdhesionParameters::new(adhesion.energy, adhesion.equilibrium_distance)?;
        let summits = summits.validated()?;
        let critical = material.critical_values(summits.radius);
        let plasticity_index = material.plasticity_index(summits.sigma_s, summits.radius);
        Ok(Self {
            laws,
            summits,
            material,
            adhesion,
            nominal_area,
            adhesion_beyond_fits,
            critical,
            plasticity_index,
        })
    }

    /// Summit-height std in σ units, s = σ_s/σ.
    pub fn summit_std_star(&self) -> f64 {
        self.summits.summit_std_ratio()
    }

    /// ω_c* = ω_c/σ.
    pub fn critical_interference_star(&self) -> f64 {
        self.critical.interference / self.summits.sigma
    }

    fn summit_count(&self) -> f64 {
        self.summits.density * self.nominal_area
    }

    fn adhesion_scale(&self) -> f64 {
        self.summit_count()
            * 2.0
            * std::f64::consts::PI
            * self.summits.radius
            * self.adhesion.energy
    }

    /// ∫ law((z* − d*)/ω_c*) φ*(z*) dz* over the summits with x_from ≤ x ≤ x_support.
    fn contact_integral(
        &self,
        d_star: f64,
        law: &dyn Fn(f64) -> f64,
        law_breaks: &[f64],
        (x_from, x_support): (f64, f64),
    ) -> QuadratureOutcome {
        let s = self.summit_std_star();
        let wc = self.critical_interference_star();
        let z_max = d_star.max(0.0) + GAUSSIAN_CUT * s;
        let x_max = ((z_max - d_star) / wc).min(x_support);
        if x_from >= x_max {
            return QuadratureOutcome {
                value: 0.0,
                error: 0.0,
                evaluations: 0,
                converged: true,
            };
        }
        let mut candidates: Vec<f64> = law_breaks.to_vec();
        candidates.extend(GAUSSIAN_FEATURES.iter().map(|g| (g * s - d_star) / wc));
        let points = breakpoints(x_from, x_max, &candidates);
        let integrand = |x: f64| law(x) * normal_pdf(d_star + wc * x, s) * wc;
        let pieces = pieces_graded_at_start(&points, &integrand);
        integrate(&pieces, INTEGRAL_REL_TOL, 0.0)
    }

    /// Contact load P(d*) (N).
    pub fn contact_load(&self, d_star: f64) -> Result<IntegralValue, FrictionError> {
        let laws = &self.laws;
        let outcome = self.contact_integral(
            d_star,
            &|x| laws.load_ratio(x),
            &laws.load_breaks(),
            (0.0, f64::INFINITY),
        );
        finished(
            outcome,
            self.summit_count() * self.critical.load,
            "contact load P",
        )
    }

    /// The part of the contact load P(d*) (N) carried by summits beyond the validated range of
    /// the model's friction law (x > [`AsperityLaws::fit_limit`]).
    pub fn load_beyond_fit(&self, d_star: f64) -> Result<IntegralValue, FrictionError> {
        let laws = &self.laws;
        let outcome = self.contact_integral(
            d_star,
            &|x| laws.load_ratio(x),
            &laws.load_breaks(),
            (laws.fit_limit(), f64::INFINITY),
        );
        finished(
            outcome,
            self.summit_count() * self.critical.load,
            "contact load beyond the fit",
        )
    }

    /// Real contact area A(d*) (m²).
    pub fn contact_area(&self, d_star: f64) -> Result<IntegralValue, FrictionError> {
        let laws = &self.laws;
        let outcome = self.contact_integral(
            d_star,
            &|x| laws.area_ratio(x),
            &laws.load_breaks(),
            (0.0, f64::INFINITY),
        );
        finished(
            outcome,
            self.summit_count() * self.critical.area,
            "contact area A",
        )
    }

    /// Static friction force Q_max(d*) (N): KE 2004 (literal or clipped polynomial), the CEB
    /// baseline (elastic asperities only) or full stick.
    pub fn static_friction_force(&self, d_star: f64) -> Result<IntegralValue, FrictionError> {
        let laws = &self.laws;
        let outcome = self.contact_integral(
            d_star,
            &|x| laws.friction_ratio(x),
            &laws.friction_breaks(),
            (0.0, laws.friction_support()),
        );
        finished(
            outcome,
            self.summit_count() * self.critical.load,
            "static friction force Q_max",
        )
    }

    /// Adhesion force F_s(d*) (N), contacting + non-contacting. Exactly zero when Δγ = 0.
    pub fn adhesion_force(&self, d_star: f64) -> Result<AdhesionForce, FrictionError> {
        let zero = IntegralValue {
            value: 0.0,
            error: 0.0,
            evaluations: 0,
        };
        if self.adhesion.energy == 0.0 {
            return Ok(AdhesionForce {
                contacting: zero,
                non_contacting: zero,
            });
        }
        let scale = self.adhesion_scale();
        let eps_over_wc = self.adhesion.equilibrium_distance / self.critical.interference;
        let beyond = self.adhesion_beyond_fits;
        let contacting = self.contact_integral(
            d_star,
            &|x| contacting_adhesion_ratio(x, eps_over_wc, beyond),
            &KE_BREAKPOINTS,
            (0.0, f64::INFINITY),
        );
        let contacting = finished(contacting, scale, "contacting adhesion force")?;
        let non_contacting = finished(
            self.non_contacting_integral(d_star),
            scale,
            "non-contacting adhesion force",
        )?;
        Ok(AdhesionForce {
            contacting,
            non_contacting,
        })
    }

    /// An upper bound of F_s(d*) (N) for every d*: each summit adheres with at most
    /// 2πRΔγ · max(1, max_x F_s/(2πRΔγ) of a contacting summit) (the Lennard-Jones force of a
    /// non-contacting summit peaks at 2πRΔγ at h = ε). `None` when the contacting law is unbounded
    /// ([`AdhesionBeyondFits::ExtendLastFit`]); 0 without adhesion.
    pub fn adhesion_force_bound(&self) -> Option<f64> {
        if self.adhesion.energy == 0.0 {
            return Some(0.0);
        }
        let eps_over_wc = self.adhesion.equilibrium_distance / self.critical.interference;
        let contacting = contacting_adhesion_ratio_max(eps_over_wc, self.adhesion_beyond_fits)?;
        Some(self.adhesion_scale() * contacting.max(1.0))
    }

    /// ∫_{−∞}^{d*} f(h)/(2πRΔγ) φ*(z*) dz* with h = ε(1 + t), z* = d* − (ε/σ) t, taken in
    /// v = ln(1 + t) (so the decades t = 1, 10, 100, … are equally spaced and (1 + t)⁻² dt = e⁻ᵛ dv
    /// is smooth), split at the Gaussian peak and flanks.
    fn non_contacting_integral(&self, d_star: f64) -> QuadratureOutcome {
        let s = self.summit_std_star();
        let eps_star = self.adhesion.equilibrium_distance / self.summits.sigma;
        let z_low = d_star.min(0.0) - GAUSSIAN_CUT * s;
        let v_max = ((d_star - z_low) / eps_star).ln_1p();
        let candidates: Vec<f64> = GAUSSIAN_FEATURES
            .iter()
            .map(|g| (d_star - g * s) / eps_star)
            .filter(|t| *t > 0.0)
            .map(f64::ln_1p)
            .collect();
        let points = breakpoints(0.0, v_max, &candidates);
        let integrand = |v: f64| {
            let h_over_eps = v.exp();
            lennard_jones_adhesion_ratio(h_over_eps)
                * h_over_eps
                * normal_pdf(d_star - eps_star * (h_over_eps - 1.0), s)
                * eps_star
        };
        let pieces: Vec<Piece<'_>> = points
            .windows(2)
            .map(|w| Piece {
                a: w[0],
                b: w[1],
                grading: Grading::Uniform,
                f: &integrand,
            })
            .collect();
        integrate(&pieces, INTEGRAL_REL_TOL, 0.0)
    }

    /// Expected number of contacting summits N(d*) = η A_n ∫_{d*}^∞ φ* dz* (closed form via erfc).
    pub fn contacting_summits(&self, d_star: f64) -> f64 {
        self.summit_count() * upper_tail_probability(d_star / self.summit_std_star())
    }
}
