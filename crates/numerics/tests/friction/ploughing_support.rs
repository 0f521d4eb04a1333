//! The production path of the per-spot deformation part for the tests: the `ploughing` law of
//! the registry, and a rigid–perfectly-plastic contact section of a lower and an upper body run
//! through [`per_spot_friction`], the call a study's node makes.

use asperity_numerics::friction::{
    find_law, per_spot_friction, AdhesionParameters, BodyHardness, BodyMaps, Connectivity,
    ContactBodies, ContactSection, FrictionLaw, LawInputs, Material, SectionFriction,
};
use ndarray::Array2;

pub const DX: f64 = 1.0e-6;
pub const DY: f64 = 1.5e-6;
/// Flow pressure of the rigid–perfectly-plastic soft body (Pa) and interfacial shear strength:
/// the adhesion part of junction shear is then τ/H = 0.2 on every spot.
pub const H: f64 = 3.0e9;
pub const TAU: f64 = 0.2 * H;
pub const HARD: f64 = 8.0e9;

pub fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

/// The `ploughing` law of the registry with `deformation` along ψ (junction shear c = 1 with
/// k = τ, so the adhesion part is τ A).
pub fn ploughing(deformation: &str, psi: f64, penetration_limit: f64) -> Box<dyn FrictionLaw> {
    let law = find_law("ploughing").unwrap();
    let mut parameters = law.default_parameters();
    for (name, value) in [
        (
            "deformation",
            law.parameter("deformation").unwrap().choice(deformation),
        ),
        (
            "sliding_direction",
            law.parameter("sliding_direction").unwrap().number(psi),
        ),
        (
            "penetration_limit",
            law.parameter("penetration_limit")
                .unwrap()
                .number(penetration_limit),
        ),
    ] {
        assert!(parameters.set(name, value.unwrap()));
    }
    let inputs = LawInputs {
        material: Material::new(115e9, H, 0.3).unwrap(),
        yield_strength: H / 2.8,
        shear_strength: TAU,
        parameters,
    };
    (law.build)(&inputs).unwrap()
}

/// A rigid–perfectly-plastic contact of a lower and an upper body: pressure H on `cells`, no
/// elastic deformation, the soft body's flow takes the interpenetration.
pub struct Pair {
    pub lower: Array2<f64>,
    pub upper: Array2<f64>,
    pub cells: Vec<(usize, usize)>,
    pub hardness: BodyHardness,
    pub periodic: bool,
}

impl Pair {
    /// The section on the spacings `DX`, `DY`.
    pub fn friction(&self, law: &dyn FrictionLaw) -> SectionFriction {
        self.friction_on(law, (DX, DY))
    }

    /// The section on `spacing` (dx, dy).
    pub fn friction_on(&self, law: &dyn FrictionLaw, spacing: (f64, f64)) -> SectionFriction {
        let composite = &self.lower + &self.upper;
        let mut pressure = Array2::zeros(composite.dim());
        for &c in &self.cells {
            pressure[c] = H;
        }
        let zero = Array2::zeros(composite.dim());
        let gap = Array2::from_elem(composite.dim(), 1e-6);
        let maps = BodyMaps {
            composite_height: composite.view(),
            upper_height: Some(self.upper.view()),
            deformation_lower: zero.view().into(),
            deformation_upper: Some(zero.view().into()),
            plastic_penetration: zero.view().into(),
        };
        let section = ContactSection {
            pressure: pressure.view(),
            gap: gap.view().into(),
            bodies: ContactBodies::new(maps, self.hardness).unwrap(),
            spacing,
            periodic: self.periodic,
            connectivity: Connectivity::Eight,
            adhesion: AdhesionParameters::new(0.0, 0.158e-9).unwrap(),
        };
        per_spot_friction(&section, law).unwrap()
    }

    /// The same contact seen from the other side: the bodies and their hardness swapped.
    pub fn swapped(&self) -> Self {
        Self {
            lower: self.upper.clone(),
            upper: self.lower.clone(),
            cells: self.cells.clone(),
            hardness: BodyHardness {
                lower: self.hardness.upper,
                upper: self.hardness.lower,
            },
            periodic: self.periodic,
        }
    }
}

/// μ_d and μ_s of a section.
pub fn parts(found: &SectionFriction) -> (f64, f64) {
    let r = &found.result;
    let net = r.total_normal_force - r.adhesion_force;
    (r.total_deformation_force / net, r.mu_s.unwrap())
}
