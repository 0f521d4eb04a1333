//! The load-stepped contact solver: problem definition, warm starts, step results.

use ndarray::ArrayView2;
use rayon::prelude::*;

use super::approach_search;
use super::constrained_cg::{self, CgOutcome, CgSettings, Control};
use super::derived::{self, StepSolution};
use super::error::ContactError;
use super::influence::InfluenceOperator;
use super::load_curve::{ContactFields, LoadCurve, LoadStep};
use super::material::ContactMaterial;
use super::multilevel;
use super::options::{FieldRequest, SolvePath, SolveStrategy, SolverOptions, Termination};
use super::problem::ContactProblem;
use super::workspace::{Workspace, BLOCK};

/// Sums over the fields of a converged step, block by block (combined in block order, so they do
/// not depend on the thread count).
#[derive(Debug, Clone, Copy)]
struct FieldSums {
    contact: usize,
    saturated: usize,
    pressure_sum: f64,
    separation: f64,
    max_u: f64,
}

impl FieldSums {
    const EMPTY: Self = Self {
        contact: 0,
        saturated: 0,
        pressure_sum: 0.0,
        separation: 0.0,
        max_u: f64::NEG_INFINITY,
    };

    fn of_block(p: &[f64], g: &[f64], u: &[f64], plim: f64) -> Self {
        let mut sums = Self::EMPTY;
        for ((&p, &g), &u) in p.iter().zip(g).zip(u) {
            sums.contact += usize::from(p > 0.0);
            sums.saturated += usize::from(p >= plim);
            sums.pressure_sum += p;
            sums.separation += g.max(0.0);
            sums.max_u = sums.max_u.max(u);
        }
        sums
    }

    fn combine(self, other: Self) -> Self {
        Self {
            contact: self.contact + other.contact,
            saturated: self.saturated + other.saturated,
            pressure_sum: self.pressure_sum + other.pressure_sum,
            separation: self.separation + other.separation,
            max_u: self.max_u.max(other.max_u),
        }
    }
}

/// Whether the CG of a contact may precondition its directions (`SolverOptions::preconditioned`):
/// only elastic contacts, without a flow pressure, ever are, so only their operator carries the
/// preconditioner's kernel.
fn preconditions(options: &SolverOptions, material: &ContactMaterial) -> bool {
    options.preconditioned && material.is_elastic()
}

/// Reusable solver of one [`ContactProblem`]: holds the FFT plans, the influence kernel and all
/// work arrays (allocated once), and the pressures of the last converged step for warm starts.
#[derive(Debug)]
pub struct ContactSolver {
    problem: ContactProblem,
    options: SolverOptions,
    operator: InfluenceOperator,
    workspace: Workspace,
    rms: f64,
    last_nominal: Option<f64>,
}

impl ContactSolver {
    /// Plans the FFTs and builds the influence kernel.
    pub fn new(problem: ContactProblem, options: SolverOptions) -> Result<Self, ContactError> {
        options.check()?;
        let gap = problem.gap();
        let operator = InfluenceOperator::new(
            gap.nx(),
            gap.ny(),
            gap.dx(),
            gap.dy(),
            problem.material().composite_modulus(),
            problem.boundary(),
            preconditions(&options, problem.material()),
        )?;
        let workspace = Workspace::new(
            gap.shared_values(),
            gap.nx(),
            problem.material().flow_pressure(),
        );
        let rms = gap.rms();
        Ok(Self {
            problem,
            options,
            operator,
            workspace,
            rms,
            last_nominal: None,
        })
    }

    /// The problem being solved.
    pub fn problem(&self) -> &ContactProblem {
        &self.problem
    }

    /// Forgets the warm start: the next step starts from a uniform pressure.
    pub fn reset(&mut self) {
        self.last_nominal = None;
    }

    /// Solves the nominal pressures `nominal_pressures` (Pa, strictly ascending, each below
    /// `p_lim`) in order, each warm-started from the previous one (on elastic contacts, each from
    /// the multilevel start where the grid allows it). A step that does not converge ends the
    /// curve with [`ContactError::NotConverged`].
    pub fn solve_load_steps(
        &mut self,
        nominal_pressures: &[f64],
    ) -> Result<LoadCurve, ContactError> {
        let mut steps = Vec::with_capacity(nominal_pressures.len());
        let mut previous: Option<f64> = None;
        for (step, &pressure) in nominal_pressures.iter().enumerate() {
            if let Some(prev) = previous {
                if pressure <= prev {
                    return Err(ContactError::NotAscending {
                        step,
                        pressure,
                        previous: prev,
                    });
                }
            }
            steps.push(self.solve_indexed(step, pressure)?);
            previous = Some(pressure);
        }
        Ok(LoadCurve { steps })
    }

