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
//!
//! A caller deriving several steps of one contact splits the work: the convolution `u = K p` of
//! each step by one [`DisplacementOperator`] (built once: its kernel and plans serve every
//! step), and the fields from `u` by [`fields_from_displacement`], into arrays reused from one
//! step to the next. The result is [`fields_from_pressure`]'s, bit for bit.

use ndarray::{Array2, ArrayView2, CowArray, Ix2};
use rayon::prelude::*;

use super::error::ContactError;
use super::influence::{Boundary, InfluenceOperator};
use super::load_curve::ContactFields;
use super::material::ContactMaterial;
use super::options::FieldRequest;
use super::point_fields::{deformation, gap, plastic, PointFields};
use super::problem::ContactProblem;

/// Points per parallel chunk of the field passes (each value is computed alone, so the fields do
/// not depend on the thread count).
const CHUNK: usize = 1 << 14;

/// The requested fields of a step from its pressure `p` (Pa), gap `g` and composite displacement
/// `u` (m), each `ny × nx` row-major, `shape = (ny, nx)`.
pub(crate) fn assemble_fields(
    shape: (usize, usize),
    (p, g, u): (&[f64], &[f64], &[f64]),
    material: &ContactMaterial,
    request: FieldRequest,
) -> ContactFields {
    let mut fields = ContactFields::default();
    write_fields(&mut fields, shape, (p, |i| g[i], u), material, request);
    fields
}

/// The pressure `p` (Pa), gap `g` and composite displacement `u` (m) of a converged step, each
/// `ny × nx` row-major, owned: what a consumed solver leaves ([`super::ContactSolver::
/// into_last_solution`]). Its fields ([`Self::into_fields`]) are [`assemble_fields`]'s, bit for
/// bit, in the arrays of `p`, `g` and `u` themselves: only the plastic penetration and the
/// second body's deformation are new arrays.
#[derive(Debug)]
pub struct StepSolution {
    shape: (usize, usize),
    p: Vec<f64>,
    g: Vec<f64>,
    u: Vec<f64>,
    material: ContactMaterial,
}

impl StepSolution {
    /// The solution `[p, g, u]` on the grid `shape = (ny, nx)` of a contact of `material`.
    pub(crate) fn new(
        shape: (usize, usize),
        [p, g, u]: [Vec<f64>; 3],
        material: ContactMaterial,
    ) -> Self {
        Self {
            shape,
            p,
            g,
            u,
            material,
        }
    }

    /// The grid, `(ny, nx)`.
    pub fn shape(&self) -> (usize, usize) {
        self.shape
    }

    /// The pressure `p` (Pa) and the composite displacement `u = K p` (m) in their own arrays,
    /// the gap released: every other field follows from them point by point
    /// ([`super::PointFields`]).
    pub fn into_pressure_and_displacement(self) -> (Array2<f64>, Array2<f64>) {
        let grid = |values: Vec<f64>| {
            Array2::from_shape_vec(self.shape, values)
                .unwrap_or_else(|_| unreachable!("ny · nx values of the solver"))
        };
        (grid(self.p), grid(self.u))
    }

    /// The requested fields, the pressure, gap and first body's deformation in the arrays of
    /// `p`, `g` and `u` (the deformation `u · c₁/(c₁ + c₂)` scaled in place).
    pub fn into_fields(self, request: FieldRequest) -> ContactFields {
        let Self {
            shape,
            p,
            g,
            mut u,
            material,
        } = self;
        let plim = material.flow_pressure();
        let share = material.first_body_share();
        let grid = |values: Vec<f64>| {
            Array2::from_shape_vec(shape, values)
                .unwrap_or_else(|_| unreachable!("ny · nx values of the solver"))
        };
        let plastic_penetration = request
            .plastic_penetration
            .then(|| new_grid(shape, |i| plastic(p[i], g[i], plim)));
        let deformation_second = request
            .deformation
            .then(|| new_grid(shape, |i| deformation(u[i], 1.0 - share)));
        let deformation_first = request.deformation.then(|| {
            u.par_iter_mut().for_each(|v| *v = deformation(*v, share));
            grid(u)
        });
        ContactFields {
            pressure: request.pressure.then(|| grid(p)),
            gap: request.gap.then(|| grid(g)),
            deformation_first,
            deformation_second,
            plastic_penetration,
        }
    }
}

