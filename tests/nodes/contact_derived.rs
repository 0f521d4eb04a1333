//! The contact's maps derived from its pressure maps (what its cache entry keeps) equal the
//! solver's: the final step's displacement, as the engine derives it for a consumer of a cached
//! contact, and every step's maps read point by point (the final step's from
//! `ContactView::of`, an earlier step's from `ContactTask::step_pressure`) equal those of the
//! contact stopped at that step.

use asperity::contact::PointMap;
use asperity::engine::artifact::Artifact;
use asperity::engine::plan::Plan;
use asperity::nodes::{ContactTask, ContactView, StepPressure};
use ndarray::{Array2, ArrayD, ArrayView2, Ix2};

use crate::nodes_common::{compute_all, study};

/// Two rough bodies of different materials (both deform, differently), an elastic–plastic
/// contact solved over three load steps, and the same contact stopped after each earlier step.
fn text(periodic: bool) -> String {
    let contact = |name: &str, pressures: &str| {
        [
            format!("  {name}:"),
            String::from("    contact:"),
            String::from("      lower: a"),
            String::from("      upper: b"),
            String::from("      lower_material: s235jr"),
            String::from(
                "      upper_material: {youngs_modulus: 110 GPa, poisson_ratio: 0.34, hardness: 1 GPa}",
            ),
            format!("      nominal_pressures: [{pressures}]"),
            format!("      periodic: {periodic}"),
            String::from("      fields: true\n"),
        ]
        .join("\n")
    };
    format!(
        r#"
study: derived
nodes:
  a:
    surface:
      synthetic: {{grid: [96, 80], size: [0.3 mm, 0.25 mm], sq: 1 um, hurst: 0.8,
                  correlation_length: 40 um, seed: 1}}
  b:
    surface:
      synthetic: {{grid: [96, 80], size: [0.3 mm, 0.25 mm], sq: 0.7 um, hurst: 0.7,
                  correlation_length: 30 um, seed: 2}}
{}{}{}"#,
        contact("c1", "5 MPa"),
        contact("c2", "5 MPa, 20 MPa"),
        contact("c3", "5 MPa, 20 MPa, 60 MPa")
    )
}

/// The largest difference of two maps relative to the largest magnitude of the first.
fn relative_difference(a: ArrayView2<f64>, b: ArrayView2<f64>) -> f64 {
    assert_eq!(a.dim(), b.dim());
    let scale = a.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
    let diff = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |m, (&x, &y)| m.max((x - y).abs()));
    if scale > 0.0 {
        diff / scale
    } else {
        diff
    }
}

/// A map read point by point, as an array.
fn grid(map: &PointMap) -> Array2<f64> {
    Array2::from_shape_fn(map.dim(), |at| map.at(at))
}

fn map(a: &ArrayD<f64>) -> ArrayView2<'_, f64> {
    a.view().into_dimensionality::<Ix2>().unwrap()
}

#[test]
fn derived_maps_equal_the_solvers_at_every_step() {
    for periodic in [true, false] {
        let study = study(&text(periodic));
        let plan = Plan::build(&study).unwrap();
        let artifacts = compute_all(&plan);
        let index = |name: &str| plan.nodes.iter().position(|n| n.names[0] == name).unwrap();
        let c3 = &plan.nodes[index("c3")];
        let surfaces = [&artifacts["a"], &artifacts["b"]];
        let full = &artifacts["c3"];

        // The final step: what the cache keeps, completed by the kind's derivation.
        let storage = c3.task.array_storage();
        let mut lean = Artifact {
            arrays: (full.arrays.iter())
                .filter(|(name, _)| storage.stores(name))
                .map(|(n, a)| (n.clone(), a.clone()))
                .collect(),
            ..full.clone()
        };
        let kept: Vec<&String> = lean.arrays.keys().collect();
        assert_eq!(
            kept,
            ["pressure", "pressure_step_0", "pressure_step_1"],
            "periodic {periodic}"
        );
        c3.task.derive_arrays(&surfaces, &mut lean).unwrap();
        assert_eq!(
            lean.arrays.keys().collect::<Vec<_>>(),
            full.arrays.keys().collect::<Vec<_>>()
        );
        assert_eq!(
            full.arrays.keys().collect::<Vec<_>>(),
            [
                "composite_height",
                "displacement",
                "height_upper",
                "pressure",
                "pressure_step_0",
                "pressure_step_1",
                "step_displacements"
            ]
        );
        for (name, array) in &full.arrays {
            if name.starts_with("pressure_step_") {
                continue;
            }
            if name == "step_displacements" {
                // Convolved from the same stored pressures by the same operator.
                assert_eq!(array, &lean.arrays[name], "periodic {periodic}");
                continue;
            }
            let d = relative_difference(map(array), map(&lean.arrays[name]));
            assert!(d <= 1e-12, "periodic {periodic}, final {name}: {d:e}");
        }

        // Every step: the maps of `c3` at step i against those of the contact stopped there
        // (the same warm-started steps, so the same solution; its maps from the solver's own
        // displacement); the earlier steps' from their pressure and the displacement convolved
        // for them, the final step's from the contact's own.
        let task = c3.task.as_any().downcast_ref::<ContactTask>().unwrap();
        let mut previous = None;
        for (step, stopped) in ["c1", "c2", "c3"].into_iter().enumerate() {
            let earlier: Option<StepPressure> =
                (step < 2).then(|| task.step_pressure(&lean, step, previous.take()).unwrap());
            let view = match &earlier {
                Some(pressure) => pressure.view(&lean).unwrap(),
                None => ContactView::of(&lean, task.material()).unwrap(),
            };
            let solved = &artifacts[stopped];
            let own = ContactView::of(solved, task.material()).unwrap();
            for (name, derived, reference) in [
                ("gap", view.gap, own.gap),
                (
                    "deformation_lower",
                    view.deformation_lower,
                    own.deformation_lower,
                ),
                (
                    "deformation_upper",
                    view.deformation_upper.unwrap(),
                    own.deformation_upper.unwrap(),
                ),
                (
                    "plastic_penetration",
                    view.plastic_penetration,
                    own.plastic_penetration,
                ),
            ] {
                let d = relative_difference(grid(&reference).view(), grid(&derived).view());
                assert!(d <= 1e-12, "periodic {periodic}, step {step} {name}: {d:e}");
            }
            let d = relative_difference(map(&solved.arrays["pressure"]), view.pressure);
            assert!(
                d <= 1e-12,
                "periodic {periodic}, step {step} pressure: {d:e}"
            );
            assert_eq!(view.composite_height, map(&full.arrays["composite_height"]));
            previous = earlier;
        }
        assert!(task.step_pressure(&lean, 2, None).is_err());
        assert!(task.step_pressure(&lean, 3, None).is_err());
    }
}
