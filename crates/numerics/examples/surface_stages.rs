//! Where the time of one synthetic `surface` node goes: every stage of the `surfaces` row (the
//! calls of `src/nodes/surface/metrics.rs`, in its order) on one synthetic surface, each timed
//! on its own, median of `--repeat` runs, one line per stage on stdout.
//!
//! Run: `cargo run --release -p asperity-numerics --example surface_stages -- [--n N]
//!       [--repeat R]` (defaults: 3512 points a side, 3 repeats). The surface is body S I of
//! `studies/ground-validation.yaml` at its measured size (1.953 mm square, Sq 1.19 µm, roll-off
//! 120 µm along x with anisotropy ratio 3, H 0.8, S-filter 2.5 µm, seed 101), so `--n 3512` is a
//! surface of the full-size validation. Thread count: rayon's (`RAYON_NUM_THREADS`).
//!
//! Each line is `stage  wall_ms  min_ms  max_ms  cpu_ms`: the median wall time of the stage, its
//! range, and the median CPU time of the process over the stage (every thread; from
//! `/proc/self/stat`, 10 ms resolution, so on a busy machine the CPU time is the steadier figure).
//! The last line, `total`, sums the medians. Under
//! `valgrind --tool=callgrind` use `--repeat 1`: each stage is then one call, and the inclusive
//! instruction counts of the functions named in the stage column are the stage's.

use std::process::ExitCode;
use std::time::Instant;

use asperity_numerics::surface::spectral::{
    hurst_exponent_of, periodic_autocorrelation_with, radial_psd_of, spectral_moments_of,
    texture_direction_of, HurstFitOptions, Window, ISO_ACF_THRESHOLD,
};
use asperity_numerics::surface::synthetic::{
    generate_synthetic_surface_with_spectrum, Anisotropy, SyntheticSurfaceSpec,
};
use asperity_numerics::surface::{
    amplitude_statistics, find_summits, functional_parameters_of, Boundary, FunctionalOptions,
    MaterialRatioCurve, SummitOptions,
};

/// Samples of the material ratio table (as the node writes it: every 1 %).
const MATERIAL_RATIO_SAMPLES: usize = 101;

struct Args {
    n: usize,
    repeat: usize,
}

fn parse_args() -> Result<Args, String> {
    let mut args = Args { n: 3512, repeat: 3 };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let value = it.next().ok_or_else(|| format!("`{flag}` needs a value"))?;
        let parsed: usize = value
            .parse()
            .map_err(|_| format!("`{flag}` = `{value}`: expected a positive integer"))?;
        match flag.as_str() {
            "--n" if parsed >= 16 => args.n = parsed,
            "--repeat" if parsed >= 1 => args.repeat = parsed,
            "--n" | "--repeat" => {
                return Err(format!(
                    "`{flag}` = {parsed}: expected --n ≥ 16, --repeat ≥ 1"
                ))
            }
            _ => return Err(format!("unknown option `{flag}` (expected --n, --repeat)")),
        }
    }
    Ok(args)
}

/// Body S I of the ground validation on an `n × n` grid of the measured spacing (0.556 µm).
fn spec(n: usize) -> SyntheticSurfaceSpec {
    let length = 1.953e-3 * n as f64 / 3512.0;
    SyntheticSurfaceSpec {
        nx: n,
        ny: n,
        lx: length,
        ly: length,
        sq: 1.19e-6,
        hurst: 0.8,
        correlation_length: 120e-6,
        short_wavelength_cutoff: Some(2.5e-6),
        anisotropy: Some(Anisotropy {
            aspect_ratio: 3.0,
            angle: 0.0,
        }),
        seed: 101,
    }
}

/// CPU time of the whole process (every thread), seconds: `utime + stime` of `/proc/self/stat`
/// in clock ticks of 1/100 s (Linux); NaN where that file is not readable.
fn process_cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    // Fields after the command name (in parentheses, which may hold spaces): utime and stime
    // are the 12th and 13th.
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

/// The median of `values` (sorted in place).
fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Per-stage medians: wall and CPU time, ms.
#[derive(Default)]
struct Totals {
    wall: f64,
    cpu: f64,
}