/// The requested fields of [`assemble_fields`] written into `fields` from `p`, the gap `g(i)` at
/// the flat index `i = iy·nx + ix` and `u`: an array of the grid's shape is overwritten in place,
/// any other one replaced; a field not requested is `None`.
fn write_fields(
    fields: &mut ContactFields,
    shape: (usize, usize),
    (p, g, u): (&[f64], impl Fn(usize) -> f64 + Sync + Copy, &[f64]),
    material: &ContactMaterial,
    request: FieldRequest,
) {
    let plim = material.flow_pressure();
    let share = material.first_body_share();
    fill(&mut fields.pressure, request.pressure, shape, |i| p[i]);
    fill(&mut fields.gap, request.gap, shape, g);
    fill(
        &mut fields.deformation_first,
        request.deformation,
        shape,
        |i| deformation(u[i], share),
    );
    fill(
        &mut fields.deformation_second,
        request.deformation,
        shape,
        |i| deformation(u[i], 1.0 - share),
    );
    fill(
        &mut fields.plastic_penetration,
        request.plastic_penetration,
        shape,
        |i| plastic(p[i], g(i), plim),
    );
}

/// `slot` set to the `shape` grid of `f` at every flat index `iy·nx + ix` (its own array
/// overwritten when it has that shape), or to `None` when not `wanted`.
fn fill(
    slot: &mut Option<Array2<f64>>,
    wanted: bool,
    shape: (usize, usize),
    f: impl Fn(usize) -> f64 + Sync,
) {
    if !wanted {
        *slot = None;
        return;
    }
    if let Some(values) = slot
        .as_mut()
        .filter(|a| a.dim() == shape)
        .and_then(|a| a.as_slice_mut())
    {
        values
            .par_chunks_mut(CHUNK)
            .enumerate()
            .for_each(|(c, chunk)| {
                let base = c * CHUNK;
                for (k, v) in chunk.iter_mut().enumerate() {
                    *v = f(base + k);
                }
            });
        return;
    }
    *slot = Some(new_grid(shape, f));
}

/// A new `shape` grid of `f` at every flat index, each value written once (no zeroing pass).
fn new_grid(shape: (usize, usize), f: impl Fn(usize) -> f64 + Sync) -> Array2<f64> {
    let mut values = Vec::new();
    (0..shape.0 * shape.1)
        .into_par_iter()
        .with_min_len(CHUNK)
        .map(&f)
        .collect_into_vec(&mut values);
    Array2::from_shape_vec(shape, values).unwrap_or_else(|_| unreachable!("ny · nx values"))
}

/// `u = K p` on one grid by the solver's influence operator in double precision, built once (its
/// kernel, plans and buffers) for the pressures of any number of load steps: a convolution keeps
/// nothing of the one before, so each result equals that of a newly built operator, bit for bit.
#[derive(Debug)]
pub struct DisplacementOperator {
    operator: InfluenceOperator,
    /// `(ny, nx)`.
    shape: (usize, usize),
}

impl DisplacementOperator {
    /// The operator of a `shape = (ny, nx)` grid of spacing `(dx, dy)` (m), the composite modulus
    /// of `material` and `boundary`, as the solver builds it.
    pub fn new(
        shape: (usize, usize),
        (dx, dy): (f64, f64),
        material: &ContactMaterial,
        boundary: Boundary,
    ) -> Result<Self, ContactError> {
        let (ny, nx) = shape;
        let operator = InfluenceOperator::double_only(
            nx,
            ny,
            dx,
            dy,
            material.composite_modulus(),
            boundary,
            false,
        )?;
        Ok(Self { operator, shape })
    }

