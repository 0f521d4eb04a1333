#!/usr/bin/env bash
# A reproducible race of asperity's contact solver against its peers, Tamaas and
# ContactMechanics, on one core and at matched accuracy. Run by hand (not part of `cargo test`
# or CI); it prints a Markdown table to paste into the README verbatim.
#
# What it does:
#  1. creates a Python virtual environment in target/race-venv (git-ignored; reused when its
#     pinned packages are already installed) and installs from PyPI with pip the versions pinned
#     in PINS below: tamaas, ContactMechanics and their numerical dependencies;
#  2. builds the example `race` of asperity-numerics (crates/numerics/examples/race.rs);
#  3. runs scripts/race_peers.py on core 0 (`taskset -c 0` when available, and
#     RAYON_NUM_THREADS = OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = MKL_NUM_THREADS = 1): it
#     generates one periodic self-affine surface (target/race/surface-N.f64, read by every
#     solver), computes a tight reference contact area with asperity, then times
#       * elastic: asperity vs Tamaas PolonskyKeerRey vs ContactMechanics (CCG);
#       * capped (elastic-perfectly-plastic, p <= 2.9 GPa): asperity vs ContactMechanics'
#         plastic system vs Tamaas KatoSaturated;
#     each at the loosest tolerance of 1e-1, 1e-2, ... whose A/A0 matches the reference to
#     0.5 % (searched with one solve per tolerance; it fails loudly if none does), timed as the
#     median of --repeat solves. The table's header gives date, CPU, versions and the problem.
#
# Usage: scripts/race-peers.sh [--grid N] [--repeat R] [--out FILE] [--skip SOLVER]...
#                              [--tolerance RACE:SOLVER=VALUE]... [--in-process]
#   --grid N       grid points per side (default 1024: 11 to 14 min on a busy 2-core machine,
#                  about 5 of them Tamaas KatoSaturated; 512: about 2 min)
#   --repeat R     timed solves per racer, the median is reported (default 3)
#   --out FILE     also write the table to FILE
#   --skip SOLVER  leave out a peer (tamaas-pkr, tamaas-kato, cm-ccg, cm-plastic)
#   --tolerance    race at this tolerance instead of searching one, e.g. capped:tamaas-kato=1e-5
#                  (RACE is elastic or capped, SOLVER asperity or a peer)
#   --in-process   every racer in one Python process, asperity through its Python package
#                  (built here as a release wheel with maturin and installed into the venv;
#                  SOLVER asperity-py)
# Env: PYTHON (interpreter for the venv, default python3; the pinned wheels need Python 3.11 to
#      3.13 on x86-64 Linux), RACE_VENV (default target/race-venv).
set -euo pipefail

caller=$PWD
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

# Versions used for the published table; the whole list is a pip constraints file.
PINS=(
    tamaas==2.9.0
    ContactMechanics==1.8.3
    SurfaceTopography==1.27.1
    muGrid==1.6.1
    NuMPI==0.18.1
    numpy==2.4.6
    scipy==1.17.1
)

PYTHON=${PYTHON:-python3}
VENV=${RACE_VENV:-$root/target/race-venv}

log() { echo "race-peers: $*" >&2; }
die() {
    echo "race-peers: ERROR: $*" >&2
    exit 1
}

case "${1:-}" in
-h | --help)
    sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'
    exit 0
    ;;
esac

command -v "$PYTHON" >/dev/null || die "no Python interpreter '$PYTHON' (set PYTHON=...)"
command -v cargo >/dev/null || die "cargo is not on PATH"

# --- 1. Python environment -----------------------------------------------------------------------
stamp="$VENV/race-pins.txt"
pins=$(printf '%s\n' "${PINS[@]}")
if [[ -x "$VENV/bin/python" && -f "$stamp" && "$(cat "$stamp")" == "$pins" ]]; then
    log "reusing $VENV (pins unchanged)"
else
    if [[ ! -x "$VENV/bin/python" ]]; then
        log "creating the virtual environment $VENV with $("$PYTHON" --version 2>&1)"
        "$PYTHON" -m venv "$VENV" ||
            die "'$PYTHON -m venv $VENV' failed (on Debian/Ubuntu: apt-get install python3-venv)"
    fi
    rm -f "$stamp"
    echo "$pins" >"$VENV/race-constraints.txt"
    "$VENV/bin/python" -m pip install --quiet --upgrade pip ||
        die "could not upgrade pip in $VENV (is PyPI reachable?)"
    # One package at a time, so that a failure names the package; the constraints keep every
    # dependency at its pinned version.
    for pin in "${PINS[@]}"; do
        log "pip install $pin"
        "$VENV/bin/python" -m pip install --quiet -c "$VENV/race-constraints.txt" "$pin" ||
            die "pip could not install $pin into $VENV (see pip's message above). If pip found \
no wheel for $("$VENV/bin/python" --version 2>&1), use Python 3.11 to 3.13, e.g. \
PYTHON=python3.11 RACE_VENV=target/race-venv-311 $0"
    done
    "$VENV/bin/python" -c "import tamaas, ContactMechanics, SurfaceTopography" ||
        die "the packages installed but do not import (see the traceback above)"
    echo "$pins" >"$stamp"
fi

# --- 2. asperity example -------------------------------------------------------------------------
log "building the race example (release)"
cargo build --release --quiet -p asperity-numerics --example race ||
    die "cargo could not build the example race of asperity-numerics"
target_dir=$(cargo metadata --format-version 1 --no-deps |
    "$VENV/bin/python" -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
asperity="$target_dir/release/examples/race"
[[ -x "$asperity" ]] || die "the built example is not at $asperity"

# --- 2b. the Python package, for --in-process -------------------------------------------------
for arg in "$@"; do
    if [[ "$arg" == "--in-process" ]]; then
        log "building the asperity wheel (release) and installing it into $VENV"
        "$VENV/bin/python" -m pip install --quiet "maturin>=1.7,<2" ||
            die "pip could not install maturin into $VENV"
        rm -rf "$target_dir/wheels-race"
        "$VENV/bin/maturin" build --release --quiet --manifest-path python/Cargo.toml \
            --interpreter "$VENV/bin/python" --out "$target_dir/wheels-race" ||
            die "maturin could not build the asperity wheel"
        "$VENV/bin/python" -m pip install --quiet --force-reinstall --no-deps \
            "$target_dir"/wheels-race/asperity-*.whl ||
            die "pip could not install the asperity wheel into $VENV"
    fi
done

# --- 3. the race, on one core --------------------------------------------------------------------
export RAYON_NUM_THREADS=1 OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1
pin=()
if command -v taskset >/dev/null && taskset -c 0 true 2>/dev/null; then
    pin=(taskset -c 0)
else
    log "taskset is not available: the solvers run single-threaded but are not pinned to a core"
fi

cd "$caller"
"${pin[@]}" "$VENV/bin/python" "$root/scripts/race_peers.py" \
    --asperity "$asperity" \
    --asperity-version "$(git -C "$root" describe --always --dirty 2>/dev/null || echo unknown)" \
    --rustc "$(rustc --version)" \
    --workdir "$root/target/race" \
    "$@"
