"""Shared fixtures: the `asperity` binary the results are compared with, the shared data folder,
and a study with a synthetic surface and a contact whose inputs the tests repeat in Python."""

import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]

# The study of the comparisons: one synthetic surface against a rigid flat, its contact at two
# load steps and its statistical friction, the parameters repeated by `CONTACT_INPUTS`.
CONTACT_STUDY = """\
study: py-contact
parameters:
  product:
    seed: [3, 4]
nodes:
  rough:
    surface:
      synthetic: {grid: [64, 48], size: [0.32 mm, 0.24 mm], sq: 0.8 um, hurst: 0.7,
                  correlation_length: 40 um, seed: "${seed}"}
  squeeze:
    contact:
      lower: rough
      lower_material: s235jr
      nominal_pressures: [5 MPa, 20 MPa]
      tolerance: 1e-8
      fields: true
  spots:
    friction:
      method: per_spot
      model: full_stick
      contact: squeeze
      lower_material: s235jr
  grip:
    friction:
      model: kogut_etsion
      lower: rough
      lower_material: s235jr
      nominal_pressures: [5 MPa, 20 MPa]
outputs: [surfaces, contacts, friction]
"""

CONTACT_INPUTS = dict(
    grid=(64, 48),
    size=(0.32e-3, 0.24e-3),
    sq=0.8e-6,
    hurst=0.7,
    correlation_length=40e-6,
    material="s235jr",
    pressures=[5e6, 20e6],
    tolerance=1e-8,
)


@pytest.fixture(scope="session")
def asperity_bin() -> Path:
    """The command line built from this checkout (scripts/python-test.sh sets ASPERITY_BIN)."""
    path = Path(os.environ.get("ASPERITY_BIN", REPO / "target" / "debug" / "asperity"))
    assert path.is_file(), f"{path}: build it with `cargo build --bin asperity`"
    return path


@pytest.fixture(scope="session")
def data_dir():
    """The shared topography folder; missing, the tests that need it fail under CI, else skip."""
    candidates = [os.environ.get("ASPERITY_TEST_DATA")] + [
        str(p / "shared" / "data" / "topography") for p in REPO.parents
    ]
    for c in candidates:
        if c and (Path(c) / "SOURCES.md").is_file():
            return Path(c)
    assert "CI" not in os.environ, "shared topography data not found (set ASPERITY_TEST_DATA)"
    pytest.skip("shared topography data not found")


def run_cli(binary: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([str(binary), *args], cwd=cwd, capture_output=True, text=True, timeout=600)


@pytest.fixture()
def contact_study(tmp_path: Path) -> Path:
    path = tmp_path / "py-contact.yaml"
    path.write_text(CONTACT_STUDY)
    return path