    /// The operator of `problem`'s grid, material and boundary.
    pub fn of_problem(problem: &ContactProblem) -> Result<Self, ContactError> {
        let gap = problem.gap();
        Self::new(
            (gap.ny(), gap.nx()),
            (gap.dx(), gap.dy()),
            problem.material(),
            problem.boundary(),
        )
    }

    /// `displacement = K pressure`: the composite displacement (m, `ny · nx` values row-major) of
    /// `pressure` (Pa, `[[iy, ix]]`). An error when either is not on the operator's grid or a
    /// transform fails.
    pub fn apply(
        &mut self,
        pressure: ArrayView2<f64>,
        displacement: &mut [f64],
    ) -> Result<(), ContactError> {
        let shape = self.shape;
        if pressure.dim() != shape || displacement.len() != shape.0 * shape.1 {
            return Err(ContactError::FieldShape {
                expected: shape,
                got: pressure.dim(),
            });
        }
        let p = pressure.as_standard_layout();
        self.operator.apply(values(&p), displacement)?;
        Ok(())
    }
}

/// The values of a standard-layout array, row-major.
fn values<'a>(a: &'a CowArray<'_, f64, Ix2>) -> &'a [f64] {
    a.as_slice()
        .unwrap_or_else(|| unreachable!("a standard-layout array is one slice"))
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
    let p = pressure.as_standard_layout().into_owned();
    let mut u = vec![0.0; p.len()];
    DisplacementOperator::of_problem(problem)?.apply(p.view(), &mut u)?;
    let g0 = gap.gap();
    let g0 = g0
        .as_slice()
        .unwrap_or_else(|| unreachable!("a gap is one slice"));
    let mut g = Vec::new();
    g0.par_iter()
        .with_min_len(CHUNK)
        .zip(&u)
        .map(|(&g0, &ui)| g0 + ui - approach)
        .collect_into_vec(&mut g);
    let p = p.into_raw_vec_and_offset().0;
    Ok(StepSolution::new(shape, [p, g, u], *problem.material()).into_fields(request))
}

