//! The fields of a converged load step from its pressure alone: what a caller that kept only the
//! pressure (and the approach) of a step recomputes, equal to what the solver returned.
//!
//! A converged step satisfies `u = K p` (the solver recomputes the displacement from the
//! pressure before it accepts a step) and `g = g₀ + u − δ`; the deformation of each body is its
//! share of `u` (`c₁/(c₁ + c₂)` and `c₂/(c₁ + c₂)`, Johnson 1985, §13.1) and the plastic
//! penetration is `max(0, −g)` where `p = p_lim`. [`fields_from_pressure`] evaluates these with
//! the influence operator the solver uses (one convolution), so the fields equal the solver's
//! to round-off (bit for bit where both run the same transforms); [`assemble_fields`] is the one
//! place that turns `p`, `g` and `u` into [`ContactFields`], for the solver and for this
//! recomputation alike.

use ndarray::{Array2, ArrayView2};

use super::error::ContactError;
use super::influence::InfluenceOperator;
use super::load_curve::ContactFields;
use super::material::ContactMaterial;
use super::options::FieldRequest;
use super::problem::ContactProblem;

/// The requested fields of a step from its pressure `p` (Pa), gap `g` and composite displacement
/// `u` (m), each `ny × nx` row-major, `shape = (ny, nx)`.
pub(crate) fn assemble_fields(
    shape: (usize, usize),
    (p, g, u): (&[f64], &[f64], &[f64]),
    material: &ContactMaterial,
    request: FieldRequest,
) -> ContactFields {
    let plim = material.flow_pressure();
    let share = material.first_body_share();
    let grid =
        |f: &dyn Fn(usize) -> f64| Array2::from_shape_fn(shape, |(iy, ix)| f(iy * shape.1 + ix));
    ContactFields {
        pressure: request.pressure.then(|| grid(&|i| p[i])),
        gap: request.gap.then(|| grid(&|i| g[i])),
        deformation_first: request.deformation.then(|| grid(&|i| u[i] * share)),
        deformation_second: request.deformation.then(|| grid(&|i| u[i] * (1.0 - share))),
        plastic_penetration: request.plastic_penetration.then(|| {
            grid(&|i| {
                if p[i] >= plim {
                    (-g[i]).max(0.0)
                } else {
                    0.0
                }
            })
        }),
    }
}

