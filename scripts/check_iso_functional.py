#!/usr/bin/env python3
"""Independent check of asperity's ISO 25178-2 functional and volume parameters against surfalize.

Creates a virtual environment (default /tmp/asperity-iso-check-venv), installs surfalize into it,
computes Sk, Spk, Svk, Smr1, Smr2, Sxp, Vmp, Vmc, Vvc, Vvv of real instrument files with surfalize
and with `asperity inspect`, and prints a Markdown table of both and their relative difference.
Not part of CI (it needs PyPI); the table of one run is in docs/iso-functional.md.

    python3 scripts/check_iso_functional.py [--asperity target/debug/asperity]
        [--data ../shared/data/topography] [--venv DIR] [FILE ...]

Files with missing points are skipped: surfalize refuses them, asperity leaves them out of the
curve. Both see the raw file: no levelling, no filtering.
"""

import argparse
import os
import re
import subprocess
import sys
import venv

DEFAULT_FILES = [
    "al3d/al3d-1.al3d",
    "plu/plu-1.plu",
    "sur/sur-2.sur",
    "sur/sur-3.sur",
    "sdf/sdf-1.sdf",
    "x3p/KautschukInfiniteFocus.x3p",
    "opd/opd-1.opd",
]

# (asperity's label in `inspect`, surfalize method, factor from surfalize's unit to asperity's)
PARAMETERS = [
    ("Sk", "Sk", 1e-6),
    ("Spk", "Spk", 1e-6),
    ("Svk", "Svk", 1e-6),
    ("Smr1", "Smr1", 1.0),
    ("Smr2", "Smr2", 1.0),
    ("Sxp", "Sxp", 1e-6),
    ("Vmp", "Vmp", 1e-6),
    ("Vmc", "Vmc", 1e-6),
    ("Vvc", "Vvc", 1e-6),
    ("Vvv", "Vvv", 1e-6),
]

# Runs inside the venv: prints `name value` lines (surfalize's units: µm, %, µm³/µm²).
SURFALIZE_PROBE = r"""
import sys
from surfalize import Surface
s = Surface.load(sys.argv[1])
if s.has_missing_points:
    print("MISSING")
    sys.exit(0)
for name in sys.argv[2:]:
    print(name, float(getattr(s, name)()))
"""


def python_in(venv_dir):
    return os.path.join(venv_dir, "bin", "python")


def ensure_venv(venv_dir):
    """The venv with surfalize, created and installed when missing."""
    if not os.path.exists(python_in(venv_dir)):
        venv.create(venv_dir, with_pip=True)
    check = subprocess.run(
        [python_in(venv_dir), "-c", "import surfalize"], capture_output=True
    )
    if check.returncode != 0:
        subprocess.run(
            [python_in(venv_dir), "-m", "pip", "install", "-q", "surfalize"], check=True
        )
    version = subprocess.run(
        [python_in(venv_dir), "-c", "import surfalize; print(surfalize.__version__)"],
        capture_output=True,
        text=True,
        check=True,
    )
    return version.stdout.strip()


def surfalize_values(venv_dir, path):
    names = [p[1] for p in PARAMETERS]
    out = subprocess.run(
        [python_in(venv_dir), "-c", SURFALIZE_PROBE, path, *names],
        capture_output=True,
        text=True,
    )
    if out.returncode != 0:
        return None, out.stderr.strip().splitlines()[-1] if out.stderr else "failed"
    if out.stdout.strip() == "MISSING":
        return None, "missing points (surfalize needs them filled)"
    return {k: float(v) for k, v in (line.split() for line in out.stdout.splitlines())}, ""


def asperity_values(binary, path):
    out = subprocess.run([binary, "inspect", path], capture_output=True, text=True)
    if out.returncode != 0:
        return None, out.stderr.strip()
    values = {}
    for label, _, _ in PARAMETERS:
        m = re.search(rf"^\s+{label}\s+=\s+(\S+)", out.stdout, re.MULTILINE)
        if m:
            values[label] = float(m.group(1))
    missing = re.search(r"^missing:\s+(\d+) of", out.stdout, re.MULTILINE)
    return values, missing.group(1) if missing else "?"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*")
    parser.add_argument("--asperity", default="target/debug/asperity")
    parser.add_argument("--data", default="../shared/data/topography")
    parser.add_argument("--venv", default="/tmp/asperity-iso-check-venv")
    args = parser.parse_args()
    version = ensure_venv(args.venv)
    files = args.files or [os.path.join(args.data, f) for f in DEFAULT_FILES]
    print(f"surfalize {version}; asperity: {args.asperity}\n")
    print("| file | parameter | asperity | surfalize | relative difference |")
    print("|---|---|---|---|---|")
    for path in files:
        name = os.path.relpath(path, args.data) if path.startswith(args.data) else path
        ours, missing = asperity_values(args.asperity, path)
        if ours is None:
            print(f"| {name} | — | asperity failed: {missing} | | |")
            continue
        theirs, why = surfalize_values(args.venv, path)
        if theirs is None:
            print(f"| {name} | — | skipped: {why} | | |")
            continue
        for label, method, factor in PARAMETERS:
            a = ours.get(label)
            b = theirs[method] * factor
            if label.startswith("Smr"):
                a_text, b_text = f"{a:.3f} %", f"{b:.3f} %"
            else:
                a_text, b_text = f"{a:.4e}", f"{b:.4e}"
            diff = abs(a - b) / abs(b) if b else float("nan")
            print(f"| {name} | {label} | {a_text} | {b_text} | {100 * diff:.2f} % |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
