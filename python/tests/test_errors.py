"""Every argument of every public function: a wrong type, a wrong length, a value out of range or
in the wrong unit raises TypeError or ValueError whose message names the parameter, the value
given and the expected unit or range. A test fails naming any public parameter without a case."""

import inspect
import warnings
from pathlib import Path

import numpy as np
import pytest

import asperity

REPO = Path(__file__).resolve().parents[2]
SDF = str(REPO / "tests" / "data" / "sdf-1.sdf")
Z = np.random.default_rng(1).normal(size=(32, 32)) * 1e-6
T = asperity.Topography(Z, 1e-6)
SYNTHETIC = asperity.synthetic_surface(64, 1e-4, sq=1e-6, hurst=0.8, correlation_length=2e-5)
with warnings.catch_warnings():
    warnings.simplefilter("ignore", asperity.PlausibilityWarning)
    C = asperity.contact(T, nominal_pressures=1e6, lower_material="s235jr")
STUDY = "/no/such/study.yaml"

# The call each case starts from: a valid call (or, for the studies, one that fails only at the
# file), whose argument `parameter` the case replaces.
BASE = {
    "run": dict(study=STUDY),
    "plan": dict(study=STUDY),
    "validate": dict(study=STUDY),
    "Topography": dict(heights=Z, dx=1e-6),
    "Topography.statistics": dict(),
    "read_topography": dict(path=SDF),
    "read_line_scan": dict(path=SDF),
    "topography_format": dict(path=SDF),
    "surface_statistics": dict(heights=Z, dx=1e-6),
    "remove_form": dict(heights=Z, dx=1e-6),
    "gaussian_filter": dict(heights=Z, dx=1e-6, kind="low", cutoff=4e-6),
    "fill_missing": dict(heights=Z, dx=1e-6),
    "synthetic_surface": dict(grid=16, size=1e-4, sq=1e-6, hurst=0.8, correlation_length=2e-5),
    "synthetic_twin": dict(measured=[SYNTHETIC], sq=1e-6, grid=16, size=1e-4),
    "material": dict(name="s235jr"),
    "contact": dict(lower=Z, dx=1e-6, nominal_pressures=1e6, lower_material="s235jr"),
    "friction_laws": dict(),
    "static_friction": dict(model="full_stick", nominal_pressures=1e6, nominal_area=1e-6, material="s235jr", summits=(3e-7, 5e-5, 5e9)),
    "per_spot_friction": dict(result=C, composite_height=Z, dx=1e-6, model="full_stick", material="s235jr"),
    "per_summit_friction": dict(result=C, composite_height=Z, dx=1e-6, material="s235jr"),
}

# Public callables whose arguments need no case, with the reason.
EXEMPT = {
    "RunResult": "a record run() fills, not called by users",
    "LineScan": "a record read_line_scan() fills, not called by users",
    "StudyError": "an exception raised by the package",
    "PlausibilityWarning": "a warning raised by the package",
}