    /// Solves one nominal pressure in Pa, warm-started from the last converged step (on elastic
    /// contacts, from the multilevel start where the grid allows it).
    pub fn solve(&mut self, nominal_pressure: f64) -> Result<LoadStep, ContactError> {
        self.solve_indexed(0, nominal_pressure)
    }

    /// Runs the solve on a rayon worker thread: called from outside the pool (a user's main
    /// thread), every parallel pass of the iteration would otherwise be handed to the pool and
    /// waited for across threads, which dominated small grids (256² rough benchmark: 35–40 %
    /// of the solve time; 512²: 12–50 %). Called from a worker (the study engine), it runs in
    /// place.
    fn solve_indexed(&mut self, step: usize, pressure: f64) -> Result<LoadStep, ContactError> {
        rayon::scope(|_| self.solve_on_worker(step, pressure, false))
    }

    /// One step; `prolongated`: the workspace holds pressures prolongated from a coarser grid's
    /// solution (the multilevel start of that grid), which start the step as a warm start would.
    fn solve_on_worker(
        &mut self,
        step: usize,
        pressure: f64,
        prolongated: bool,
    ) -> Result<LoadStep, ContactError> {
        let plim = self.problem.material().flow_pressure();
        if !(pressure.is_finite() && pressure > 0.0) {
            return Err(ContactError::BadNominalPressure { step, pressure });
        }
        if pressure >= plim {
            return Err(ContactError::AboveFlowPressure {
                step,
                pressure,
                flow_pressure: plim,
            });
        }
        let n = self.workspace.p.len() as f64;
        let cold = !prolongated && (self.last_nominal.is_none() || self.restarts_every_step());
        let (coarse_iterations, prolongated) = if cold {
            self.cold_start(pressure)
        } else {
            self.workspace.rebalance(pressure * n);
            (0, prolongated)
        };
        let settings = self.cg_settings(pressure, prolongated);
        self.last_nominal = None;
        let (outcome, path) = self.run_strategy(pressure, &settings)?;
        if outcome.termination != Termination::Converged {
            return Err(ContactError::NotConverged {
                step,
                pressure,
                termination: outcome.termination,
                iterations: outcome.work.iterations,
                residuals: outcome.residuals,
            });
        }
        self.last_nominal = Some(pressure);
        let mut step = self.step_result(pressure, &outcome, path);
        step.coarse_iterations = coarse_iterations;
        Ok(step)
    }

    /// The settings of a step's constrained CG at `pressure` (Pa); `prolongated`: the step
    /// starts from a coarse grid's solution.
    fn cg_settings(&self, pressure: f64, prolongated: bool) -> CgSettings {
        let e_star = self.problem.material().composite_modulus();
        let gap = self.problem.gap();
        let pixel_displacement = pressure * (gap.dx() * gap.dy()).sqrt() / e_star;
        CgSettings {
            tolerance: self.options.tolerance,
            max_iterations: self.options.max_iterations,
            stall_iterations: self.options.stall_iterations,
            flow_pressure: self.problem.material().flow_pressure(),
            gap_scale: self.rms.max(pixel_displacement),
            default_step: 1.0 / self.operator.self_influence(),
            // Measured to pay from a coarse grid's solution only (`precondition` in
            // `constrained_cg.rs`).
            precondition: preconditions(&self.options, self.problem.material()) && prolongated,
            mixed_precision: self.options.mixed_precision,
        }
    }

