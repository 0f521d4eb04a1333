#!/usr/bin/env python3
"""Driver of scripts/race-peers.sh: asperity's contact solver against Tamaas and ContactMechanics.

Run it through scripts/race-peers.sh, which creates the Python environment, builds the asperity
example and pins everything to one core. It generates one surface, computes a tight reference
A/A0 with asperity, finds for every racer the loosest tolerance of LADDER that reproduces that
A/A0 to MATCH, times the racer there and prints a Markdown table (stdout; --out FILE too).
`race_peers.py solve ...` (internal) runs one peer solver in its own process and prints a JSON
line, as the Rust example `race` does for asperity. With `--in-process` every racer runs inside
this one Python process and asperity is the Python package (`asperity.contact`, installed into
the race environment by scripts/race-peers.sh), called as a notebook user would.

Every solver reads the same surface file (raw little-endian f64 heights in metres) and gets the
same SI inputs; the peers convert them to micrometres and GPa (Tamaas' Kato solvers take a
gradient step that is not scale invariant: in SI they do not move, in um/GPa the numbers are
of order one).
"""

import argparse
import contextlib
import datetime
import importlib.metadata
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

# Problem: steel on steel (E = 210 GPa, nu = 0.3 on both sides) reduced to one elastic body of
# composite modulus E* against a rigid flat.
LENGTH = 1e-3  # side of the periodic square, m
SQ = 1e-6  # rms height, m
HURST = 0.8
ROLLOFF_DIVISOR = 4  # roll-off wavelength L/4
CUTOFF_PIXELS = 8  # short-wavelength cut-off, in pixels
SEED = 1
COMPOSITE_MODULUS = 210e9 / (2.0 * (1.0 - 0.3**2))  # 115.4 GPa
FLOW_PRESSURE = 2.9e9  # p_lim of the capped race, Pa
TARGET_ELASTIC_AREA = 0.03  # the nominal pressure aims at A/A0 = 3 % in the elastic race
REFERENCE_TOLERANCE = 1e-10  # asperity's tolerance for the reference A/A0
MATCH = 5e-3  # racers must reproduce the reference A/A0 to 0.5 % (relative)
LADDER = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]  # race tolerances tried, loosest first
MAX_ITERATIONS = 100_000

RACES = {
    "elastic": ["asperity", "tamaas-pkr", "cm-ccg"],
    "capped": ["asperity", "cm-plastic", "tamaas-kato"],
}
# `--in-process`: the Python package in place of the Rust example, every racer in this process.
IN_PROCESS_RACES = {
    race: ["asperity-py" if solver == "asperity" else solver for solver in solvers]
    for race, solvers in RACES.items()
}
LABELS = {
    "asperity": "asperity `ContactSolver`",
    "asperity-py": "asperity `asperity.contact` (Python)",
    "tamaas-pkr": "Tamaas `PolonskyKeerRey`",
    "tamaas-kato": "Tamaas `KatoSaturated`",
    "cm-ccg": "ContactMechanics `NonSmoothContactSystem`",
    "cm-plastic": "ContactMechanics `PlasticNonSmoothContactSystem`",
}
PEERS = sorted(set(LABELS) - {"asperity"})
PACKAGES = ["numpy", "tamaas", "ContactMechanics", "SurfaceTopography", "muGrid", "NuMPI", "asperity"]

