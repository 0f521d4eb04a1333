//! Per-spot friction on solved contacts of two elastic–plastic bodies with built-in materials,
//! through the production path (the contact solver, then `per_spot_friction`): swapping the
//! bodies and reversing the sliding direction gives the same μ_s for every law, and the harder
//! body ploughs — a hard rough body on a soft flat has a deformation part, a soft rough body on a
//! hard flat (nearly) none.

use crate::ploughing_support::rel;
use asperity_numerics::contact::{
    Boundary, CompositeGap, ContactMaterial, ContactProblem, ContactSolver, FieldRequest,
    SolverOptions,
};
use asperity_numerics::friction::{
    find_law, per_spot_friction_with_baseline, AdhesionParameters, BodyHardness, BodyMaps,
    Connectivity, ContactBodies, ContactSection, FrictionLaw, LawInputs, Material, SectionFriction,
};
use asperity_numerics::materials::{find_material, BodyMaterial, MaterialPair};
use asperity_numerics::surface::synthetic::{generate_synthetic_surface, SyntheticSurfaceSpec};
use asperity_numerics::surface::HeightMap;
use ndarray::Array2;
use std::f64::consts::PI;

const N: usize = 64;
const SIDE: f64 = 64e-6;

fn rough(seed: u64, sq: f64) -> Array2<f64> {
    generate_synthetic_surface(&SyntheticSurfaceSpec {
        nx: N,
        ny: N,
        lx: SIDE,
        ly: SIDE,
        sq,
        hurst: 0.8,
        correlation_length: SIDE / 4.0,
        short_wavelength_cutoff: None,
        anisotropy: None,
        seed,
    })
    .unwrap()
    .into_heights()
}

fn body(name: &str) -> BodyMaterial {
    BodyMaterial::new(find_material(name).unwrap().constants).unwrap()
}

/// A solved contact of `lower` against `upper` at 20 MPa with every field.
struct Solved {
    lower: Array2<f64>,
    upper: Array2<f64>,
    pair: MaterialPair,
    pressure: Array2<f64>,
    gap: Array2<f64>,
    deformation: (Array2<f64>, Array2<f64>),
    plastic: Array2<f64>,
}

impl Solved {
    fn new(lower: Array2<f64>, upper: Array2<f64>, materials: (&str, &str)) -> Self {
        let d = SIDE / N as f64;
        let pair = MaterialPair::new(body(materials.0), Some(body(materials.1)));
        let gap = CompositeGap::from_surfaces(
            &HeightMap::new(lower.clone(), d, d).unwrap(),
            &HeightMap::new(upper.clone(), d, d).unwrap(),
        )
        .unwrap();
        let problem = ContactProblem::new(gap, ContactMaterial::new(pair), Boundary::Periodic);
        let options = SolverOptions {
            tolerance: 1e-10,
            ..SolverOptions::default()
        };
        let mut solver = ContactSolver::new(problem, options).unwrap();
        solver.solve_load_steps(&[20e6]).unwrap();
        let f = solver.last_fields(FieldRequest::ALL).unwrap();
        Self {
            lower,
            upper,
            pair,
            pressure: f.pressure.unwrap(),
            gap: f.gap.unwrap(),
            deformation: (f.deformation_first.unwrap(), f.deformation_second.unwrap()),
            plastic: f.plastic_penetration.unwrap(),
        }
    }

    /// The friction material and strengths of the pair, as a study's node derives them.
    fn inputs(&self, law: &str) -> LawInputs {
        let (_, softer) = self.pair.softer();
        LawInputs {
            material: Material::from_pair(&self.pair).unwrap(),
            yield_strength: softer.yield_strength().unwrap(),
            shear_strength: softer.shear_strength().unwrap(),
            parameters: find_law(law).unwrap().default_parameters(),
        }
    }

    fn friction(&self, law: &dyn FrictionLaw) -> SectionFriction {
        self.friction_with_baseline(law, None)
    }

    /// [`per_spot_friction_with_baseline`] of this contact: the slope baseline `known`, or
    /// computed.
    fn friction_with_baseline(&self, law: &dyn FrictionLaw, known: Option<f64>) -> SectionFriction {
        let d = SIDE / N as f64;
        let composite = &self.lower + &self.upper;
        let maps = BodyMaps {
            composite_height: composite.view(),
            upper_height: Some(self.upper.view()),
            deformation_lower: self.deformation.0.view().into(),
            deformation_upper: Some(self.deformation.1.view().into()),
            plastic_penetration: self.plastic.view().into(),
        };
        let section = ContactSection {
            pressure: self.pressure.view(),
            gap: self.gap.view().into(),
            bodies: ContactBodies::new(maps, BodyHardness::of(&self.pair)).unwrap(),
            spacing: (d, d),
            periodic: true,
            connectivity: Connectivity::Four,
            adhesion: AdhesionParameters::new(0.5, 0.158e-9).unwrap(),
        };
        per_spot_friction_with_baseline(&section, law, known).unwrap()
    }
}