    /// Solves the started step by the configured strategy (`SolveStrategy`), with the work of
    /// every attempt added up.
    fn run_strategy(
        &mut self,
        pressure: f64,
        settings: &CgSettings,
    ) -> Result<(CgOutcome, SolvePath), ContactError> {
        let ws = &mut self.workspace;
        let op = &mut self.operator;
        let load = Control::Load {
            nominal_pressure: pressure,
        };
        // Zero load-controlled iterations: only the approach estimate of the start.
        let estimate = CgSettings {
            max_iterations: 0,
            ..*settings
        };
        Ok(match self.options.strategy {
            SolveStrategy::ConstrainedCg => (
                constrained_cg::solve(ws, op, load, settings)?,
                SolvePath::ConstrainedCg,
            ),
            SolveStrategy::ApproachSearch => {
                let start = constrained_cg::solve(ws, op, load, &estimate)?;
                let mut search =
                    approach_search::solve(ws, op, pressure, start.approach, settings)?;
                search.work += start.work;
                (search, SolvePath::ApproachSearch)
            }
            SolveStrategy::Auto => {
                let first = constrained_cg::solve(ws, op, load, settings)?;
                // Overflowing numbers overflow on every path: no fall-back.
                if matches!(
                    first.termination,
                    Termination::Converged | Termination::NonFinite
                ) {
                    (first, SolvePath::ConstrainedCg)
                } else {
                    // Restart from the rigid-plastic start: the stalled iterate may be far off.
                    ws.start_rigid_plastic(pressure);
                    let start = constrained_cg::solve(ws, op, load, &estimate)?;
                    let budget = CgSettings {
                        max_iterations: settings
                            .max_iterations
                            .saturating_sub(first.work.iterations),
                        ..*settings
                    };
                    let mut second =
                        approach_search::solve(ws, op, pressure, start.approach, &budget)?;
                    second.work += first.work + start.work;
                    (second, SolvePath::ApproachSearch)
                }
            }
        })
    }

    /// Whether every step starts cold, from the multilevel start, instead of from the last
    /// converged step: on elastic contacts (no flow pressure) whose grid can be coarsened. A warm
    /// start leaves the load to move between distant contact spots on the fine grid, without the
    /// preconditioner (which applies only from a coarse grid's solution); the coarse grids move
    /// it at a fraction of the cost. Capped contacts keep the warm start, where the multilevel
    /// start gains nothing (`docs/contact-solver-design.md`).
    fn restarts_every_step(&self) -> bool {
        self.options.multilevel
            && self.problem.material().is_elastic()
            && multilevel::coarsenable(self.problem.gap().nx(), self.problem.gap().ny())
    }

    /// The start of a step without a warm start: the multilevel start where it applies
    /// (`SolverOptions::multilevel`, see [`Self::multilevel_start`]), else the rigid-plastic
    /// start. Returns the CG iterations on the coarse grids (also when they were discarded) and
    /// whether the multilevel start was taken.
    fn cold_start(&mut self, pressure: f64) -> (usize, bool) {
        let (start, coarse_iterations) = if self.options.multilevel {
            self.multilevel_start(pressure)
        } else {
            (None, 0)
        };
        let prolongated = start.is_some();
        match start {
            Some(coarse) => {
                let nx = self.problem.gap().nx();
                multilevel::prolongate(&coarse, &mut self.workspace.p, nx);
                let n = self.workspace.p.len() as f64;
                self.workspace.rebalance(pressure * n);
            }
            None => self.workspace.start_rigid_plastic(pressure),
        }
        (coarse_iterations, prolongated)
    }

    /// The pressures of the next coarser grid for the multilevel start (`multilevel.rs`): the
    /// coarsest grid solved from its rigid-plastic start, each finer one from the prolongated
    /// pressures of the one below. `None` (with the iterations spent) when the grid cannot be
    /// coarsened, when a coarse solve fails, or when the coarsest contact is mostly saturated.
    fn multilevel_start(&self, pressure: f64) -> (Option<Vec<f64>>, usize) {
        let options = SolverOptions {
            tolerance: self.options.tolerance.max(multilevel::COARSE_TOLERANCE),
            fields: FieldRequest::NONE,
            multilevel: false,
            ..self.options
        };
        let mut iterations = 0;
        let mut start: Option<Vec<f64>> = None;
        for level in multilevel::coarse_levels(&self.problem).into_iter().rev() {
            let nx = level.gap().nx();
            let Ok(mut solver) = ContactSolver::new(level, options) else {
                return (None, iterations);
            };
            if let Some(coarser) = &start {
                multilevel::prolongate(coarser, &mut solver.workspace.p, nx);
            }
            let Ok(step) = solver.solve_on_worker(0, pressure, start.is_some()) else {
                return (None, iterations);
            };
            iterations += step.iterations;
            if start.is_none() && step.plastic_area_share > multilevel::MAX_COARSE_PLASTIC_SHARE {
                return (None, iterations);
            }
            start = Some(std::mem::take(&mut solver.workspace.p));
        }
        (start, iterations)
    }