# (function, parameter, value, error, fragments the message must hold: the parameter, the value
# as given, and the expected unit or range)
CASES = [
    ("run", "study", 42, TypeError, ["study", "42", "path"]),
    ("run", "set", 42, TypeError, ["set", "42", "name=value"]),
    ("run", "out", 3.5, TypeError, ["out", "3.5", "path"]),
    ("run", "cache", 3.5, TypeError, ["cache", "3.5", "path"]),
    ("run", "jobs", 0, ValueError, ["jobs", "0", ">= 1"]),
    ("run", "jobs", 1.5, TypeError, ["jobs", "1.5", "worker threads"]),
    ("run", "memory_mib", -1, ValueError, ["memory_mib", "-1", ">= 1"]),
    ("run", "progress", 3, TypeError, ["progress", "3", "callable"]),
    ("run", "force", "yes", TypeError, ["force", "'yes'", "True or False"]),
    ("plan", "study", None, TypeError, ["study", "None", "path"]),
    ("plan", "set", {1: 2}, TypeError, ["set", "[1]", "names"]),
    ("plan", "cache", 1, TypeError, ["cache", "1", "path"]),
    ("validate", "study", b"x.yaml", TypeError, ["study", "b'x.yaml'", "path"]),
    ("validate", "set", [1], TypeError, ["set", "[1]", "name=value"]),
    ("Topography", "heights", [[1.0]], TypeError, ["heights", "[[1.0]]", "in m"]),
    ("Topography", "heights", np.zeros(4), ValueError, ["heights", "shape (4,)", "in m"]),
    ("Topography", "dx", "5 MPa", ValueError, ["dx", "5 MPa", "length"]),
    ("Topography", "dx", -1.0, ValueError, ["dx", "-1 m", "> 0 m"]),
    ("Topography", "dy", [1e-6], TypeError, ["dy", "[1e-06]", "length in m"]),
    ("Topography", "periodic", "yes", TypeError, ["periodic", "'yes'", "True or False"]),
    ("Topography", "metadata", {"a": 1}, TypeError, ["metadata", "{'a': 1}", "str to str"]),
    ("Topography.statistics", "periodic", 1, TypeError, ["periodic", "1 (int)", "True or False"]),
    ("read_topography", "path", 3, TypeError, ["path", "3", "path"]),
    ("read_topography", "pixel_size", -1e-6, ValueError, ["pixel_size", "-1e-06 m", "> 0 m"]),
    ("read_topography", "pixel_size", (1e-6, 1e-6, 1e-6), ValueError, ["pixel_size", "3 values", "(x, y) in m"]),
    ("read_topography", "size", "1 MPa", ValueError, ["size", "1 MPa", "length"]),
    ("read_topography", "override_file_spacing", "no", TypeError, ["override_file_spacing", "'no'", "True or False"]),
    ("read_topography", "channel", 3, TypeError, ["channel", "3", "channel name"]),
    ("read_topography", "channel", "no such channel", OSError, ["channel", "no such channel", "holds `height`"]),
    ("read_topography", "height_unit", "um", ValueError, ["height_unit", "states its own height unit", "remove"]),
    ("read_topography", "height_unit", "5 Pa", ValueError, ["height_unit", "5 Pa", "length"]),
    ("read_line_scan", "path", SDF, ValueError, ["path", "sdf-1.sdf", "read_topography"]),
    ("read_line_scan", "pixel_size", -1.0, ValueError, ["pixel_size", "-1 m", "> 0 m"]),
    ("read_line_scan", "size", [], ValueError, ["size", "0 values", "in m"]),
    ("read_line_scan", "override_file_spacing", 1, TypeError, ["override_file_spacing", "1 (int)", "True or False"]),
    ("read_line_scan", "channel", 1.0, TypeError, ["channel", "1.0", "channel name"]),
    ("read_line_scan", "height_unit", -1.0, ValueError, ["height_unit", "-1 m", "> 0 m"]),
    ("topography_format", "path", 1, TypeError, ["path", "1 (int)", "path"]),
    ("surface_statistics", "heights", [[1.0, 2.0]], TypeError, ["heights", "[[1.0, 2.0]]", "in m"]),
    ("surface_statistics", "heights", np.array([["a", "b"]]), TypeError, ["heights", "dtype <U1", "in m"]),
    ("surface_statistics", "dx", "1 um um", ValueError, ["dx", "1 um um", "unit"]),
    ("surface_statistics", "dx", float("nan"), ValueError, ["dx", "nan m", "> 0 m"]),
    ("surface_statistics", "dy", "3 N", ValueError, ["dy", "3 N", "length"]),
    ("surface_statistics", "periodic", "no", TypeError, ["periodic", "'no'", "True or False"]),
    ("remove_form", "heights", "z", TypeError, ["heights", "'z'", "in m"]),
    ("remove_form", "dx", (1e-6,), TypeError, ["dx", "(1e-06,)", "length in m"]),
    ("remove_form", "dy", 0, ValueError, ["dy", "0 m", "> 0 m"]),
    ("remove_form", "degree", -1, ValueError, ["degree", "-1", ">= 0"]),
    ("remove_form", "degree", 1.5, TypeError, ["degree", "1.5", "polynomial degree"]),
    ("gaussian_filter", "heights", Z[0], ValueError, ["heights", "shape (32,)", "in m"]),
    ("gaussian_filter", "dx", "-1 um", ValueError, ["dx", "-1 um", "> 0 m"]),
    ("gaussian_filter", "dy", "x", ValueError, ["dy", "'x'", "quantity"]),
    ("gaussian_filter", "kind", "median", ValueError, ["kind", "'median'", "'low', 'high', 'band'"]),
    ("gaussian_filter", "kind", 3, TypeError, ["kind", "3", "'low'"]),
    ("gaussian_filter", "cutoff", "4 GPa", ValueError, ["cutoff", "4 GPa", "length"]),
    ("gaussian_filter", "long_cutoff", -1.0, ValueError, ["long_cutoff", "-1 m", "> 0 m"]),
    ("fill_missing", "heights", None, TypeError, ["heights", "None", "in m"]),
    ("fill_missing", "dx", [], TypeError, ["dx", "[]", "length in m"]),
    ("fill_missing", "dy", -2e-6, ValueError, ["dy", "-2e-06 m", "> 0 m"]),
    ("synthetic_surface", "grid", 64.0, TypeError, ["grid", "64.0 (float)", "integers >= 2"]),
    ("synthetic_surface", "grid", (8, 8, 8), ValueError, ["grid", "3 values", "(nx, ny)"]),
    ("synthetic_surface", "grid", 1, ValueError, ["grid", "1", ">= 2"]),
    ("synthetic_surface", "size", "1 MPa", ValueError, ["size", "1 MPa", "length"]),
    ("synthetic_surface", "size", (1e-4,), ValueError, ["size", "1 values", "(x, y) in m"]),
    ("synthetic_surface", "sq", 0.0, ValueError, ["sq", "0 m", "> 0 m"]),
    ("synthetic_surface", "hurst", 1.5, ValueError, ["hurst", "1.5", "(0, 1]"]),
    ("synthetic_surface", "hurst", "0.8 m", ValueError, ["hurst", "0.8 m", "dimensionless"]),
    ("synthetic_surface", "correlation_length", [2e-5], TypeError, ["correlation_length", "[2e-05]", "length in m"]),
    ("synthetic_surface", "seed", -1, ValueError, ["seed", "-1", ">= 0"]),
    ("synthetic_surface", "short_wavelength_cutoff", -1.0, ValueError, ["short_wavelength_cutoff", "-1 m", "> 0 m"]),
    ("synthetic_surface", "anisotropy", 4, TypeError, ["anisotropy", "4 (int)", "aspect ratio"]),
    ("synthetic_surface", "anisotropy", (4, "30 m"), ValueError, ["anisotropy[1]", "30 m", "angle"]),
    ("synthetic_twin", "measured", T, TypeError, ["measured", "Topography(", "list"]),
    ("synthetic_twin", "measured", [Z], TypeError, ["measured[0]", "array(", "(heights, dx, dy)"]),
    ("synthetic_twin", "sq", "1 Pa", ValueError, ["sq", "1 Pa", "length"]),
    ("synthetic_twin", "grid", "16", TypeError, ["grid", "'16'", "integers >= 2"]),
    ("synthetic_twin", "size", -1e-4, ValueError, ["size", "-0.0001 m", "> 0 m"]),
    ("synthetic_twin", "seed", "1", TypeError, ["seed", "'1'", ">= 0"]),
    ("synthetic_twin", "short_wavelength_cutoff", 0.0, ValueError, ["short_wavelength_cutoff", "0 m", "> 0 m"]),
    ("synthetic_twin", "threshold", 1.5, ValueError, ["threshold", "1.5", "(0, 1)"]),
    ("synthetic_twin", "spectrum", "fitted", ValueError, ["spectrum", "'fitted'", "'measured'"]),
    ("synthetic_twin", "extrapolation", "flat", ValueError, ["extrapolation", "'flat'", "'power_law'"]),
    ("material", "name", 3, TypeError, ["name", "3", "material name"]),
    ("material", "name", "unobtainium", ValueError, ["material", "unobtainium", "s235jr"]),
    ("contact", "lower", [[0.0]], TypeError, ["lower", "[[0.0]]", "in m"]),
    ("contact", "dx", "1 N", ValueError, ["dx", "1 N", "length"]),
    ("contact", "dy", -1.0, ValueError, ["dy", "-1 m", "> 0 m"]),
    ("contact", "nominal_pressures", [], ValueError, ["nominal_pressures", "empty", "Pa"]),
    ("contact", "nominal_pressures", "5 um", ValueError, ["nominal_pressures[0]", "5 um", "pressure"]),
    ("contact", "nominal_pressures", [2e6, 1e6], ValueError, ["nominal_pressures[1]", "1e6 Pa", "ascend"]),
    ("contact", "nominal_pressures", np.ones((2, 2)), ValueError, ["nominal_pressures", "shape (2, 2)", "1-D"]),
    ("contact", "lower_material", 3, TypeError, ["lower_material", "3", "youngs_modulus: Pa"]),
    ("contact", "lower_material", {"youngs_modulus": 2e11, "poisson_ratio": 0.7}, ValueError, ["lower_material.poisson_ratio", "0.7", "[0, 0.5]"]),
    ("contact", "lower_material", {"E": 2e11}, ValueError, ["lower_material", "'E'", "youngs_modulus"]),
    ("contact", "lower_material", {"youngs_modulus": "210 m", "poisson_ratio": 0.3}, ValueError, ["lower_material.youngs_modulus", "210 m", "pressure"]),
    ("contact", "upper", Z[:8], ValueError, ["upper", "(8, 32)", "(32, 32)"]),
    ("contact", "upper_material", {"poisson_ratio": 0.3}, ValueError, ["upper_material", "youngs_modulus", "Pa"]),
    ("contact", "flow_pressure", "2 GPa m", ValueError, ["flow_pressure", "2 GPa m", "unit"]),
    ("contact", "periodic", None, TypeError, ["periodic", "None", "True or False"]),
    ("contact", "tolerance", 2.0, ValueError, ["tolerance", "2", "1"]),
    ("contact", "fields", "some", ValueError, ["fields", "'some'", "'all'"]),
    ("contact", "tolerance", "1e-6 m", ValueError, ["tolerance", "1e-6 m", "dimensionless"]),
    ("static_friction", "model", 3, TypeError, ["model", "3", "kogut_etsion"]),
    ("static_friction", "model", "coulomb", ValueError, ["model", "coulomb", "kogut_etsion"]),
    ("static_friction", "nominal_pressures", -1.0, ValueError, ["nominal_pressures[0]", "-1 Pa", "> 0 Pa"]),
    ("static_friction", "nominal_pressures", 5e9, ValueError, ["nominal_pressures[0]", "5e9 Pa", "H ="]),
    ("static_friction", "nominal_area", "1 mm", ValueError, ["nominal_area", "1 mm", "area"]),
    ("static_friction", "material", 0.3, TypeError, ["material", "0.3", "youngs_modulus: Pa"]),
    ("static_friction", "composite_modulus", 2e11, ValueError, ["material", "composite_modulus", "not both"]),
    ("static_friction", "hardness", 2e9, ValueError, ["material", "hardness", "not both"]),
    ("static_friction", "poisson_ratio", 0.3, ValueError, ["material", "poisson_ratio", "not both"]),
    ("static_friction", "moments", (1e-12, 1e-2), ValueError, ["moments", "2 value(s)", "m0 in m^2, m2 in 1, m4 in m^-2"]),
    ("static_friction", "moments", "m", TypeError, ["moments", "'m'", "m0 in m^2"]),
    ("static_friction", "summits", (3e-7, -5e-5, 5e9), ValueError, ["summits", "radius", "-5e-05 m"]),
    ("static_friction", "surface", Z, TypeError, ["surface", "array(", "Topography"]),
    ("static_friction", "adhesion_energy", "1 MPa", ValueError, ["adhesion_energy", "1 MPa", "surface energy"]),
    ("static_friction", "adhesion_energy", -0.5, ValueError, ["adhesion_energy", "-0.5 N/m", ">= 0 N/m"]),
    ("static_friction", "equilibrium_distance", 0.0, ValueError, ["equilibrium_distance", "0 m", "> 0 m"]),
    ("static_friction", "parameters", {"b": 2}, ValueError, ["parameters.b", "2", "(0, 1)"]),
    ("static_friction", "parameters", {"c": 1.0}, ValueError, ["parameters", "'c'", "a, b"]),
    ("static_friction", "parameters", {"a": [1]}, TypeError, ["parameters.a", "[1]", "number (SI)"]),
    ("static_friction", "parameters", ["a"], TypeError, ["parameters", "['a']", "mapping"]),
    ("static_friction", "yield_strength", "1 m", ValueError, ["yield_strength", "1 m", "pressure"]),
    ("static_friction", "shear_strength", -1.0, ValueError, ["shear_strength", "-1 Pa", "> 0 Pa"]),
    ("per_spot_friction", "result", 3, TypeError, ["result", "3", "asperity.contact"]),
    ("per_spot_friction", "step", 0, ValueError, ["step", "0", "fields='all'"]),
    ("per_summit_friction", "step", 5, ValueError, ["step", "5", "fields='all'"]),
    ("per_spot_friction", "result", {"pressure": Z}, TypeError, ["result", "'gap'", "asperity.contact"]),
    ("per_spot_friction", "composite_height", Z[:8], ValueError, ["composite_height", "(8, 32)", "shape"]),
    ("per_spot_friction", "upper_material", {"youngs_modulus": 2e11, "poisson_ratio": 0.3}, ValueError, ["upper_material", "hardness", "Pa"]),
    ("per_spot_friction", "upper_height", Z, ValueError, ["upper_height", "upper_material"]),
    ("per_spot_friction", "dx", "-2 um", ValueError, ["dx", "-2 um", "> 0 m"]),
    ("per_spot_friction", "dy", 0.0, ValueError, ["dy", "0 m", "> 0 m"]),
    ("per_spot_friction", "model", "coulomb", ValueError, ["model", "coulomb", "full_stick"]),
    ("per_spot_friction", "material", {"youngs_modulus": 2e11, "poisson_ratio": 0.3}, ValueError, ["material", "hardness", "Pa"]),
    ("per_spot_friction", "composite_modulus", "1 MPa", ValueError, ["material", "composite_modulus", "not both"]),
    ("per_spot_friction", "hardness", 1.0, ValueError, ["material", "hardness", "not both"]),
    ("per_spot_friction", "poisson_ratio", 0.3, ValueError, ["material", "poisson_ratio", "not both"]),
    ("per_spot_friction", "periodic", "True", TypeError, ["periodic", "'True'", "True or False"]),
    ("per_spot_friction", "connectivity", 6, ValueError, ["connectivity", "6", "4 or 8"]),
    ("per_spot_friction", "connectivity", 4.0, TypeError, ["connectivity", "4.0", "4 or 8"]),
    ("per_spot_friction", "adhesion_energy", "1 m", ValueError, ["adhesion_energy", "1 m", "surface energy"]),
    ("per_spot_friction", "equilibrium_distance", -1.0, ValueError, ["equilibrium_distance", "-1 m", "> 0 m"]),
    ("per_spot_friction", "parameters", {"a": -1.0}, ValueError, ["parameters.a", "-1", "> 0"]),
    ("per_spot_friction", "yield_strength", [1], TypeError, ["yield_strength", "[1]", "pressure in Pa"]),
    ("per_spot_friction", "shear_strength", "1 um", ValueError, ["shear_strength", "1 um", "pressure"]),
    ("per_summit_friction", "result", [], TypeError, ["result", "[]", "asperity.contact"]),
    ("per_summit_friction", "composite_height", np.zeros((8, 8)), ValueError, ["pressure", "(32, 32)", "(8, 8)"]),
    ("per_summit_friction", "dx", "1 MPa", ValueError, ["dx", "1 MPa", "length"]),
    ("per_summit_friction", "dy", -1.0, ValueError, ["dy", "-1 m", "> 0 m"]),
    ("per_summit_friction", "model", "junction_shear", ValueError, ["model", "junction_shear", "single-asperity"]),
    ("per_summit_friction", "material", "unobtainium", ValueError, ["material", "unobtainium", "s235jr"]),
    ("per_summit_friction", "composite_modulus", 1.0, ValueError, ["material", "composite_modulus", "not both"]),
    ("per_summit_friction", "hardness", 1.0, ValueError, ["material", "hardness", "not both"]),
    ("per_summit_friction", "poisson_ratio", 1.0, ValueError, ["material", "poisson_ratio", "not both"]),
    ("per_summit_friction", "periodic", 0, TypeError, ["periodic", "0 (int)", "True or False"]),
    ("per_summit_friction", "adhesion_energy", [0.5], TypeError, ["adhesion_energy", "[0.5]", "surface energy in N/m"]),
    ("per_summit_friction", "equilibrium_distance", "0.4 MPa", ValueError, ["equilibrium_distance", "0.4 MPa", "length"]),
    ("per_summit_friction", "parameters", {"static_friction_form": "cubic"}, ValueError, ["parameters.static_friction_form", "cubic", "literal, clipped"]),
    ("per_summit_friction", "yield_strength", 0.0, ValueError, ["yield_strength", "0 Pa", "> 0 Pa"]),
]


