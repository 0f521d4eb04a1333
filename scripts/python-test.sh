#!/usr/bin/env bash
# The Python package's tests: a fresh virtual environment, maturin, pytest, numpy, polars, mypy
# and matplotlib from PyPI, the wheel built from python/ in the dev profile into the workspace's
# target folder (so the crates `cargo test` built are reused, not rebuilt in release), installed,
# then pytest (which also runs the documentation's code blocks and `mypy --strict` on the package
# and on those blocks).
# Needs only the Rust toolchain and python3 (>= 3.9, with venv). The contact and study tests
# compare against the `asperity` binary, built here if `cargo test` has not built it.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
venv=${ASPERITY_PY_VENV:-$root/target/python-venv}
python=${PYTHON:-python3}
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    "maturin>=1.7,<2" "pytest>=7" numpy polars "mypy>=1.8" "matplotlib>=3.8"
cargo build --bin asperity
rm -rf "$root/target/wheels/asperity-"*.whl
"$venv/bin/maturin" build --manifest-path python/Cargo.toml --profile dev \
    --interpreter "$venv/bin/python" --out "$root/target/wheels" --quiet
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check --force-reinstall \
    --no-deps "$root"/target/wheels/asperity-*.whl
ASPERITY_BIN="$root/target/debug/asperity" "$venv/bin/python" -m pytest -q python/tests "$@"
