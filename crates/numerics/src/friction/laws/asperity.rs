//! Single-asperity laws as ratios to the Kogut–Etsion critical values of the asperity
//! (x = ω/ω_c, P/P_c, A/A_c, Q_max/P_c with ω_c = (πKH/(2E'))² R, P_c = (2/3)πKHRω_c,
//! A_c = πRω_c; [`crate::friction::material`]), so the statistical integrals, the per-summit
//! model and the per-spot inversion treat every interference-driven law alike. The laws
//! themselves live beside their descriptors: [`super::kogut_etsion`], [`super::chang_etsion_bogy`],
//! [`super::full_stick`].

use std::fmt;

/// x = 1: the first-yield interference, end of the elastic (Hertz) range of every law.
pub const ELASTIC_LIMIT: f64 = 1.0;

/// The largest μ_s of a yield-inception law (KE 2004, CEB) reported as `ok`: the tangential
/// capacity of an asperity at first yield is 0.52 P_c against its load P_c (KE 2004 at x = 1),
/// and beyond first yield it falls; a section above 1 carries its load on barely touching
/// asperities (x ≪ 1, where Q/P = 0.52 x^−0.518 grows without bound), outside what the fits
/// describe.
pub const YIELD_INCEPTION_MU_S_MAX: f64 = 1.0;

/// Single-asperity laws as ratios to the Kogut–Etsion critical values (see the module docs).
pub trait AsperityLaws: fmt::Debug + Send + Sync {
    /// P/P_c at x (0 for x ≤ 0).
    fn load_ratio(&self, x: f64) -> f64;

    /// A/A_c at x (0 for x ≤ 0).
    fn area_ratio(&self, x: f64) -> f64;

    /// Q_max/P_c at x (0 for x ≤ 0).
    fn friction_ratio(&self, x: f64) -> f64;

    /// Breaks in x of the load and area laws (smooth between them).
    fn load_breaks(&self) -> Vec<f64>;

    /// Breaks in x of the friction law below [`AsperityLaws::friction_support`].
    fn friction_breaks(&self) -> Vec<f64>;

    /// The x beyond which Q_max/P_c is zero (+∞ when it never is).
    fn friction_support(&self) -> f64;

    /// The x beyond which the friction law is outside its validated range.
    fn fit_limit(&self) -> f64;

    /// κ ∈ (0, 1] with P/P_c(x′) ≤ P/P_c(x)/κ for every x′ ≤ x: the load laws increase between
    /// their breaks, so κ is the product of the drops at the breaks (1 when the law never drops).
    fn load_drop_bound(&self) -> f64 {
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
}