/// Runs `f` `repeat` times; prints the stage's median wall time, its min and max and its median
/// CPU time (ms), adds the medians to `totals` and returns the last result.
fn stage<T>(totals: &mut Totals, name: &str, repeat: usize, mut f: impl FnMut() -> T) -> T {
    let mut wall = Vec::with_capacity(repeat);
    let mut cpu = Vec::with_capacity(repeat);
    let mut last = None;
    for _ in 0..repeat {
        let (start, cpu_start) = (Instant::now(), process_cpu_seconds());
        let value = std::hint::black_box(f());
        wall.push(start.elapsed().as_secs_f64() * 1e3);
        cpu.push((process_cpu_seconds() - cpu_start) * 1e3);
        last = Some(value);
    }
    let (wall_median, cpu_median) = (median(&mut wall), median(&mut cpu));
    println!(
        "{name:<26} {wall_median:>9.1} {:>9.1} {:>9.1} {cpu_median:>9.0}",
        wall[0],
        wall[wall.len() - 1]
    );
    totals.wall += wall_median;
    totals.cpu += cpu_median;
    last.expect("repeat ≥ 1")
}

fn run(args: &Args) -> Result<(), String> {
    let r = args.repeat;
    let err = |e: &dyn std::fmt::Display| e.to_string();
    println!(
        "# {n}² synthetic surface, {r} repeats, {threads} threads",
        n = args.n,
        threads = rayon::current_num_threads()
    );
    println!(
        "{:<26} {:>9} {:>9} {:>9} {:>9}",
        "stage", "wall_ms", "min_ms", "max_ms", "cpu_ms"
    );
    let spec = spec(args.n);
    let t = &mut Totals::default();
    // The node takes the periodogram from the synthesis (no forward transform of the heights),
    // and its inverse transform for the autocorrelation.
    let (map, p, mut transform) = stage(t, "synthesis_and_periodogram", r, || {
        generate_synthetic_surface_with_spectrum(&spec)
    })
    .map_err(|e| err(&e))?;
    stage(t, "amplitude_statistics", r, || {
        amplitude_statistics(&map, Boundary::Periodic)
    })
    .map_err(|e| err(&e))?;
    let curve = stage(t, "material_ratio_curve", r, || {
        MaterialRatioCurve::of(&map)
    })
    .map_err(|e| err(&e))?;
    stage(t, "functional_parameters", r, || {
        functional_parameters_of(&curve, FunctionalOptions::default())
    })
    .map_err(|e| err(&e))?;
    stage(t, "material_ratio_table", r, || {
        curve.sampled(MATERIAL_RATIO_SAMPLES)
    });
    let psd = stage(t, "radial_psd", r, || radial_psd_of(&p, &map));
    stage(t, "spectral_moments", r, || spectral_moments_of(&p, &map)).map_err(|e| err(&e))?;
    // The node writes the autocorrelation into the material-ratio curve's memory: each repeat
    // takes memory of that size already in use (copies made outside the timing).
    let mut spares = vec![curve.into_heights(); r];
    let acf = stage(t, "autocorrelation", r, || {
        let spare = spares.pop().unwrap_or_default();
        periodic_autocorrelation_with(&p, &map, &mut transform, spare)
    })
    .map_err(|e| err(&e))?;
    stage(t, "acf_texture_sal_str", r, || {
        acf.texture(ISO_ACF_THRESHOLD)
    })
    .map_err(|e| err(&e))?;
    stage(t, "acf_correlation_lengths", r, || {
        acf.correlation_lengths(ISO_ACF_THRESHOLD)
    })
    .map_err(|e| err(&e))?;
    stage(t, "texture_direction", r, || texture_direction_of(&p, &map)).map_err(|e| err(&e))?;
    let options = HurstFitOptions {
        q_min: None,
        q_max: None,
        window: Window::None,
    };
    stage(t, "hurst_fit", r, || hurst_exponent_of(&psd, &map, options)).map_err(|e| err(&e))?;
    stage(t, "acf_radial", r, || acf.radial());
    let summit_options = SummitOptions {
        boundary: Boundary::Periodic,
        min_height: None,
        min_prominence: None,
    };
    stage(t, "summits", r, || find_summits(&map, summit_options)).map_err(|e| err(&e))?;
    println!(
        "{:<26} {:>9.1} {:>9} {:>9} {:>9.0}",
        "total", t.wall, "", "", t.cpu
    );
    Ok(())
}

fn main() -> ExitCode {
    match parse_args().and_then(|args| run(&args)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("surface_stages: {message}");
            ExitCode::FAILURE
        }
    }
}