def target(name):
    if name == "Topography.statistics":
        return T.statistics
    return getattr(asperity, name)


# A roughness given in a case replaces the base call's (static_friction takes exactly one).
ROUGHNESS = ("moments", "summits", "surface")


def call(function, parameter, value):
    kwargs = dict(BASE[function])
    if parameter in ROUGHNESS:
        kwargs = {k: v for k, v in kwargs.items() if k not in ROUGHNESS}
    kwargs[parameter] = value
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", asperity.PlausibilityWarning)
        return target(function)(**kwargs)


@pytest.mark.parametrize(
    "function, parameter, value, error, fragments", CASES, ids=[f"{c[0]}-{c[1]}-{i}" for i, c in enumerate(CASES)]
)
def test_a_bad_argument_is_named_with_its_value_and_unit(function, parameter, value, error, fragments):
    with pytest.raises(error) as caught:
        call(function, parameter, value)
    message = str(caught.value)
    for fragment in fragments:
        assert fragment in message, (fragment, message)


def test_every_base_call_is_valid():
    """The cases start from calls that succeed (the studies' fail only at their file)."""
    for function in BASE:
        if function in ("run", "plan", "validate"):
            with pytest.raises(asperity.StudyError, match="no/such/study"):
                target(function)(**BASE[function])
        elif function != "read_line_scan":  # the fixtures are areal maps: its base is an error case
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", asperity.PlausibilityWarning)
                target(function)(**BASE[function])