NOTES = """\
* Solve time: median of {repeat} solves from a cold start on one core (`taskset -c 0`; \
`RAYON_NUM_THREADS`, `OMP_NUM_THREADS`, `OPENBLAS_NUM_THREADS`, `MKL_NUM_THREADS` = 1), {where}; \
imports, reading the surface and building the solver objects are outside the timer.
* asperity: `ContactSolver::solve` of a new `ContactSolver` (`ContactSolver::new`, which plans \
the FFTs and builds the kernel, is outside); tolerance: `SolverOptions::tolerance`, the bound \
on every relative residual (gap / Sq, force balance).
* Tamaas (PyPI wheel, serial `cpp` backend): `solve(p)` of a solver built on a fresh `Model`; \
tolerance: the solver's own error norm; inputs in µm and GPa.
* ContactMechanics: `minimize_proxy(external_force=...)` of a system built on a fresh \
substrate and topography (the package's Python CCG loop and its FFTs); tolerance ε: \
`pentol = ε Sq`, `forcetol = ε p̄ A_pixel`, `thermotol = ε`.
* asperity (Python, `--in-process` only): `asperity.contact(heights, dx, nominal_pressures=[p̄], \
lower_material={{youngs_modulus: E*, poisson_ratio: 0}}, flow_pressure=…, tolerance=ε)`, every \
racer in one Python process; its timer includes what the Rust row leaves out (FFT plans, \
kernel, copying the arrays in and the fields out).
* Matched accuracy: A/A₀ is the share of grid points with p > 0. The reference is asperity at \
tolerance {reference}; each racer runs at the loosest of {ladder} whose A/A₀ is within \
{match:g} % of it (the column before shows the next looser one, empty if there is none); \
the script fails otherwise.
"""


def log(message):
    print(f"race: {message}", file=sys.stderr, flush=True)


def fail(message):
    print(f"race: ERROR: {message}", file=sys.stderr, flush=True)
    sys.exit(1)


# --- surface -------------------------------------------------------------------------------------


def wavevectors(grid, length):
    """Angular wavevector moduli |q| of the rfft2 layout (rows: fftfreq, columns: rfftfreq)."""
    qy = 2 * np.pi * np.fft.fftfreq(grid, d=length / grid)
    qx = 2 * np.pi * np.fft.rfftfreq(grid, d=length / grid)
    return np.hypot(qy[:, None], qx[None, :]), qy, qx


def self_affine_surface(grid, length):
    """Periodic Gaussian self-affine heights (m): white noise filtered to the isotropic PSD
    C(q) ∝ 1 below the roll-off, ∝ q^-2(1+H) up to the cut-off, 0 above; scaled to Sq."""
    q, _, _ = wavevectors(grid, length)
    q_rolloff = 2 * np.pi * ROLLOFF_DIVISOR / length
    q_cutoff = 2 * np.pi * grid / (CUTOFF_PIXELS * length)
    psd = (np.maximum(q, q_rolloff) / q_rolloff) ** (-2 * (1 + HURST))
    psd[q > q_cutoff] = 0.0
    psd[0, 0] = 0.0
    noise = np.fft.rfft2(np.random.default_rng(SEED).standard_normal((grid, grid)))
    heights = np.fft.irfft2(noise * np.sqrt(psd), s=(grid, grid))
    return heights * (SQ / np.sqrt(np.mean(heights**2)))


def rms_slope(heights, length):
    """Spectral rms gradient sqrt(<|grad h|^2>) of periodic heights."""
    grid = heights.shape[0]
    _, qy, qx = wavevectors(grid, length)
    spectrum = np.fft.rfft2(heights)
    gx = np.fft.irfft2(1j * qx[None, :] * spectrum, s=heights.shape)
    gy = np.fft.irfft2(1j * qy[:, None] * spectrum, s=heights.shape)
    return float(np.sqrt(np.mean(gx**2 + gy**2)))


def nominal_pressure(slope):
    """p with A/A0 ≈ TARGET_ELASTIC_AREA by A/A0 = 2 p / (E* h'), 3 significant digits."""
    pressure = TARGET_ELASTIC_AREA * COMPOSITE_MODULUS * slope / 2
    return float(f"{pressure:.3g}")


def read_surface(path, grid):
    return np.fromfile(path, dtype="<f8").reshape(grid, grid)


# --- peer solvers (run in a child process each: `race_peers.py solve ...`) -----------------------