/// The requested fields of the converged step of `problem` whose pressure is `pressure` (Pa,
/// `[[iy, ix]]` on the problem's grid) at the rigid-body approach `approach` (m, as the step
/// reported it): `u = K p` by the solver's influence operator, `g = g₀ + u − δ`, then
/// [`assemble_fields`]. One convolution (and the operator's construction, one more). An error
/// when the pressure is not on the problem's grid or a transform fails.
pub fn fields_from_pressure(
    problem: &ContactProblem,
    pressure: ArrayView2<f64>,
    approach: f64,
    request: FieldRequest,
) -> Result<ContactFields, ContactError> {
    let gap = problem.gap();
    let shape = (gap.ny(), gap.nx());
    if pressure.dim() != shape {
        return Err(ContactError::FieldShape {
            expected: shape,
            got: pressure.dim(),
        });
    }
    let mut operator = InfluenceOperator::new(
        gap.nx(),
        gap.ny(),
        gap.dx(),
        gap.dy(),
        problem.material().composite_modulus(),
        problem.boundary(),
        false,
    )?;
    let p: Vec<f64> = pressure.iter().copied().collect();
    let mut u = vec![0.0; p.len()];
    operator.apply(&p, &mut u)?;
    let g: Vec<f64> = gap
        .gap()
        .iter()
        .zip(&u)
        .map(|(&g0, &ui)| g0 + ui - approach)
        .collect();
    Ok(assemble_fields(
        shape,
        (&p, &g, &u),
        problem.material(),
        request,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{Boundary, CompositeGap, ContactSolver, SolverOptions};
    use crate::surface::synthetic::{generate_synthetic_surface, SyntheticSurfaceSpec};

    /// The largest difference between two fields relative to the largest magnitude of the first.
    fn relative_difference(a: &Array2<f64>, b: &Array2<f64>) -> f64 {
        let scale = a.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
        let diff = a
            .iter()
            .zip(b)
            .fold(0.0f64, |m, (&x, &y)| m.max((x - y).abs()));
        if scale > 0.0 {
            diff / scale
        } else {
            diff
        }
    }

    fn rough(seed: u64, n: usize) -> crate::surface::HeightMap {
        generate_synthetic_surface(&SyntheticSurfaceSpec {
            nx: n,
            ny: n,
            lx: n as f64 * 1e-6,
            ly: n as f64 * 1e-6,
            sq: 0.3e-6,
            hurst: 0.8,
            correlation_length: 20e-6,
            short_wavelength_cutoff: None,
            anisotropy: None,
            seed,
        })
        .unwrap()
    }

    /// Every step of a load curve, elastic and capped, periodic and isolated, one body against a
    /// flat and two bodies: the fields recomputed from the pressure equal the solver's within
    /// 1e-12 of each field's largest magnitude.
    #[test]
    fn fields_recomputed_from_the_pressure_equal_the_solvers() {
        let (lower, upper) = (rough(3, 48), rough(4, 48));
        for (boundary, flow_pressure, two_bodies) in [
            (Boundary::Periodic, f64::INFINITY, false),
            (Boundary::Periodic, 2e9, true),
            (Boundary::NonPeriodic, 2e9, false),
            (Boundary::NonPeriodic, f64::INFINITY, true),
        ] {
            let gap = if two_bodies {
                CompositeGap::from_surfaces(&lower, &upper).unwrap()
            } else {
                CompositeGap::against_flat(&lower).unwrap()
            };
            let material = ContactMaterial::against_rigid_flat(110e9, flow_pressure).unwrap();
            let problem = ContactProblem::new(gap, material, boundary);
            let options = SolverOptions {
                tolerance: 1e-10,
                fields: FieldRequest::ALL,
                ..SolverOptions::default()
            };
            let mut solver = ContactSolver::new(problem.clone(), options).unwrap();
            let curve = solver.solve_load_steps(&[2e7, 1e8, 3e8]).unwrap();
            for step in &curve.steps {
                let solved = step.fields.as_ref().unwrap();
                let pressure = solved.pressure.as_ref().unwrap();
                let derived = fields_from_pressure(
                    &problem,
                    pressure.view(),
                    step.approach,
                    FieldRequest::ALL,
                )
                .unwrap();
                for (name, a, b) in [
                    ("gap", &solved.gap, &derived.gap),
                    (
                        "first",
                        &solved.deformation_first,
                        &derived.deformation_first,
                    ),
                    (
                        "second",
                        &solved.deformation_second,
                        &derived.deformation_second,
                    ),
                    (
                        "plastic",
                        &solved.plastic_penetration,
                        &derived.plastic_penetration,
                    ),
                    ("pressure", &solved.pressure, &derived.pressure),
                ] {
                    let d = relative_difference(a.as_ref().unwrap(), b.as_ref().unwrap());
                    assert!(d <= 1e-12, "{boundary:?} {flow_pressure} {name}: {d:e}");
                }
            }
        }
    }

    #[test]
    fn a_pressure_off_the_grid_is_refused() {
        let problem = ContactProblem::new(
            CompositeGap::against_flat(&rough(1, 16)).unwrap(),
            ContactMaterial::against_rigid_flat(1e11, f64::INFINITY).unwrap(),
            Boundary::Periodic,
        );
        let wrong = Array2::<f64>::zeros((16, 15));
        assert!(matches!(
            fields_from_pressure(&problem, wrong.view(), 0.0, FieldRequest::ALL),
            Err(ContactError::FieldShape { .. })
        ));
    }
}
