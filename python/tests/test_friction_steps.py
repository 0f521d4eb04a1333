"""Friction at every load step: ``contact(..., fields="all")`` gives each step's maps, and
``per_spot_friction``/``per_summit_friction`` with ``step=i`` equal row ``i`` of the study's
``friction_curve``."""

import polars as pl
import pytest

import asperity
from conftest import CONTACT_INPUTS as C
from conftest import CONTACT_STUDY, run_cli

RIDGES = "  ridges:\n    friction:\n      method: per_summit\n      contact: squeeze\n      lower_material: s235jr\n"


def test_every_step_from_python_equals_the_study_curve(asperity_bin, tmp_path):
    study = tmp_path / "steps.yaml"
    study.write_text(CONTACT_STUDY.replace("outputs:", RIDGES + "outputs:"))
    cli = run_cli(asperity_bin, "run", str(study), "--out", "out", "--cache", "cache", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    friction = pl.read_parquet(tmp_path / "out" / "friction.parquet")
    curve = pl.read_parquet(tmp_path / "out" / "friction_curve.parquet")
    contacts = pl.read_parquet(tmp_path / "out" / "contacts.parquet")
    surfaces = pl.read_parquet(tmp_path / "out" / "surfaces.parquet")
    t = asperity.synthetic_surface(
        C["grid"], C["size"], sq=C["sq"], hurst=C["hurst"], correlation_length=C["correlation_length"], seed=3
    )
    c = asperity.contact(t, nominal_pressures=C["pressures"], lower_material=C["material"], tolerance=C["tolerance"], fields="all")
    final = asperity.contact(t, nominal_pressures=C["pressures"], lower_material=C["material"], tolerance=C["tolerance"])
    assert [s["nominal_pressure_Pa"] for s in c["steps"]] == C["pressures"]
    assert "steps" not in final
    # The final step's maps are the default ones, bit for bit.
    for name in ("pressure", "gap", "deformation_lower", "plastic_penetration"):
        assert (c["steps"][-1][name] == c[name]).all() and (c[name] == final[name]).all(), name
    contact_key = contacts.filter(pl.col("lower_key") == surfaces.filter(pl.col("seed") == 3)["key"][0])["key"][0]
    for method, call in (
        ("per_spot", lambda **k: asperity.per_spot_friction(c, t, model="full_stick", material=C["material"], **k)),
        ("per_summit", lambda **k: asperity.per_summit_friction(c, t, model="kogut_etsion", material=C["material"], **k)),
    ):
        key = friction.filter((pl.col("contact_key") == contact_key) & (pl.col("method") == method))["key"][0]
        rows = curve.filter(pl.col("key") == key).sort("step")
        assert rows["step"].to_list() == [0, 1]
        assert rows["nominal_pressure_Pa"].to_list() == C["pressures"]
        for step in (0, 1):
            ours = call(step=step)
            assert ours["mu_s_computed"] == pytest.approx(rows["mu_s_computed"][step], rel=1e-12), (method, step)
            assert ours["mu_s"] == pytest.approx(rows["mu_s"][step], rel=1e-12, abs=0.0), (method, step)
            # A step's dict as the result is the same.
            if method == "per_spot":
                assert asperity.per_spot_friction(c["steps"][step], t, model="full_stick", material=C["material"]) == ours
        assert call(step=-1) == call()
        # Each step is its own solution: the contact load grows with the step.
        assert rows["normal_load_N"][0] < rows["normal_load_N"][1]


def test_step_needs_every_steps_maps():
    t = asperity.synthetic_surface(32, 64e-6, sq=0.1e-6, hurst=0.8, correlation_length=20e-6)
    c = asperity.contact(t, nominal_pressures=[5e6, 20e6], lower_material="s235jr")
    with pytest.raises(ValueError, match="fields='all'"):
        asperity.per_spot_friction(c, t, model="full_stick", material="s235jr", step=0)
    every = asperity.contact(t, nominal_pressures=[5e6, 20e6], lower_material="s235jr", fields="all")
    with pytest.raises(ValueError, match="step: 2 is out of range"):
        asperity.per_summit_friction(every, t, material="s235jr", step=2)
    with pytest.raises(TypeError, match="step"):
        asperity.per_summit_friction(every, t, material="s235jr", step=1.0)
    with pytest.raises(ValueError, match="fields: 'some'"):
        asperity.contact(t, nominal_pressures=[5e6], lower_material="s235jr", fields="some")