/// [`fields_from_pressure`]'s fields of a step from its `pressure` (Pa) and its composite
/// displacement `u = K p` (m, [`DisplacementOperator::apply`]), all `[[iy, ix]]` on one grid:
/// the gap `g = g₀ + u − δ` with `g₀ = max z − z` of the composite height `z` the contact was
/// solved on (as [`super::CompositeGap`] makes it), at the approach `approach` (m), then the
/// fields as [`assemble_fields`] makes them, bit for bit. Written into `fields`, whose arrays are
/// overwritten in place where they have the grid's shape (a caller deriving several steps
/// allocates them once). An error when the maps are not on one grid.
pub fn fields_from_displacement(
    composite_height: ArrayView2<f64>,
    pressure: ArrayView2<f64>,
    displacement: ArrayView2<f64>,
    approach: f64,
    material: &ContactMaterial,
    request: FieldRequest,
    fields: &mut ContactFields,
) -> Result<(), ContactError> {
    let top = PointFields::new(composite_height, pressure, displacement, approach, material)?.top();
    let shape = composite_height.dim();
    let (z, p, u) = (
        composite_height.as_standard_layout(),
        pressure.as_standard_layout(),
        displacement.as_standard_layout(),
    );
    let (z, p, u) = (values(&z), values(&p), values(&u));
    let gap = |i: usize| gap(top, z[i], u[i], approach);
    write_fields(fields, shape, (p, gap, u), material, request);
    Ok(())
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

    /// One operator applied to every step's pressure in turn, and the fields assembled from its
    /// displacement into the arrays of the step before, equal the fields a new operator derives
    /// for each step alone, bit for bit (elastic and capped, periodic and isolated).
    #[test]
    fn one_operator_for_all_steps_gives_each_steps_fields_bit_for_bit() {
        let (lower, upper) = (rough(5, 40), rough(6, 40));
        for (boundary, flow_pressure) in [
            (Boundary::Periodic, 2e9),
            (Boundary::NonPeriodic, f64::INFINITY),
        ] {
            let composite = lower.heights() + upper.heights();
            let gap = CompositeGap::from_surfaces(&lower, &upper).unwrap();
            let material = ContactMaterial::against_rigid_flat(110e9, flow_pressure).unwrap();
            let problem = ContactProblem::new(gap, material, boundary);
            let options = SolverOptions {
                fields: FieldRequest::ALL,
                ..SolverOptions::default()
            };
            let mut solver = ContactSolver::new(problem.clone(), options).unwrap();
            let curve = solver.solve_load_steps(&[2e7, 1e8, 3e8]).unwrap();
            let mut operator = DisplacementOperator::of_problem(&problem).unwrap();
            let mut reused = ContactFields::default();
            for step in &curve.steps {
                let pressure = step.fields.as_ref().unwrap().pressure.as_ref().unwrap();
                let mut u = Array2::zeros(pressure.dim());
                operator
                    .apply(pressure.view(), u.as_slice_mut().unwrap())
                    .unwrap();
                fields_from_displacement(
                    composite.view(),
                    pressure.view(),
                    u.view(),
                    step.approach,
                    &material,
                    FieldRequest::ALL,
                    &mut reused,
                )
                .unwrap();
                let alone = fields_from_pressure(
                    &problem,
                    pressure.view(),
                    step.approach,
                    FieldRequest::ALL,
                )
                .unwrap();
                assert_eq!(
                    reused, alone,
                    "{boundary:?}, step at {} Pa",
                    step.nominal_pressure
                );
            }
        }
    }

    /// On a grid of several parallel chunks, with saturated, free and zero pressures: the fields
    /// in new arrays, in reused arrays and moved out of a solution are the point formulas, bit
    /// for bit.
    #[test]
    fn every_path_writes_the_point_formulas_on_a_grid_of_several_chunks() {
        let shape = (300, 131);
        let n = shape.0 * shape.1;
        assert!(n > 2 * CHUNK);
        let material = ContactMaterial::from_young_poisson(210e9, 0.3, 70e9, 0.33, 5e8).unwrap();
        let (plim, share) = (material.flow_pressure(), material.first_body_share());
        let wave = |i: usize, k: f64| ((i as f64) * k).sin();
        let p: Vec<f64> = (0..n)
            .map(|i| (plim * 1.2 * wave(i, 0.37)).max(0.0).min(plim))
            .collect();
        let g: Vec<f64> = (0..n).map(|i| 1e-7 * wave(i, 0.11)).collect();
        let u: Vec<f64> = (0..n).map(|i| 3e-7 * wave(i, 0.013)).collect();
        let grid =
            |f: &dyn Fn(usize) -> f64| Array2::from_shape_fn(shape, |(y, x)| f(y * shape.1 + x));
        let expected = ContactFields {
            pressure: Some(grid(&|i| p[i])),
            gap: Some(grid(&|i| g[i])),
            deformation_first: Some(grid(&|i| u[i] * share)),
            deformation_second: Some(grid(&|i| u[i] * (1.0 - share))),
            plastic_penetration: Some(grid(&|i| if p[i] >= plim { (-g[i]).max(0.0) } else { 0.0 })),
        };
        assert!(p.contains(&plim) && p.iter().any(|&v| v > 0.0 && v < plim));
        let fresh = assemble_fields(shape, (&p, &g, &u), &material, FieldRequest::ALL);
        assert_eq!(fresh, expected);
        let mut reused = ContactFields {
            pressure: Some(Array2::from_elem(shape, 9.0)),
            gap: Some(Array2::from_elem(shape, 9.0)),
            deformation_first: Some(Array2::from_elem(shape, 9.0)),
            deformation_second: Some(Array2::from_elem((3, 3), 9.0)),
            plastic_penetration: None,
        };
        write_fields(
            &mut reused,
            shape,
            (&p, |i| g[i], &u),
            &material,
            FieldRequest::ALL,
        );
        assert_eq!(reused, expected);
        let moved = StepSolution::new(shape, [p, g, u], material).into_fields(FieldRequest::ALL);
        assert_eq!(moved, expected);
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