@contextlib.contextmanager
def captured_stderr(lines):
    """Collects what C++ code writes to file descriptor 2 (Tamaas' iteration log) into lines."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile() as sink:
        os.dup2(sink.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            sink.seek(0)
            lines.extend(sink.read().decode(errors="replace").splitlines())


def tamaas_log(lines):
    """Iterations and final error of a solve from Tamaas' log: the sum of the last iteration
    number of each `Iter Cost_f Error` block (KatoSaturated runs more than one block per solve)
    and the error of the last row."""
    total, last, error = 0, None, float("nan")
    for line in lines + [" Iter"]:
        fields = line.split()
        if fields and fields[0] == "Iter":
            total += last or 0
            last = None
        elif len(fields) == 3 and fields[0].isdigit():
            last, error = int(fields[0]), float(fields[2])
    return total, error


def solve_tamaas(kind, heights, args):
    import tamaas as tm

    tm.initialize(1)
    um, gpa = 1e-6, 1e9
    grid = heights.shape[0]
    surface = np.ascontiguousarray(heights / um)

    def build():
        model = tm.ModelFactory.createModel(
            tm.model_type.basic_2d, [args.length / um] * 2, [grid, grid]
        )
        model.E, model.nu = args.modulus / gpa, 0.0
        if kind == "tamaas-pkr":
            solver = tm.PolonskyKeerRey(model, surface, args.tolerance)
        else:
            solver = tm.KatoSaturated(model, surface, args.tolerance, args.flow_pressure / gpa)
        solver.max_iter = MAX_ITERATIONS
        return model, solver

    def solve(state):
        model, solver = state
        lines = []
        with captured_stderr(lines):
            start = time.perf_counter()
            solver.solve(args.pressure / gpa)
            elapsed = time.perf_counter() - start
        iterations, error = tamaas_log(lines)
        if not error <= args.tolerance:
            raise RuntimeError(
                f"{kind} did not converge: error {error:g} > {args.tolerance:g} after "
                f"{iterations} iterations; its log:\n" + "\n".join(lines[-5:])
            )
        area = float(np.mean(model.traction > 0))
        return elapsed, area, iterations, error

    return build, solve


def solve_contact_mechanics(kind, heights, args):
    from ContactMechanics import PeriodicFFTElasticHalfSpace, make_plastic_system, make_system
    from SurfaceTopography import PlasticTopography, Topography

    um, gpa = 1e-6, 1e9
    grid = heights.shape[0]
    length = args.length / um
    pressure = args.pressure / gpa
    surface = heights / um
    sq = float(np.sqrt(np.mean((surface - surface.mean()) ** 2)))
    eps = args.tolerance

    def build():
        substrate = PeriodicFFTElasticHalfSpace(
            (grid, grid), args.modulus / gpa, physical_sizes=(length, length)
        )
        topography = Topography(surface, physical_sizes=(length, length), periodic=True)
        if kind == "cm-plastic":
            return make_plastic_system(
                surface=PlasticTopography(topography, args.flow_pressure / gpa),
                substrate=substrate,
            )
        return make_system(surface=topography, substrate=substrate)

    def solve(system):
        start = time.perf_counter()
        result = system.minimize_proxy(
            external_force=pressure * length**2,
            pentol=eps * sq,
            forcetol=eps * pressure * (length / grid) ** 2,
            thermotol=eps,
            maxiter=MAX_ITERATIONS,
        )
        elapsed = time.perf_counter() - start
        if not result.success:
            raise RuntimeError(f"{kind} did not converge: {result.message}")
        area = float(np.mean(result.jac > 0))
        return elapsed, area, int(result.nit), None

    return build, solve


def solve_asperity_py(kind, heights, args):
    import asperity

    grid = heights.shape[0]
    spacing = args.length / grid
    material = {"youngs_modulus": args.modulus, "poisson_ratio": 0.0}
    flow = None if np.isinf(args.flow_pressure) else args.flow_pressure

    def build():
        return None

    def solve(_):
        start = time.perf_counter()
        result = asperity.contact(
            heights,
            spacing,
            nominal_pressures=[args.pressure],
            lower_material=material,
            flow_pressure=flow,
            tolerance=args.tolerance,
        )
        elapsed = time.perf_counter() - start
        area = float(np.mean(result["pressure"] > 0))
        return elapsed, area, int(result["iterations"]), float(result["residual"])

    return build, solve


def solver_for(solver):
    if solver == "asperity-py":
        return solve_asperity_py
    if solver.startswith("tamaas"):
        return solve_tamaas
    return solve_contact_mechanics


def iteration_count(row):
    """CG iterations, with asperity's multilevel-start iterations on the coarser grids."""
    coarse = row.get("coarse_iterations", 0)
    return f"{row['iterations']} + {coarse} coarse" if coarse else f"{row['iterations']}"


