//! The asperity side of `scripts/race-peers.sh`: one periodic rough surface against a rigid flat,
//! solved at one nominal pressure, timed, and reported as one JSON line on stdout.
//!
//! The surface file holds `grid × grid` heights in metres as raw little-endian `f64`, row-major
//! (`[[iy, ix]]`, x fastest), one period of a doubly periodic surface of side `--length` metres.
//!
//! Run: `cargo run --release -p asperity-numerics --example race -- --surface FILE --grid N
//!       --length M --modulus PA --pressure PA [--flow-pressure PA] [--tolerance T] [--repeat R]
//!       [--mixed-precision true|false]`
//!
//! * `--modulus`: composite modulus `E*` of the elastic body (the flat is rigid);
//! * `--flow-pressure`: pressure cap `p_lim` (elastic–perfectly-plastic); omitted: elastic;
//! * `--tolerance`: `SolverOptions::tolerance` (default: the solver's default);
//! * `--repeat`: number of timed solves, each by a new solver (default 1);
//! * `--mixed-precision`: `SolverOptions::mixed_precision` (default: the solver's default).
//!
//! `iterations` are the CG iterations on the grid, `coarse_iterations` those of the multilevel
//! start on the coarser grids (their time is in `solve_s`).
//!
//! Each repetition builds a fresh `ContactSolver` (timed in `setup_s`: FFT plans, influence
//! kernel, work arrays) and solves once (timed in `solve_s`: `ContactSolver::solve` from its
//! cold start to the converged load step, area fraction included). Thread count: rayon's
//! (`RAYON_NUM_THREADS`). On Linux `solve_cpu_s` is the CPU time of the process's threads during
//! each solve (from `/proc/self/task/*/schedstat`): unlike the wall time it leaves out the time
//! the solver waited for a core, so A/B comparisons on a loaded machine use it.

use std::process::ExitCode;
use std::time::Instant;

use asperity_numerics::contact::{
    Boundary, ContactMaterial, ContactProblem, ContactSolver, SolverOptions,
};
use ndarray::Array2;

/// Parsed command line.
struct Args {
    surface: String,
    grid: usize,
    length: f64,
    modulus: f64,
    pressure: f64,
    flow_pressure: f64,
    tolerance: f64,
    repeat: usize,
    mixed_precision: bool,
}

const USAGE: &str = "usage: race --surface FILE --grid N --length M --modulus PA --pressure PA \
                     [--flow-pressure PA] [--tolerance T] [--repeat R] \
                     [--mixed-precision true|false]";

fn main() -> ExitCode {
    match run() {
        Ok(line) => {
            println!("{line}");
            ExitCode::SUCCESS
        }
        Err(message) => {
            eprintln!("race: {message}");
            ExitCode::FAILURE
        }
    }
}

fn parse_args() -> Result<Args, String> {
    let mut surface = None;
    let mut grid = None;
    let mut length = None;
    let mut modulus = None;
    let mut pressure = None;
    let mut flow_pressure = f64::INFINITY;
    let mut tolerance = SolverOptions::default().tolerance;
    let mut repeat = 1;
    let mut mixed_precision = SolverOptions::default().mixed_precision;
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args
            .next()
            .ok_or_else(|| format!("{flag} needs a value\n{USAGE}"))?;
        let number = || {
            value
                .parse::<f64>()
                .map_err(|e| format!("{flag} {value}: {e}"))
        };
        let count = || {
            value
                .parse::<usize>()
                .map_err(|e| format!("{flag} {value}: {e}"))
        };
        match flag.as_str() {
            "--surface" => surface = Some(value.clone()),
            "--grid" => grid = Some(count()?),
            "--length" => length = Some(number()?),
            "--modulus" => modulus = Some(number()?),
            "--pressure" => pressure = Some(number()?),
            "--flow-pressure" => flow_pressure = number()?,
            "--tolerance" => tolerance = number()?,
            "--repeat" => repeat = count()?,
            "--mixed-precision" => {
                mixed_precision = value
                    .parse::<bool>()
                    .map_err(|e| format!("{flag} {value}: {e} (true or false)"))?
            }
            _ => return Err(format!("unknown argument {flag}\n{USAGE}")),
        }
    }
    let missing = |name: &str| format!("{name} is required\n{USAGE}");
    Ok(Args {
        surface: surface.ok_or_else(|| missing("--surface"))?,
        grid: grid.ok_or_else(|| missing("--grid"))?,
        length: length.ok_or_else(|| missing("--length"))?,
        modulus: modulus.ok_or_else(|| missing("--modulus"))?,
        pressure: pressure.ok_or_else(|| missing("--pressure"))?,
        flow_pressure,
        tolerance,
        repeat: repeat.max(1),
        mixed_precision,
    })
}

