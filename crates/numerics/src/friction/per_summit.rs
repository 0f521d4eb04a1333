//! Per-summit (deterministic) static friction: the single-asperity laws applied to identified
//! summits of a measured or synthetic surface (docs/friction-models.md, "Per summit").
//!
//! Input per summit: radius of curvature R_i (m) and interference ω_i (m) taken from the contact
//! solution at the summit position (ω_i ≤ 0: not in contact, gap g_i = −ω_i). With
//! ω_c,i = (πKH/2E)² R_i and x_i = ω_i/ω_c,i, each summit gets
//!
//! * F_n = P_c,i · (P/P_c)(x_i) (the law's [`AsperityLaws`]), 0 when
//!   not in contact;
//! * F_a = 2πR_iΔγ · (KE 2003 contacting fit at x_i, ε/ω_c,i) in contact, or the DMT/LJ force
//!   2πR_iΔγ [(4/3)(ε/h)² − (1/3)(ε/h)⁸] with h = ε + g_i out of contact;
//! * F_f = Q_max = P_c,i · (Q/P_c)(x_i) (KE 2004, literal or clipped; CEB: elastic summits only;
//!   full stick: μ(P*) P);
//! * local μ = F_f / (F_n − F_a) when F_n − F_a > 0;
//! * the deformation state (elastic x ≤ 1, elastic-plastic 1 < x ≤ 110, fully plastic x > 110).
//!
//! The section value is the force-weighted μ = ΣF_f / Σ(F_n − F_a) over all summits (non-contacting
//! summits contribute their adhesion to the denominator), i.e. Coulomb's law for the section as a
//! whole, not a mean of local ratios.
//!
//! # Homogenization from a section to the whole surface
//! The section is a statistically representative sample of a stationary surface, so sums of forces
//! scale with area: the whole-surface forces are the section sums times A_n/A_section (summit
//! density η_section = count/A_section estimates η), and the force-weighted μ of the section is the
//! estimate of the whole surface's μ (the ratio is invariant under that scaling). Its sampling
//! uncertainty can be judged by repeating the computation on several sections (or sub-windows) and
//! comparing; the statistical KE model fed with the same surface's σ, R, η (spectral moments) is the
//! large-area limit to compare against. The per-summit distribution summary is reported to show how
//! concentrated the friction capacity is.

use super::adhesion::{
    contacting_adhesion_ratio, lennard_jones_adhesion_ratio, AdhesionBeyondFits,
};
use super::error::{require_positive, FrictionError};
use super::laws::asperity::AsperityLaws;
use super::laws::kogut_etsion::DeformationState;
use super::material::{AdhesionParameters, Material};

/// One identified summit with its interference from the contact solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SummitContact {
    /// Radius of curvature R_i (m), > 0.
    pub radius: f64,
    /// Interference ω_i (m); ≤ 0 means not in contact with gap −ω_i.
    pub interference: f64,
}

/// Forces and state of one summit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SummitFriction {
    /// Normal contact force F_n (N).
    pub normal_force: f64,
    /// Adhesion force F_a (N, attractive positive).
    pub adhesion_force: f64,
    /// Tangential capacity F_f = Q_max (N).
    pub friction_force: f64,
    /// Local μ = F_f/(F_n − F_a), None when F_n − F_a ≤ 0.
    pub local_mu: Option<f64>,
    /// Dimensionless interference x = ω/ω_c.
    pub interference_ratio: f64,
    /// Deformation state.
    pub state: DeformationState,
}

/// Five-number summary and mean of the local μ values that exist.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DistributionSummary {
    /// Number of values.
    pub count: usize,
    /// Minimum.
    pub min: f64,
    /// First quartile (linear interpolation).
    pub lower_quartile: f64,
    /// Median.
    pub median: f64,
    /// Third quartile.
    pub upper_quartile: f64,
    /// Maximum.
    pub max: f64,
    /// Arithmetic mean.
    pub mean: f64,
}

/// Result of the per-summit model for a section.
#[derive(Debug, Clone, PartialEq)]
pub struct PerSummitResult {
    /// Per-summit values, in input order.
    pub summits: Vec<SummitFriction>,
    /// ΣF_n (N).
    pub total_normal_force: f64,
    /// ΣF_a (N).
    pub total_adhesion_force: f64,
    /// ΣF_f (N).
    pub total_friction_force: f64,
    /// Force-weighted μ = ΣF_f / Σ(F_n − F_a); None when Σ(F_n − F_a) ≤ 0.
    pub mu_s: Option<f64>,
    /// Counts of summits by state: [not in contact, elastic, elastic-plastic, fully plastic].
    pub state_counts: [usize; 4],
    /// ΣF_n of the summits beyond the validated range of the friction law (N; x above
    /// [`AsperityLaws::fit_limit`]).
    pub load_beyond_fit: f64,
    /// Summary of the local μ values (None when no summit has F_n − F_a > 0).
    pub local_mu_summary: Option<DistributionSummary>,
}