def peer_result(args):
    """One peer's solves as the JSON result dict (area, iterations, residual, times)."""
    heights = read_surface(args.surface, args.grid)
    build, solve = solver_for(args.solver)(args.solver, heights, args)
    setups, times = [], []
    for _ in range(args.repeat):
        start = time.perf_counter()
        state = build()
        setups.append(time.perf_counter() - start)
        elapsed, area, iterations, residual = solve(state)
        times.append(elapsed)
    return {
        "area_fraction": area,
        "iterations": iterations,
        "residual": residual,
        "setup_s": setups,
        "solve_s": times,
    }


def run_peer(args):
    print(json.dumps(peer_result(args)))


# --- orchestration -------------------------------------------------------------------------------


def run_racer(solver, race, tolerance, repeat, setup):
    """Runs one racer in a child process and returns its JSON result (dies loudly on failure)."""
    common = [
        "--surface", setup["surface"],
        "--grid", str(setup["grid"]),
        "--length", repr(LENGTH),
        "--modulus", repr(COMPOSITE_MODULUS),
        "--pressure", repr(setup["pressure"]),
        "--tolerance", repr(tolerance),
        "--repeat", str(repeat),
    ]  # fmt: skip
    if race == "capped":
        common += ["--flow-pressure", repr(FLOW_PRESSURE)]
    log(f"{race}: {solver} at tolerance {tol(tolerance)}, {repeat} solve(s) ...")
    if setup["in_process"]:
        result = run_in_process(solver, race, common)
    else:
        result = run_child(solver, race, common, setup)
    result["median_s"] = statistics.median(result["solve_s"])
    result["tolerance"] = tolerance
    reference = setup["reference"].get(race)
    versus = "" if reference is None else f" ({deviation(result['area_fraction'], reference):+.3%})"
    log(
        f"{race}: {solver}: A/A0 = {result['area_fraction']:.6f}{versus}, "
        f"{result['iterations']} iterations, median {result['median_s']:.3f} s"
    )
    return result


def run_in_process(solver, race, common):
    """The racer in this process (`--in-process`), with the arguments a child would get."""
    parser = argparse.ArgumentParser()
    add_solve_arguments(parser)
    args = parser.parse_args(["--solver", solver, *common])
    try:
        return peer_result(args)
    except Exception as e:  # a racer's failure ends the race with its message
        fail(f"{race} race: {solver} failed: {type(e).__name__}: {e}")


def run_child(solver, race, common, setup):
    """The racer in a child process: the Rust example, or this script's `solve` mode."""
    if solver == "asperity":
        command = [setup["asperity"], *common]
    else:
        command = [sys.executable, os.path.abspath(__file__), "solve", "--solver", solver, *common]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        fail(
            f"{race} race: {solver} failed (exit {done.returncode}):\n"
            f"  command: {' '.join(command)}\n  {done.stderr.strip()[-3000:]}"
        )
    try:
        return json.loads(done.stdout.strip().splitlines()[-1])
    except (IndexError, json.JSONDecodeError):
        fail(f"{race} race: {solver} printed no JSON result line:\n{done.stdout}\n{done.stderr}")


def tol(value):
    """1e-04 -> 1e-4."""
    mantissa, _, exponent = f"{value:.0e}".partition("e")
    return f"{mantissa}e{int(exponent)}"


def deviation(area, reference):
    return (area - reference) / reference


def matched_tolerance(solver, race, setup):
    """The loosest tolerance of LADDER whose A/A0 is within MATCH of the reference, and the
    deviation at the next looser one (None if the loosest matched)."""
    looser = None
    for tolerance in LADDER:
        area = run_racer(solver, race, tolerance, 1, setup)["area_fraction"]
        off = deviation(area, setup["reference"][race])
        if abs(off) <= MATCH:
            return tolerance, looser
        looser = off
    fail(
        f"{race} race: {solver} does not reproduce the reference A/A0 to {MATCH * 100:g} % at "
        f"any tolerance down to {tol(LADDER[-1])} (last: {looser * 100:+.3f} %)"
    )


