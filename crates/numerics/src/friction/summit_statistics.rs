//! Summit statistics of an isotropic Gaussian surface from its profile spectral moments
//! (Nayak, J. Lubr. Technol. 93 (1971) 398; McCool, Wear 107 (1986) 37).
//!
//! With profile moments m0 = ⟨z²⟩, m2 = ⟨(dz/dx)²⟩, m4 = ⟨(d²z/dx²)²⟩ and α = m0 m4 / m2²:
//!
//! ```text
//! η = m4 / (6π√3 m2)      R = (3/8) √(π/m4)      σ = √m0
//! σ_s² = (1 − 0.8968/α) m0      y_s = 4 √(m0/(π α))
//! ```
//!
//! and, with β = η R σ, α = 768 π β², σ_s/σ = √(1 − 3.717e-4/β²), y_s/σ = 0.045944/β. These are
//! valid for α > 0.8968 (β > 0.01928); at or below the bound a typed error is returned.
//!
//! Two rough surfaces in contact are replaced by their sum: moments add, m_k = m_k(1) + m_k(2), so
//! σ² = σ1² + σ2² and R⁻² = R1⁻² + R2⁻². The moments must come from the same band-limited data
//! (same sampling interval and the same S-/L-filter): m2 and especially m4 grow as the sampling
//! gets finer, so η, R and β depend on the measurement resolution and filter, not only on the
//! surface; state them with every result.

use super::error::{require_positive, FrictionError};

/// McCool's lower bound on Nayak's α for which the summit-height variance is positive.
pub const MCCOOL_ALPHA_BOUND: f64 = 0.8968;

/// Profile spectral moments of an isotropic surface (SI: m0 in m², m2 dimensionless, m4 in m⁻²).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralMoments {
    /// m0 = ⟨z²⟩ (m²).
    pub m0: f64,
    /// m2 = ⟨(dz/dx)²⟩ (dimensionless).
    pub m2: f64,
    /// m4 = ⟨(d²z/dx²)²⟩ (m⁻²).
    pub m4: f64,
}

impl SpectralMoments {
    /// Validated moments (each finite and > 0).
    pub fn new(m0: f64, m2: f64, m4: f64) -> Result<Self, FrictionError> {
        Ok(Self {
            m0: require_positive("m0", m0)?,
            m2: require_positive("m2", m2)?,
            m4: require_positive("m4", m4)?,
        })
    }

    /// Moments of the equivalent (sum) surface of two independent rough surfaces: m_k = m_k(1) + m_k(2).
    pub fn combined_with(&self, other: &SpectralMoments) -> SpectralMoments {
        SpectralMoments {
            m0: self.m0 + other.m0,
            m2: self.m2 + other.m2,
            m4: self.m4 + other.m4,
        }
    }

    /// Nayak's bandwidth parameter α = m0 m4 / m2².
    pub fn bandwidth_alpha(&self) -> f64 {
        self.m0 * self.m4 / (self.m2 * self.m2)
    }
}

/// Greenwood–Williamson summit statistics of the equivalent rough surface (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SummitStatistics {
    /// Std of surface heights σ (m).
    pub sigma: f64,
    /// Std of summit heights σ_s (m).
    pub sigma_s: f64,
    /// Offset y_s from the mean plane of heights to the mean plane of summits (m).
    pub y_s: f64,
    /// Mean summit radius of curvature R (m).
    pub radius: f64,
    /// Summit areal density η (m⁻²).
    pub density: f64,
    /// Roughness parameter β = η R σ (dimensionless).
    pub beta: f64,
    /// Nayak's bandwidth parameter α = 768 π β² (dimensionless).
    pub alpha: f64,
}

impl SummitStatistics {
    /// Summit statistics from profile spectral moments (Nayak 1971, McCool 1986; formulas in the
    /// module docs). Errors if a moment is not positive or α ≤ 0.8968.
    pub fn from_moments(m0: f64, m2: f64, m4: f64) -> Result<Self, FrictionError> {
        Self::from_spectral_moments(&SpectralMoments::new(m0, m2, m4)?)
    }

    /// As [`SummitStatistics::from_moments`], from a [`SpectralMoments`] value (e.g. a combined one).
    pub fn from_spectral_moments(m: &SpectralMoments) -> Result<Self, FrictionError> {
        let m = SpectralMoments::new(m.m0, m.m2, m.m4)?;
        let alpha = m.bandwidth_alpha();
        let density = m.m4 / (6.0 * std::f64::consts::PI * 3f64.sqrt() * m.m2);
        let radius = 0.375 * (std::f64::consts::PI / m.m4).sqrt();
        let sigma = m.m0.sqrt();
        let beta = density * radius * sigma;
        if alpha.is_nan() || alpha <= MCCOOL_ALPHA_BOUND {
            return Err(FrictionError::BandwidthBelowMcCoolBound { alpha, beta });
        }
        let sigma_s = ((1.0 - MCCOOL_ALPHA_BOUND / alpha) * m.m0).sqrt();
        let y_s = 4.0 * (m.m0 / (std::f64::consts::PI * alpha)).sqrt();
        Ok(Self {
            sigma,
            sigma_s,
            y_s,
            radius,
            density,
            beta,
            alpha,
        })
    }

    /// Summit statistics from explicit σ (m), R (m) and η (m⁻²).
    ///
    /// σ_s and y_s are NOT taken equal to σ and 0 (the classic GW simplification): they follow
    /// from β = η R σ through McCool's identities α = 768πβ², σ_s = σ √(1 − 0.8968/α),
    /// y_s = 4σ/√(πα) — exactly what [`SummitStatistics::from_moments`] gives for the same β, so
    /// both constructors describe the same isotropic Gaussian surface. Errors if β ≤ 0.01928.
    pub fn from_explicit(sigma: f64, radius: f64, density: f64) -> Result<Self, FrictionError> {
        let sigma = require_positive("sigma", sigma)?;
        let radius = require_positive("radius", radius)?;
        let density = require_positive("density", density)?;
        let beta = density * radius * sigma;
        let alpha = 768.0 * std::f64::consts::PI * beta * beta;
        if alpha.is_nan() || alpha <= MCCOOL_ALPHA_BOUND {
            return Err(FrictionError::BandwidthBelowMcCoolBound { alpha, beta });
        }
        let sigma_s = sigma * (1.0 - MCCOOL_ALPHA_BOUND / alpha).sqrt();
        let y_s = 4.0 * sigma / (std::f64::consts::PI * alpha).sqrt();
        Ok(Self {
            sigma,
            sigma_s,
            y_s,
            radius,
            density,
            beta,
            alpha,
        })
    }

    /// Re-check a value built field by field: the explicit constructor must reproduce its σ_s,
    /// y_s and α from σ, R, η (relative 1e-9), so hand-made inconsistent values are rejected.
    pub fn validated(&self) -> Result<Self, FrictionError> {
        let check = Self::from_explicit(self.sigma, self.radius, self.density)?;
        let consistent = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
        if consistent(self.sigma_s, check.sigma_s)
            && consistent(self.y_s, check.y_s)
            && consistent(self.alpha, check.alpha)
            && consistent(self.beta, check.beta)
        {
            Ok(*self)
        } else {
            Err(FrictionError::InvalidParameter {
                name: "summit statistics",
                value: self.sigma_s,
                expected:
                    "sigma_s, y_s, beta, alpha consistent with sigma, R, eta (use the constructors)",
            })
        }
    }

    /// Ratio σ_s/σ: the standard deviation of the summit-height pdf in σ units.
    pub fn summit_std_ratio(&self) -> f64 {
        self.sigma_s / self.sigma
    }
}