/// Reads `grid × grid` little-endian `f64` heights.
fn read_heights(path: &str, grid: usize) -> Result<Array2<f64>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let expected = grid * grid * 8;
    if bytes.len() != expected {
        return Err(format!(
            "{path} has {} bytes, a {grid} × {grid} f64 surface has {expected}",
            bytes.len()
        ));
    }
    let heights = bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
        .collect();
    Array2::from_shape_vec((grid, grid), heights).map_err(|e| e.to_string())
}

fn run() -> Result<String, String> {
    let args = parse_args()?;
    let heights = read_heights(&args.surface, args.grid)?;
    let spacing = args.length / args.grid as f64;
    let material = ContactMaterial::against_rigid_flat(args.modulus, args.flow_pressure)
        .map_err(|e| e.to_string())?;
    // Against a flat the gap is −z up to a shift (`from_gap_array` shifts it to min 0).
    let problem = ContactProblem::from_gap_array(
        heights.mapv(|z| -z).view(),
        spacing,
        spacing,
        material,
        Boundary::Periodic,
    )
    .map_err(|e| e.to_string())?;
    let options = SolverOptions {
        tolerance: args.tolerance,
        mixed_precision: args.mixed_precision,
        ..SolverOptions::default()
    };
    let mut setups = Vec::with_capacity(args.repeat);
    let mut solves = Vec::with_capacity(args.repeat);
    let mut cpu = Vec::with_capacity(args.repeat);
    let mut step = None;
    for _ in 0..args.repeat {
        let start = Instant::now();
        let mut solver = ContactSolver::new(problem.clone(), options).map_err(|e| e.to_string())?;
        setups.push(start.elapsed().as_secs_f64());
        let (start, cpu_start) = (Instant::now(), process_cpu_seconds());
        let result = solver.solve(args.pressure).map_err(|e| e.to_string())?;
        solves.push(start.elapsed().as_secs_f64());
        if let (Some(a), Some(b)) = (cpu_start, process_cpu_seconds()) {
            cpu.push(b - a);
        }
        step = Some(result);
    }
    let step = step.ok_or("no solve ran")?;
    let list = |times: &[f64]| {
        times
            .iter()
            .map(|t| format!("{t:.6}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let cpu = if cpu.len() == solves.len() {
        format!(", \"solve_cpu_s\": [{}]", list(&cpu))
    } else {
        String::new()
    };
    Ok(format!(
        "{{\"area_fraction\": {}, \"iterations\": {}, \"coarse_iterations\": {}, \
         \"residual\": {:e}, \"setup_s\": [{}], \"solve_s\": [{}]{cpu}}}",
        step.area_fraction,
        step.iterations,
        step.coarse_iterations,
        step.residuals.max(),
        list(&setups),
        list(&solves)
    ))
}

/// CPU time in seconds of all threads of this process so far: the sum of the first field
/// (nanoseconds on a CPU) of `/proc/self/task/<tid>/schedstat`; `None` where that is not
/// readable (not Linux, or schedstats off).
fn process_cpu_seconds() -> Option<f64> {
    let mut total = 0u64;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let path = task.ok()?.path().join("schedstat");
        let text = std::fs::read_to_string(path).ok()?;
        total += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total as f64 * 1e-9)
}