def cpu_model():
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def versions():
    found = []
    for name in PACKAGES:
        try:
            found.append(f"{name} {importlib.metadata.version(name)}")
        except importlib.metadata.PackageNotFoundError:
            found.append(f"{name} missing")
    return f"Python {platform.python_version()}, " + ", ".join(found)


def race_table(setup, results, repeat):
    grid = setup["grid"]
    lines = [
        "### Contact solvers on one core: asperity, Tamaas and ContactMechanics",
        "",
        f"{datetime.date.today().isoformat()}, {cpu_model()}; asperity "
        f"{setup['asperity_version']} ({setup['rustc']}); {versions()}.",
        "",
        f"Surface: {grid}² periodic self-affine Gaussian, L = {LENGTH * 1e3:g} mm, "
        f"Sq = {SQ * 1e6:g} µm, H = {HURST}, roll-off L/{ROLLOFF_DIVISOR}, "
        f"cut-off {CUTOFF_PIXELS} px, seed {SEED} (rms slope {setup['slope']:.4f}), against a "
        f"rigid flat; E* = {COMPOSITE_MODULUS / 1e9:.1f} GPa, "
        f"p̄ = {setup['pressure'] / 1e6:g} MPa; capped: pressure ≤ p_lim = "
        f"{FLOW_PRESSURE / 1e9:g} GPa.",
        "",
        "| race | solver | tolerance | vs reference, 10× looser | iterations | A/A₀ | "
        "vs reference | solve time | time / asperity |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    own_solver = setup["own"]
    for race, rows in results.items():
        reference = setup["reference"][race]
        own = rows[own_solver]["median_s"]
        lines.append(
            f"| {race} | reference: {LABELS[own_solver]} | {tol(REFERENCE_TOLERANCE)} | | "
            f"{setup['reference_iterations'][race]} | {reference * 100:.4f} % | | | |"
        )
        for solver, row in rows.items():
            looser = "" if row["looser"] is None else f"{row['looser'] * 100:+.2f} %"
            lines.append(
                f"| {race} | {LABELS[solver]} | {tol(row['tolerance'])} | {looser} | "
                f"{iteration_count(row)} | {row['area_fraction'] * 100:.4f} % | "
                f"{deviation(row['area_fraction'], reference) * 100:+.3f} % | "
                f"{row['median_s']:.3f} s | {row['median_s'] / own:.1f}× |"
            )
    lines += [
        "",
        NOTES.format(
            repeat=repeat,
            where="every racer in one Python process"
            if setup["in_process"]
            else "each solver in its own process",
            reference=tol(REFERENCE_TOLERANCE),
            ladder=", ".join(tol(t) for t in LADDER),
            match=MATCH * 100,
        ),
    ]
    return "\n".join(lines)


def prepare(args):
    """Writes the surface and computes the reference A/A0 of each race."""
    os.makedirs(args.workdir, exist_ok=True)
    surface = os.path.join(args.workdir, f"surface-{args.grid}.f64")
    heights = self_affine_surface(args.grid, LENGTH)
    heights.astype("<f8").tofile(surface)
    slope = rms_slope(heights, LENGTH)
    setup = {
        "surface": surface,
        "grid": args.grid,
        "slope": slope,
        "pressure": nominal_pressure(slope),
        "asperity": args.asperity,
        "asperity_version": args.asperity_version,
        "rustc": args.rustc,
        "reference": {},
        "reference_iterations": {},
        "in_process": args.in_process,
        "own": "asperity-py" if args.in_process else "asperity",
        "races": IN_PROCESS_RACES if args.in_process else RACES,
    }
    log(
        f"surface {surface}: {args.grid}², Sq {SQ:g} m, rms slope {slope:.4f}, "
        f"nominal pressure {setup['pressure']:g} Pa"
    )
    for race in setup["races"]:
        reference = run_racer(setup["own"], race, REFERENCE_TOLERANCE, 1, setup)
        setup["reference"][race] = reference["area_fraction"]
        setup["reference_iterations"][race] = reference["iterations"]
    return setup


def parse_overrides(items, races):
    overrides = {}
    known = [f"{race}:{solver}" for race, solvers in races.items() for solver in solvers]
    for item in items:
        key, _, value = item.partition("=")
        if key not in known:
            fail(f"--tolerance {item}: unknown RACE:SOLVER {key!r}; known: {', '.join(known)}")
        try:
            overrides[key] = float(value)
        except ValueError:
            fail(f"--tolerance {item}: {value!r} is not a number")
    return overrides


def race(args):
    overrides = parse_overrides(args.tolerance, IN_PROCESS_RACES if args.in_process else RACES)
    setup = prepare(args)
    results, mismatches = {}, []
    for race_name, solvers in setup["races"].items():
        rows = {}
        for solver in solvers:
            if solver in args.skip:
                continue
            key = f"{race_name}:{solver}"
            if key in overrides:
                tolerance, looser = overrides[key], None
            else:
                tolerance, looser = matched_tolerance(solver, race_name, setup)
            row = run_racer(solver, race_name, tolerance, args.repeat, setup)
            row["looser"] = looser
            rows[solver] = row
            off = deviation(row["area_fraction"], setup["reference"][race_name])
            if abs(off) > MATCH:
                mismatches.append(
                    f"{race_name}: {solver} at tolerance {tol(tolerance)} gives A/A0 = "
                    f"{row['area_fraction']:.6f}, {off * 100:+.3f} % from the reference "
                    f"{setup['reference'][race_name]:.6f} (allowed ±{MATCH * 100:g} %)"
                )
        results[race_name] = rows
    table = race_table(setup, results, args.repeat)
    print(table)
    if args.out:
        with open(args.out, "w") as out:
            out.write(table + "\n")
        log(f"table written to {args.out}")
    if mismatches:
        fail("accuracy NOT matched, the times are not comparable:\n  " + "\n  ".join(mismatches))


def add_solve_arguments(peer):
    """The arguments of one peer's solves (the `solve` mode, and `--in-process` racers)."""
    peer.add_argument("--solver", required=True, choices=PEERS)
    peer.add_argument("--surface", required=True)
    peer.add_argument("--grid", type=int, required=True)
    peer.add_argument("--length", type=float, required=True)
    peer.add_argument("--modulus", type=float, required=True)
    peer.add_argument("--pressure", type=float, required=True)
    peer.add_argument("--flow-pressure", type=float, default=float("inf"))
    peer.add_argument("--tolerance", type=float, required=True)
    peer.add_argument("--repeat", type=int, default=1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="mode")
    add_solve_arguments(sub.add_parser("solve", help="internal: one peer solver, one JSON line"))
    parser.add_argument(
        "--in-process",
        action="store_true",
        help="every racer in this Python process, asperity through its Python package",
    )
    parser.add_argument("--asperity", help="path of the built `race` example")
    parser.add_argument("--asperity-version", default="unknown")
    parser.add_argument("--rustc", default="rustc")
    parser.add_argument("--grid", type=int, default=1024)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--workdir", default="target/race")
    parser.add_argument("--out", help="also write the Markdown table to this file")
    parser.add_argument(
        "--skip", action="append", default=[], choices=sorted(set(PEERS) - {"asperity-py"})
    )
    parser.add_argument(
        "--tolerance",
        action="append",
        default=[],
        metavar="RACE:SOLVER=VALUE",
        help="race at this tolerance instead of searching one, e.g. capped:tamaas-kato=1e-5",
    )
    args = parser.parse_args()
    if args.mode == "solve":
        run_peer(args)
        return
    if not args.asperity and not args.in_process:
        fail("--asperity PATH (the built race example) is required")
    if args.grid < 16 or args.repeat < 1:
        fail("--grid must be at least 16 and --repeat at least 1")
    race(args)


if __name__ == "__main__":
    main()