/// The `ploughing` law of the pair's softer body (τ_s = k of the softer body, c = 1).
fn pair_ploughing(solved: &Solved, deformation: &str, psi: f64) -> Box<dyn FrictionLaw> {
    let law = find_law("ploughing").unwrap();
    let mut inputs = solved.inputs("ploughing");
    let set = [
        (
            "deformation",
            law.parameter("deformation").unwrap().choice(deformation),
        ),
        (
            "sliding_direction",
            law.parameter("sliding_direction").unwrap().number(psi),
        ),
    ];
    for (name, value) in set {
        assert!(inputs.parameters.set(name, value.unwrap()));
    }
    (law.build)(&inputs).unwrap()
}

fn mu_s(found: &SectionFriction) -> f64 {
    found.result.mu_s.unwrap()
}

#[test]
fn swapping_the_bodies_and_reversing_the_direction_gives_the_same_mu() {
    let (a, b) = (rough(11, 0.4e-6), rough(12, 0.3e-6));
    for materials in [("s235jr", "s235jr"), ("aisi52100", "al6061-t6")] {
        let one = Solved::new(a.clone(), b.clone(), materials);
        let other = Solved::new(b.clone(), a.clone(), (materials.1, materials.0));
        for deformation in ["groove", "cone", "sphere"] {
            for psi in [0.0, 1.0, 2.5] {
                let m1 = mu_s(&one.friction(pair_ploughing(&one, deformation, psi).as_ref()));
                let m2 =
                    mu_s(&other.friction(pair_ploughing(&other, deformation, psi + PI).as_ref()));
                assert!(
                    rel(m2, m1) < 1e-6,
                    "{materials:?} {deformation} ψ = {psi}: {m1} vs {m2}"
                );
            }
        }
        // The laws without a direction: the same μ_s whichever body is called lower.
        for law in [
            "kogut_etsion",
            "chang_etsion_bogy",
            "full_stick",
            "junction_shear",
        ] {
            let build = |s: &Solved| (find_law(law).unwrap().build)(&s.inputs(law)).unwrap();
            let (m1, m2) = (
                mu_s(&one.friction(build(&one).as_ref())),
                mu_s(&other.friction(build(&other).as_ref())),
            );
            // KE carries nothing beyond x = 6: 0 on both sides.
            assert!(
                (m2 - m1).abs() <= 1e-6 * m1.abs(),
                "{materials:?} {law}: {m1} vs {m2}"
            );
        }
    }
}

#[test]
fn the_harder_body_ploughs_the_softer() {
    let (rough_body, flat) = (rough(21, 0.4e-6), Array2::zeros((N, N)));
    let deformation = |solved: &Solved| {
        let found = solved.friction(pair_ploughing(solved, "groove", 0.0).as_ref());
        let r = &found.result;
        let ploughing = found.geometry.as_ref().unwrap().ploughing.name();
        (
            r.total_deformation_force / (r.total_normal_force - r.adhesion_force),
            ploughing,
        )
    };
    // A hard rough bearing steel on a soft aluminium flat: the rough body ploughs.
    let hard_rough = Solved::new(rough_body.clone(), flat.clone(), ("aisi52100", "al6061-t6"));
    let (ploughs, by) = deformation(&hard_rough);
    assert_eq!(by, "lower");
    assert!(ploughs > 0.01, "{ploughs}");
    // A soft rough aluminium on a hard bearing-steel flat: the flat ploughs, and it is flat up to
    // its elastic dents.
    let soft_rough = Solved::new(rough_body, flat, ("al6061-t6", "aisi52100"));
    let (flat_ploughs, by) = deformation(&soft_rough);
    assert_eq!(by, "upper");
    assert!(flat_ploughs < 0.02 * ploughs, "{flat_ploughs} vs {ploughs}");
}

/// A slope baseline given from an earlier load step is taken as it is, and nothing else of the
/// section depends on it: given the value `per_spot_friction` computes, the result is the same.
#[test]
fn a_known_slope_baseline_is_taken_and_changes_nothing_else() {
    let solved = Solved::new(rough(31, 0.4e-6), rough(32, 0.3e-6), ("s235jr", "s235jr"));
    let law = pair_ploughing(&solved, "groove", 1.0);
    let computed = solved.friction(law.as_ref());
    let baseline = computed.geometry.as_ref().unwrap().slope_baseline;
    assert!(baseline > 0.0);
    assert_eq!(
        solved.friction_with_baseline(law.as_ref(), Some(baseline)),
        computed
    );
    let other = solved.friction_with_baseline(law.as_ref(), Some(0.25));
    assert_eq!(other.geometry.as_ref().unwrap().slope_baseline, 0.25);
    assert_eq!(
        (&other.spots, &other.result),
        (&computed.spots, &computed.result)
    );
    assert_eq!(
        other.geometry.as_ref().unwrap().spots,
        computed.geometry.as_ref().unwrap().spots
    );
}
