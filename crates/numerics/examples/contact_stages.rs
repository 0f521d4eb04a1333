//! Where the time of one `contact` node goes: the stages of `ContactTask::compute`
//! (`src/nodes/contact/mod.rs`, in its order) on the first specimen pair of
//! `studies/ground-validation.yaml`, one line per stage on stdout.
//!
//! Run: `cargo run --release -p asperity-numerics --example contact_stages -- [--n N]`
//! (default 3512 points a side: the pair at its measured size, 1.953 mm square; S I: Sq
//! 1.19 µm, roll-off 120 µm, H 0.8, seed 101; S II: Sq 0.38 µm, roll-off 76 µm, H 0.857,
//! seed 201; both anisotropy 3 along x, S-filter 2.5 µm; S235JR on S235JR, 2 → 5 → 10 → 20 MPa,
//! fields kept). Thread count: rayon's (`RAYON_NUM_THREADS`). The node logs the same stages
//! as debug events (`asperity run -vv`, `contact stage`).
//!
//! Each line is `stage  wall_s  cpu_s` (CPU of the whole process over the stage, every thread,
//! from `/proc/self/stat` at 10 ms resolution; on a busy machine the steadier figure); a load
//! step's line adds its CG iterations, coarse iterations, free-set iterations and 2-D FFTs
//! (forward or inverse, each counted once).

use std::process::ExitCode;
use std::time::Instant;

use asperity_numerics::contact::Boundary;
use asperity_numerics::contact::{
    CompositeGap, ContactMaterial, ContactProblem, ContactSolver, DisplacementOperator,
    FieldRequest, HeightsView, SolverOptions,
};
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface, Anisotropy, SyntheticSurfaceSpec,
};
use ndarray::Array2;

/// The load steps of the study (Pa).
const PRESSURES: [f64; 4] = [2e6, 5e6, 10e6, 20e6];

fn parse_n() -> Result<usize, String> {
    let mut n = 3512;
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let value = it.next().ok_or_else(|| format!("`{flag}` needs a value"))?;
        match (flag.as_str(), value.parse::<usize>()) {
            ("--n", Ok(v)) if v >= 16 => n = v,
            ("--n", _) => return Err(format!("--n = `{value}`: expected an integer ≥ 16")),
            _ => return Err(format!("unknown option `{flag}` (expected --n)")),
        }
    }
    Ok(n)
}

/// A body of the pair on an `n × n` grid of the measured spacing (0.556 µm).
fn spec(n: usize, sq: f64, roll_off: f64, hurst: f64, seed: u64) -> SyntheticSurfaceSpec {
    let length = 1.953e-3 * n as f64 / 3512.0;
    SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: length,
        ly: length,
        sq,
        hurst,
        correlation_length: roll_off,
        short_wavelength_cutoff: Some(2.5e-6),
        anisotropy: Some(Anisotropy {
            aspect_ratio: 3.0,
            angle: 0.0,
        }),
        seed,
    }
}

/// CPU time of the whole process (every thread), seconds: `utime + stime` of `/proc/self/stat`
/// in clock ticks of 1/100 s (Linux); NaN where that file is not readable.
fn process_cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    let after_name = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let ticks: Vec<f64> = after_name
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|v| v.parse().ok())
        .collect();
    match ticks[..] {
        [user, system] => (user + system) / 100.0,
        _ => f64::NAN,
    }
}

/// Prints a stage's line when it ends.
struct Clock(Instant, f64);

impl Clock {
    fn start() -> Self {
        Self(Instant::now(), process_cpu_seconds())
    }

    fn stage(&mut self, name: &str, extra: &str) {
        let (now, cpu) = (Instant::now(), process_cpu_seconds());
        println!(
            "{name:<32} {:>8.2} {:>8.2} {extra}",
            (now - self.0).as_secs_f64(),
            cpu - self.1
        );
        (self.0, self.1) = (now, cpu);
    }
}

fn run(n: usize) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let lower =
        generate_synthetic_surface(&spec(n, 1.19e-6, 120e-6, 0.8, 101)).map_err(|e| err(&e))?;
    let upper =
        generate_synthetic_surface(&spec(n, 0.38e-6, 76e-6, 0.857, 201)).map_err(|e| err(&e))?;
    let material = ContactMaterial::from_young_poisson(210e9, 0.3, 210e9, 0.3, 1.96133e9)
        .map_err(|e| err(&e))?;
    println!("{:<32} {:>8} {:>8}", "stage", "wall_s", "cpu_s");
    let mut clock = Clock::start();
    let gap =
        CompositeGap::from_height_views(HeightsView::of(&lower), Some(HeightsView::of(&upper)))
            .map_err(|e| err(&e))?;
    clock.stage("gap", "");
    let problem = ContactProblem::new(gap, material, Boundary::Periodic);
    let mut solver = ContactSolver::new(problem, SolverOptions::default()).map_err(|e| err(&e))?;
    clock.stage("influence operator and plans", "");
    let mut earlier: Vec<Array2<f64>> = Vec::new();
    for (i, &pressure) in PRESSURES.iter().enumerate() {
        let step = solver.solve(pressure).map_err(|e| err(&e))?;
        clock.stage(
            &format!("load step {i}"),
            &format!(
                "iterations {} coarse {} free-set {} transforms {}",
                step.iterations,
                step.coarse_iterations,
                step.free_set_iterations,
                step.fft_transforms
            ),
        );
        if i + 1 < PRESSURES.len() {
            earlier.extend(solver.last_pressure().map(|p| p.to_owned()));
        }
    }
    let solution = solver
        .into_last_solution()
        .ok_or("the final step left no solution")?;
    let shape = solution.shape();
    let spacing = (lower.dx(), lower.dy());
    let mut operator = DisplacementOperator::new(shape, spacing, &material, Boundary::Periodic)
        .map_err(|e| err(&e))?;
    let mut displacement = vec![0.0; shape.0 * shape.1];
    for pressure in &earlier {
        operator
            .apply(pressure.view(), &mut displacement)
            .map_err(|e| err(&e))?;
    }
    drop(operator);
    clock.stage("earlier steps' displacements", "");
    let fields = solution.into_fields(FieldRequest::ALL);
    let composite = lower.heights() + upper.heights();
    let kept = upper.heights().to_owned();
    clock.stage("final step's maps and heights", "");
    std::hint::black_box((fields, composite, kept, displacement));
    Ok(())
}

fn main() -> ExitCode {
    match parse_n().and_then(run) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("contact_stages: {e}");
            ExitCode::FAILURE
        }
    }
}