/// Quantile `q` in [0, 1] of ascending `sorted` values by linear interpolation between order
/// statistics (0 for an empty slice).
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    let n = sorted.len();
    if n == 0 {
        return 0.0;
    }
    let pos = q * (n - 1) as f64;
    let i = pos.floor() as usize;
    let frac = pos - i as f64;
    let lo = sorted.get(i).copied().unwrap_or(0.0);
    let hi = sorted.get(i + 1).copied().unwrap_or(lo);
    lo + frac * (hi - lo)
}

/// Load-weighted quantile `q` in [0, 1] of `(value, load)` pairs: the smallest value μ_k such
/// that the pairs with a value ≤ μ_k carry at least a share `q` of the total load,
/// Σ_{μ_j ≤ μ_k} P_j ≥ q Σ P_j. Pairs with a load that is not finite and > 0 are left out; `None`
/// when none is left. Weighted by load, the quantiles describe the spots that carry the section's
/// load, as μ_s = Σ Q_i / Σ P_i = Σ (P_i/Σ P) μ_i does, instead of the many lightly loaded spots
/// whose μ_i = Q_i/P_i a law with μ → ∞ as P → 0 (full stick, junction shear, KE below first
/// yield) extrapolates without bound.
pub fn load_weighted_quantile(pairs: &[(f64, f64)], q: f64) -> Option<f64> {
    let mut loaded: Vec<(f64, f64)> = pairs
        .iter()
        .copied()
        .filter(|&(v, p)| v.is_finite() && p.is_finite() && p > 0.0)
        .collect();
    loaded.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = loaded.iter().map(|&(_, p)| p).sum();
    let target = q.clamp(0.0, 1.0) * total;
    let mut carried = 0.0;
    for &(value, load) in &loaded {
        carried += load;
        if carried >= target {
            return Some(value);
        }
    }
    loaded.last().map(|&(value, _)| value)
}

/// Summary statistics of `values` (None if empty).
pub fn summarize(values: &[f64]) -> Option<DistributionSummary> {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let (&min, &max) = (sorted.first()?, sorted.last()?);
    Some(DistributionSummary {
        count: sorted.len(),
        min,
        lower_quartile: quantile(&sorted, 0.25),
        median: quantile(&sorted, 0.5),
        upper_quartile: quantile(&sorted, 0.75),
        max,
        mean: sorted.iter().sum::<f64>() / sorted.len() as f64,
    })
}

/// The interference ω (m) of a summit from the contact solution at its grid point: where the
/// contact pressure is positive, ω = u + u_pl, the elastic deformation of both bodies
/// (`deformation`, their sum) plus the plastic penetration, at least 0 (a contacting summit
/// whose ω comes out ≤ 0 touches without interference); elsewhere ω = −max(g, 0) with g the gap
/// after loading (the Lennard-Jones adhesion sees that gap).
pub fn summit_interference(
    pressure: f64,
    deformation: f64,
    plastic_penetration: f64,
    gap: f64,
) -> f64 {
    if pressure > 0.0 {
        (deformation + plastic_penetration).max(0.0)
    } else {
        -gap.max(0.0)
    }
}

/// Per-summit forces of one summit.
pub fn summit_friction(
    summit: &SummitContact,
    laws: &dyn AsperityLaws,
    material: &Material,
    adhesion: &AdhesionParameters,
    beyond: AdhesionBeyondFits,
) -> Result<SummitFriction, FrictionError> {
    // Material and adhesion have public fields: re-validate them (cheap) before use.
    let material = &Material::new(
        material.composite_modulus,
        material.hardness,
        material.poisson_ratio,
    )?;
    let adhesion = &AdhesionParameters::new(adhesion.energy, adhesion.equilibrium_distance)?;
    forces_of(summit, laws, material, adhesion, beyond)
}

