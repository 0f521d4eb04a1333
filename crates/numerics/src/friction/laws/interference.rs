//! The laws driven by the interference alone (Kogut–Etsion, CEB): one [`FrictionLaw`]
//! implementation for all of them, from their single-asperity fits ([`AsperityLaws`]) and
//! their material. Per contact spot such a law inverts its load law for the interference x_i
//! that carries the spot's load P_i (smallest x with P_c(R_i)·(P/P_c)(x) ≥ P_i; the laws rise
//! monotonically with upward jumps), then Q_i = P_c(R_i)·(Q/P_c)(x_i); the spot is beyond the
//! fit when x_i exceeds [`AsperityLaws::fit_limit`].

use std::sync::Arc;

use super::asperity::AsperityLaws;
use super::law::{FrictionLaw, LawDescriptor};
use super::parameters::ReportedValue;
use super::spot::{SpotFriction, SpotGeometry, SpotLoad};
use crate::friction::material::Material;

/// A law whose single-asperity fits are all it needs: its descriptor, its material and the
/// values it reports beyond the material. Every such law is a [`FrictionLaw`].
pub trait InterferenceLaw: AsperityLaws + 'static {
    /// Its registry entry.
    const DESCRIPTOR: &'static LawDescriptor;

    /// The pair it was built for (E*, H, ν of the softer body).
    fn material(&self) -> &Material;

    /// Its parameters (key and table columns, in order).
    fn parameter_values(&self) -> Vec<ReportedValue>;
}

impl<T: InterferenceLaw> FrictionLaw for T {
    fn descriptor(&self) -> &'static LawDescriptor {
        T::DESCRIPTOR
    }

    fn asperity_laws(self: Arc<Self>) -> Option<Arc<dyn AsperityLaws>> {
        Some(self)
    }

    fn spot_friction(&self, spot: &SpotLoad, _: Option<&SpotGeometry>) -> Option<SpotFriction> {
        interference_spot_friction(self, self.material(), spot)
    }

    fn reported_values(&self) -> Vec<ReportedValue> {
        self.parameter_values()
    }
}

/// Q and x of one spot under an interference-driven law (see the module docs); `None` without
/// a radius.
pub fn interference_spot_friction(
    laws: &dyn AsperityLaws,
    material: &Material,
    spot: &SpotLoad,
) -> Option<SpotFriction> {
    let critical = material.critical_values(spot.radius?).load;
    let x = interference_for_load(laws, spot.load / critical);
    Some(SpotFriction {
        friction_force: critical * laws.friction_ratio(x),
        load_measure: Some(x),
        beyond_fit: x > laws.fit_limit(),
        radius_based: true,
        ..SpotFriction::default()
    })
}

/// The smallest x with (P/P_c)(x) ≥ `load_ratio` (bisection to rounding; the load laws of KE and
/// CEB rise monotonically with upward jumps).
pub fn interference_for_load(laws: &dyn AsperityLaws, load_ratio: f64) -> f64 {
    if load_ratio <= 0.0 {
        return 0.0;
    }
    let mut hi = 1.0;
    while laws.load_ratio(hi) < load_ratio && hi < 1e300 {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if laws.load_ratio(mid) >= load_ratio {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}