def public_parameters():
    """(function, parameter) of every public callable of asperity and of Topography's methods."""
    out = []
    for name in asperity.__all__:
        obj = getattr(asperity, name)
        if name in EXEMPT or (inspect.isclass(obj) and name != "Topography") or not callable(obj):
            continue
        for p in inspect.signature(obj).parameters.values():
            if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
                out.append((name, p.name))
    for method in ("statistics",):
        for p in inspect.signature(getattr(asperity.Topography, method)).parameters.values():
            if p.name != "self":
                out.append((f"Topography.{method}", p.name))
    return out


def test_every_public_parameter_has_a_case():
    covered = {(c[0], c[1]) for c in CASES}
    missing = [f"{f}({p})" for f, p in public_parameters() if (f, p) not in covered]
    assert not missing, f"parameters without a bad-argument case: {', '.join(missing)}"
    exempt_classes = [n for n in asperity.__all__ if inspect.isclass(getattr(asperity, n)) and n not in EXEMPT and n != "Topography"]
    for name in exempt_classes:
        assert hasattr(getattr(asperity, name), "__required_keys__"), f"{name}: a public class without cases or an exemption"


def test_an_angle_takes_its_unit_and_its_range_is_shown_in_rad():
    base = dict(model="ploughing", material="s235jr")
    degrees = asperity.per_spot_friction(C, T, parameters={"sliding_direction": "90 deg"}, **base)
    radians = asperity.per_spot_friction(C, T, parameters={"sliding_direction": np.pi / 2}, **base)
    assert degrees == radians
    with pytest.raises(ValueError) as caught:
        asperity.per_spot_friction(C, T, parameters={"sliding_direction": "400 deg"}, **base)
    message = str(caught.value)
    assert "parameters.sliding_direction: '400 deg' (6.981317007977318 rad) is out of range" in message, message
    assert message.endswith("6.283185307179586] rad"), message
    with pytest.raises(ValueError, match="expected a angle|expected an angle"):
        asperity.per_spot_friction(C, T, parameters={"sliding_direction": "90 um"}, **base)