/// [`summit_friction`] with validated inputs and the model's laws built once.
fn forces_of(
    summit: &SummitContact,
    laws: &dyn AsperityLaws,
    material: &Material,
    adhesion: &AdhesionParameters,
    beyond: AdhesionBeyondFits,
) -> Result<SummitFriction, FrictionError> {
    let radius = require_positive("summit radius", summit.radius)?;
    if !summit.interference.is_finite() {
        return Err(FrictionError::InvalidParameter {
            name: "summit interference",
            value: summit.interference,
            expected: "a finite interference (m)",
        });
    }
    let critical = material.critical_values(radius);
    let x = summit.interference / critical.interference;
    let adhesion_unit = 2.0 * std::f64::consts::PI * radius * adhesion.energy;
    let (normal, friction) = (laws.load_ratio(x), laws.friction_ratio(x));
    let adhesion_ratio = if x > 0.0 {
        contacting_adhesion_ratio(
            x,
            adhesion.equilibrium_distance / critical.interference,
            beyond,
        )
    } else {
        lennard_jones_adhesion_ratio(1.0 - summit.interference / adhesion.equilibrium_distance)
    };
    let normal_force = normal * critical.load;
    let adhesion_force = adhesion_ratio * adhesion_unit;
    let friction_force = friction * critical.load;
    let net = normal_force - adhesion_force;
    Ok(SummitFriction {
        normal_force,
        adhesion_force,
        friction_force,
        local_mu: (net > 0.0).then(|| friction_force / net),
        interference_ratio: x,
        state: DeformationState::from_interference_ratio(x),
    })
}

/// Per-summit model of a section: per-summit forces, force-weighted μ and the local-μ summary.
pub fn per_summit_friction(
    summits: &[SummitContact],
    laws: &dyn AsperityLaws,
    material: &Material,
    adhesion: &AdhesionParameters,
    beyond: AdhesionBeyondFits,
) -> Result<PerSummitResult, FrictionError> {
    let material = Material::new(
        material.composite_modulus,
        material.hardness,
        material.poisson_ratio,
    )?;
    let adhesion = AdhesionParameters::new(adhesion.energy, adhesion.equilibrium_distance)?;
    let (material, adhesion) = (&material, &adhesion);
    let per: Vec<SummitFriction> = summits
        .iter()
        .map(|s| forces_of(s, laws, material, adhesion, beyond))
        .collect::<Result<_, _>>()?;
    let total_normal_force: f64 = per.iter().map(|s| s.normal_force).sum();
    let total_adhesion_force: f64 = per.iter().map(|s| s.adhesion_force).sum();
    let total_friction_force: f64 = per.iter().map(|s| s.friction_force).sum();
    let fit_limit = laws.fit_limit();
    let load_beyond_fit: f64 = per
        .iter()
        .filter(|s| s.interference_ratio > fit_limit)
        .map(|s| s.normal_force)
        .sum();
    let net = total_normal_force - total_adhesion_force;
    let mut state_counts = [0usize; 4];
    for s in &per {
        let slot = match s.state {
            DeformationState::NotInContact => 0,
            DeformationState::Elastic => 1,
            DeformationState::ElasticPlastic => 2,
            DeformationState::FullyPlastic => 3,
        };
        if let Some(c) = state_counts.get_mut(slot) {
            *c += 1;
        }
    }
    let local: Vec<f64> = per.iter().filter_map(|s| s.local_mu).collect();
    Ok(PerSummitResult {
        total_normal_force,
        total_adhesion_force,
        total_friction_force,
        mu_s: (net > 0.0).then(|| total_friction_force / net),
        state_counts,
        load_beyond_fit,
        local_mu_summary: summarize(&local),
        summits: per,
    })
}

#[cfg(test)]
mod tests {
    use super::load_weighted_quantile;

    /// One spot with 80 % of the load at μ = 1 and two light ones at 2 and 3: by load, the median
    /// and the 10 % quantile are 1 (a count median would be 2), the 90 % one 2; unloaded and
    /// non-finite pairs are left out.
    #[test]
    fn quantiles_are_weighted_by_load() {
        let pairs = [
            (3.0, 1.0),
            (1.0, 8.0),
            (2.0, 1.0),
            (50.0, 0.0),
            (f64::NAN, 1.0),
        ];
        let q = |q| load_weighted_quantile(&pairs, q).unwrap();
        assert_eq!((q(0.1), q(0.5), q(0.8)), (1.0, 1.0, 1.0));
        assert_eq!((q(0.85), q(0.9), q(0.95), q(1.0)), (2.0, 2.0, 3.0, 3.0));
        assert_eq!(load_weighted_quantile(&[(5.0, 0.0)], 0.5), None);
    }
}
