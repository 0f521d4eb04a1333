"""Units checked as a study checks them: each common unit mistake, which used to give a number
without a word (A/A₀ = 1, 0 iterations, a contact on one point), now raises a
PlausibilityWarning (possible but probably wrong) or a ValueError (outside the model), whose
sentence names the value and the likely mistake; a negative μ_s is never returned as `mu_s`."""

import warnings
from pathlib import Path

import numpy as np
import pytest

import asperity

REPO = Path(__file__).resolve().parents[2]
T = asperity.synthetic_surface(64, 64e-6, sq=0.5e-6, hurst=0.8, correlation_length=20e-6)
Z, DX = np.array(T.heights), T.dx


def sentences(call):
    """The PlausibilityWarnings `call` raises, and its result."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = call()
    return [str(w.message) for w in caught if issubclass(w.category, asperity.PlausibilityWarning)], result


def test_a_plausible_contact_raises_no_warning():
    said, c = sentences(lambda: asperity.contact(T, nominal_pressures=[5e6, 20e6], lower_material="s235jr"))
    assert said == [] and 0 < c["area_fraction"] < 0.1 and c["iterations"] > 0


def test_heights_in_um_with_dx_in_m():
    said, c = sentences(lambda: asperity.contact(Z * 1e6, DX, nominal_pressures=20e6, lower_material="s235jr"))
    assert any("steeper than an instrument can measure" in s for s in said), said
    assert any("exceeds the map's larger side" in s for s in said), said


def test_heights_in_m_with_dx_in_um():
    said, _ = sentences(lambda: asperity.surface_statistics(Z, DX * 1e6))
    assert any("flatter than any engineering surface" in s for s in said), said
    assert any("dx = 1 m is coarser than a millimetre" in s for s in said), said


def test_heights_and_dx_both_in_um():
    # The slope is right, so only the absolute scale shows the mistake.
    said, _ = sentences(lambda: asperity.contact(Z * 1e6, DX * 1e6, nominal_pressures=20e6, lower_material="s235jr"))
    assert any("coarser than a millimetre" in s for s in said), said


def test_a_spacing_converted_twice():
    said, _ = sentences(lambda: asperity.Topography(Z, DX * 1e-6).statistics())
    assert any("finer than a nanometre" in s for s in said), said


def test_a_modulus_in_gpa():
    steel = {"youngs_modulus": 210, "poisson_ratio": 0.3}
    with pytest.warns(asperity.PlausibilityWarning, match="youngs_modulus = 210 Pa is below 1 MPa"):
        with pytest.raises(ValueError, match=r"nominal_pressures\[0\]: 2e7 Pa is not below the composite modulus"):
            asperity.contact(T, nominal_pressures=20e6, lower_material=steel)
    # As a string with its unit it is what was meant.
    said, c = sentences(lambda: asperity.contact(T, nominal_pressures="20 MPa", lower_material={"youngs_modulus": "210 GPa", "poisson_ratio": 0.3}))
    assert said == [] and c["composite_modulus_Pa"] == pytest.approx(210e9 / (1 - 0.09))


def test_a_pressure_in_mpa_given_as_pa():
    said, c = sentences(lambda: asperity.contact(T, nominal_pressures=[5, 20], lower_material="s235jr"))
    assert c["iterations"] == 0 and c["area_fraction"] * 64 * 64 < 4
    assert any("covers 1 grid point(s)" in s and "MPa as a plain number" in s for s in said), said
    said, rows = sentences(lambda: asperity.static_friction(model="full_stick", surface=T, nominal_pressures=20, material="s235jr"))
    assert any("fewer than one" in s for s in said), said
    said, rows = sentences(lambda: asperity.static_friction(model="full_stick", surface=T, nominal_pressures="20 MPa", material="s235jr"))
    assert said == [] and rows[0]["contacts"] > 1


def test_a_hardness_in_gpa():
    soft = {"youngs_modulus": 210e9, "poisson_ratio": 0.3, "hardness": 2}
    with pytest.warns(asperity.PlausibilityWarning, match="hardness = 2 Pa is below 1 MPa"):
        with pytest.raises(ValueError, match="exceeds the flow pressure H = 2 Pa"):
            asperity.static_friction(model="full_stick", surface=T, nominal_pressures=20e6, material=soft)


def test_a_file_without_height_unit_is_flagged_unless_given(tmp_path):
    path = tmp_path / "heights.npy"
    np.save(path, Z * 1e6)  # an .npy stores neither spacing nor unit: these are µm
    said, t = sentences(lambda: asperity.read_topography(path, pixel_size="0.5 um"))
    assert t.height_unit_source == "assumed" and t.spacing_source == "given"
    assert any("stores no height unit" in s for s in said), said
    said, t_um = sentences(lambda: asperity.read_topography(path, pixel_size="0.5 um", height_unit="um"))
    assert t_um.height_unit_source == "given" and said == []
    assert np.array_equal(t_um.heights, Z * 1e6 * 1e-6)


def test_a_negative_mu_s_is_never_returned_as_mu_s():
    """KE 2004 as published (the registry's and a study's default form) goes negative at a high
    plasticity index: `mu_s` is 0 as in the tables, the model's value is in `mu_s_computed`."""
    rough = asperity.synthetic_surface(128, 0.5e-3, sq=0.4e-6, hurst=0.8, correlation_length=50e-6)
    (row,) = asperity.static_friction(model="kogut_etsion", surface=rough, nominal_pressures=5e6, material="s235jr")
    assert row["mu_s_computed"] < 0 and row["mu_s"] == 0.0 and row["mu_s_floored"]
    (clipped,) = asperity.static_friction(
        model="kogut_etsion", surface=rough, nominal_pressures=5e6, material="s235jr", parameters={"static_friction_form": "clipped"}
    )
    assert clipped["mu_s"] == clipped["mu_s_computed"] >= 0 and not clipped["mu_s_floored"]
    c = asperity.contact(rough, nominal_pressures=5e6, lower_material="s235jr")
    for result in (
        asperity.per_summit_friction(c, rough, material="s235jr"),
        asperity.per_spot_friction(c, rough, model="kogut_etsion", material="s235jr"),
    ):
        assert result["mu_s"] is not None and result["mu_s"] >= 0
        assert result["mu_s_floored"] == (result["mu_s_computed"] < 0)


def test_a_coarse_grid_and_a_steep_slope_are_flagged_as_a_study_flags_them():
    coarse = asperity.synthetic_surface(6, 6e-6, sq=0.05e-6, hurst=0.8, correlation_length=3e-6)
    said, _ = sentences(lambda: asperity.contact(coarse, nominal_pressures=20e6, lower_material="s235jr"))
    assert any("resolves no contact spot" in s for s in said), said
    steep = asperity.synthetic_surface(64, 64e-6, sq=3e-6, hurst=0.8, correlation_length=10e-6)
    said, _ = sentences(lambda: asperity.contact(steep, nominal_pressures=20e6, lower_material="s235jr"))
    assert any("beyond the small-slope assumption" in s for s in said), said


def test_warnings_become_errors_on_request():
    with warnings.catch_warnings():
        warnings.simplefilter("error", asperity.PlausibilityWarning)
        with pytest.raises(asperity.PlausibilityWarning, match="below 1 MPa"):
            asperity.contact(T, nominal_pressures=1e3, lower_material={"youngs_modulus": 5e5, "poisson_ratio": 0.3})
