"""Bad input raises TypeError, ValueError or OSError naming the parameter; it never crashes the
interpreter (each case also runs in a child interpreter, whose exit code shows a crash)."""

import subprocess
import sys

import numpy as np
import pytest

import asperity

Z = np.random.default_rng(1).normal(size=(16, 16)) * 1e-6

CASES = [
    (TypeError, "heights", lambda: asperity.surface_statistics([[1.0, 2.0]], 1e-6)),
    (TypeError, "heights", lambda: asperity.surface_statistics(np.array([["a", "b"]]), 1e-6)),
    (ValueError, "heights", lambda: asperity.surface_statistics(np.zeros(5), 1e-6)),
    (ValueError, "heights", lambda: asperity.surface_statistics(np.zeros((1, 1)), 1e-6)),
    (ValueError, "heights", lambda: asperity.surface_statistics(np.full((4, 4), np.inf), 1e-6)),
    (ValueError, "dx", lambda: asperity.surface_statistics(Z, -1.0)),
    (ValueError, "dy", lambda: asperity.surface_statistics(Z, 1e-6, float("nan"))),
    (ValueError, "dx", lambda: asperity.surface_statistics(Z, "1 MPa")),
    (ValueError, "kind", lambda: asperity.gaussian_filter(Z, 1e-6, kind="median", cutoff=1e-5)),
    (ValueError, "long_cutoff", lambda: asperity.gaussian_filter(Z, 1e-6, kind="band", cutoff=1e-5)),
    (ValueError, "degree", lambda: asperity.remove_form(Z, 1e-6, degree=-1)),
    (ValueError, "hurst", lambda: asperity.synthetic_surface(16, 1e-4, sq=1e-6, hurst=1.5, correlation_length=1e-5)),
    (ValueError, "grid", lambda: asperity.synthetic_surface(1, 1e-4, sq=1e-6, hurst=0.5, correlation_length=1e-5)),
    (ValueError, "sq", lambda: asperity.synthetic_surface(16, 1e-4, sq=0.0, hurst=0.5, correlation_length=1e-5)),
    (ValueError, "material", lambda: asperity.contact(Z, 1e-6, nominal_pressures=1e6, lower_material="unobtainium")),
    (ValueError, "poisson_ratio", lambda: asperity.contact(Z, 1e-6, nominal_pressures=1e6, lower_material={"youngs_modulus": 1e11, "poisson_ratio": 0.7})),
    (ValueError, "nominal_pressures[1]", lambda: asperity.contact(Z, 1e-6, nominal_pressures=[2e6, 1e6], lower_material="s235jr")),
    (ValueError, "nominal_pressures[0]", lambda: asperity.contact(Z, 1e-6, nominal_pressures=1e12, lower_material="s235jr")),
    (ValueError, "tolerance", lambda: asperity.contact(Z, 1e-6, nominal_pressures=1e6, lower_material="s235jr", tolerance=2.0)),
    (ValueError, "upper", lambda: asperity.contact(Z, 1e-6, upper=Z[:8], nominal_pressures=1e6, lower_material="s235jr", upper_material="s235jr")),
    (ValueError, "upper_material", lambda: asperity.contact(Z, 1e-6, nominal_pressures=1e6, lower_material="s235jr", upper_material="s235jr")),
    (OSError, "no-such-file", lambda: asperity.read_topography("/no-such-file.x3p")),
    (ValueError, "pixel_size", lambda: asperity.read_topography("/no-such-file.x3p", pixel_size=-1e-6)),
    (ValueError, "pixel_size", lambda: asperity.read_topography("/no-such-file.x3p", pixel_size=1e-6, size=1e-3)),
    (TypeError, "study", lambda: asperity.validate(42)),
    (ValueError, "jobs", lambda: asperity.run("/no/such/study.yaml", jobs=0)),
    (asperity.StudyError, "no/such/study", lambda: asperity.validate("/no/such/study.yaml")),
    (ValueError, "measured", lambda: asperity.synthetic_twin([], sq=1e-6, grid=16, size=1e-4)),
]


@pytest.mark.parametrize("error, names, call", CASES, ids=[f"{i}-{c[1]}" for i, c in enumerate(CASES)])
def test_bad_argument_raises_naming_the_parameter(error, names, call):
    with pytest.raises(error) as caught:
        call()
    assert names in str(caught.value)


@pytest.mark.parametrize("garbage", [b"", b"\x00" * 10, b"PK\x03\x04" + b"\xff" * 200, b"ZYGO" * 1000])
@pytest.mark.parametrize("suffix", [".x3p", ".dat", ".sur", ".plu", ".txt", ".npy", ".zon"])
def test_a_damaged_file_raises_oserror(tmp_path, garbage, suffix):
    path = tmp_path / f"damaged{suffix}"
    path.write_bytes(garbage)
    with pytest.raises((OSError, ValueError)):
        asperity.read_topography(path, pixel_size=1e-6)


def test_no_bad_case_crashes_a_child_interpreter():
    code = (
        "import sys; sys.path.insert(0, %r)\n"
        "import test_bad_input as t\n"
        "for error, names, call in t.CASES:\n"
        "    try:\n"
        "        call()\n"
        "    except error:\n"
        "        pass\n"
        "print('survived')\n"
    ) % str(__import__("pathlib").Path(__file__).parent)
    child = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert child.returncode == 0 and "survived" in child.stdout, child.stderr