    fn step_result(&self, pressure: f64, outcome: &CgOutcome, path: SolvePath) -> LoadStep {
        let ws = &self.workspace;
        let plim = self.problem.material().flow_pressure();
        let n = ws.p.len() as f64;
        let FieldSums {
            contact,
            saturated,
            pressure_sum,
            separation,
            max_u,
        } =
            ws.p.par_chunks(BLOCK)
                .zip(ws.g.par_chunks(BLOCK))
                .zip(ws.u.par_chunks(BLOCK))
                .map(|((p, g), u)| FieldSums::of_block(p, g, u, plim))
                .collect::<Vec<_>>()
                .into_iter()
                .fold(FieldSums::EMPTY, FieldSums::combine);
        let area_fraction = contact as f64 / n;
        let mean_contact_pressure = if contact > 0 {
            pressure_sum / contact as f64
        } else {
            0.0
        };
        LoadStep {
            nominal_pressure: pressure,
            area_fraction,
            mean_contact_pressure,
            stress_ratio: if plim.is_finite() {
                mean_contact_pressure / plim
            } else {
                0.0
            },
            plastic_area_share: if contact > 0 {
                saturated as f64 / contact as f64
            } else {
                0.0
            },
            mean_separation: separation / n,
            max_elastic_deformation: max_u,
            approach: outcome.approach,
            iterations: outcome.work.iterations,
            coarse_iterations: 0,
            free_set_iterations: outcome.work.free_set_iterations,
            fft_transforms: outcome.work.fft_transforms,
            residuals: outcome.residuals,
            path,
            fields: self
                .options
                .fields
                .any()
                .then(|| self.fields_of_workspace(self.options.fields)),
        }
    }

    /// The requested fields of the last converged step (`None` before the first step, after a
    /// [`Self::reset`] or after a step that did not converge). With `SolverOptions::fields` off,
    /// a load curve keeps no map of any step and the caller takes the final step's maps here:
    /// one set of `ny × nx` arrays instead of one per step.
    pub fn last_fields(&self, request: FieldRequest) -> Option<ContactFields> {
        self.last_nominal.map(|_| self.fields_of_workspace(request))
    }

    /// The pressure (Pa, `[[iy, ix]]`) of the last converged step, borrowed from the solver
    /// (`None` as for [`Self::last_fields`]).
    pub fn last_pressure(&self) -> Option<ArrayView2<'_, f64>> {
        self.last_nominal?;
        let shape = (self.problem.gap().ny(), self.problem.gap().nx());
        ArrayView2::from_shape(shape, &self.workspace.p).ok()
    }

    /// The requested fields of the last converged step, as [`Self::last_fields`] gives them, from
    /// a solver no longer needed ([`Self::into_last_solution`], then
    /// [`StepSolution::into_fields`]): the pressure, gap and displacement arrays become fields.
    pub fn into_last_fields(self, request: FieldRequest) -> Option<ContactFields> {
        self.into_last_solution()
            .map(|solution| solution.into_fields(request))
    }

    /// The pressure, gap and displacement of the last converged step from a solver no longer
    /// needed: its operator, transforms, problem and every other workspace array are released,
    /// so the caller holds three grid arrays instead of the whole solver (`None` as for
    /// [`Self::last_fields`]).
    pub fn into_last_solution(self) -> Option<StepSolution> {
        self.last_nominal?;
        let shape = (self.problem.gap().ny(), self.problem.gap().nx());
        let material = *self.problem.material();
        let Self {
            workspace,
            operator,
            problem,
            ..
        } = self;
        drop((operator, problem));
        Some(StepSolution::new(
            shape,
            workspace.into_solution(),
            material,
        ))
    }

    fn fields_of_workspace(&self, request: FieldRequest) -> ContactFields {
        let ws = &self.workspace;
        let shape = (self.problem.gap().ny(), self.problem.gap().nx());
        derived::assemble_fields(
            shape,
            (&ws.p, &ws.g, &ws.u),
            self.problem.material(),
            request,
        )
    }
}
