"""Statistical μ_s from Python equals the study's friction node for the same surface and material."""

import polars as pl
import pytest

import asperity
from conftest import CONTACT_INPUTS as C
from conftest import run_cli


def test_static_friction_equals_the_cli_friction_node(asperity_bin, contact_study, tmp_path):
    cli = run_cli(asperity_bin, "run", str(contact_study), "--out", "out", "--cache", "cache", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    friction = pl.read_parquet(tmp_path / "out" / "friction.parquet")
    surfaces = pl.read_parquet(tmp_path / "out" / "surfaces.parquet")
    for seed in (3, 4):
        t = asperity.synthetic_surface(
            C["grid"], C["size"], sq=C["sq"], hurst=C["hurst"], correlation_length=C["correlation_length"], seed=seed
        )
        s = t.statistics()
        results = asperity.static_friction(
            model="kogut_etsion",
            nominal_pressures=C["pressures"],
            nominal_area=C["size"][0] * C["size"][1],
            material=C["material"],
            moments=(s["m0_m2"], s["m2"], s["m4_per_m2"]),
        )
        key = surfaces.filter(pl.col("seed") == seed)["key"][0]
        row = friction.filter(pl.col("lower_key") == key)
        assert len(row) == 1
        assert len(results) == 2
        # The node floors a negative μ_s (the literal KE 2004 polynomial) and keeps the model's
        # value, and so does the function.
        assert results[-1]["mu_s_computed"] == pytest.approx(row["mu_s_computed"][0], rel=1e-9)
        assert results[-1]["mu_s"] == pytest.approx(row["mu_s"][0], rel=1e-9, abs=0.0)
        assert results[-1]["mu_s_floored"] == row["mu_s_floored"][0]
        assert results[-1]["plasticity_index"] == pytest.approx(row["plasticity_index"][0], rel=1e-9)
        # The same from the Topography, whose size is the node's nominal area.
        assert asperity.static_friction(model="kogut_etsion", nominal_pressures=C["pressures"], material=C["material"], surface=t) == results


def test_explicit_summits_and_bad_models():
    steel = asperity.material("s235jr")
    base = dict(nominal_pressures=[1e6], nominal_area=1e-6, material=steel, summits=(0.3e-6, 50e-6, 5e9))
    for model in ("kogut_etsion", "chang_etsion_bogy", "full_stick"):
        (r,) = asperity.static_friction(model=model, **base)
        assert abs(r["mu_s"]) < 5 and r["normal_load_N"] > 0 and r["real_area_m2"] > 0, model
    (stick,) = asperity.static_friction(model="full_stick", **base)
    assert stick["mu_s"] > 0
    with pytest.raises(ValueError, match="model"):
        asperity.static_friction(model="coulomb", **base)
    with pytest.raises(ValueError, match="moments"):
        asperity.static_friction(model="full_stick", nominal_pressures=1e6, nominal_area=1e-6, material=steel)
    with pytest.raises(ValueError, match="nominal_area"):
        asperity.static_friction(model="full_stick", **{**base, "nominal_area": -1.0})


def test_per_spot_friction_equals_the_cli_per_spot_node(asperity_bin, contact_study, tmp_path):
    cli = run_cli(asperity_bin, "run", str(contact_study), "--out", "out", "--cache", "cache", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    friction = pl.read_parquet(tmp_path / "out" / "friction.parquet")
    contacts = pl.read_parquet(tmp_path / "out" / "contacts.parquet")
    surfaces = pl.read_parquet(tmp_path / "out" / "surfaces.parquet")
    t = asperity.synthetic_surface(
        C["grid"], C["size"], sq=C["sq"], hurst=C["hurst"], correlation_length=C["correlation_length"], seed=3
    )
    heights, dx, dy = t.heights, t.dx, t.dy
    c = asperity.contact(t, nominal_pressures=C["pressures"], lower_material=C["material"], tolerance=C["tolerance"])
    spots = asperity.per_spot_friction(c, t, model="full_stick", material=C["material"])
    assert asperity.per_spot_friction(c, heights, dx, dy, model="full_stick", material=C["material"]) == spots
    key = surfaces.filter(pl.col("seed") == 3)["key"][0]
    contact_key = contacts.filter(pl.col("lower_key") == key)["key"][0]
    row = friction.filter((pl.col("contact_key") == contact_key) & (pl.col("method") == "per_spot"))
    assert len(row) == 1
    assert spots["mu_s"] == pytest.approx(row["mu_s_computed"][0], rel=1e-12)
    assert spots["spot_count"] == len(spots["spot_normal_force_N"]) > 0
    assert sum(spots["spot_normal_force_N"]) == pytest.approx(spots["normal_load_N"])
    shear = asperity.per_spot_friction(c, heights, dx, dy, model="junction_shear", material=C["material"])
    assert shear["mu_s"] > 0
    with pytest.raises(ValueError, match="parameters"):
        asperity.per_spot_friction(c, heights, dx, dy, model="full_stick", material=C["material"], parameters={"no_such": 1.0})
    with pytest.raises(ValueError, match="connectivity"):
        asperity.per_spot_friction(c, heights, dx, dy, model="full_stick", material=C["material"], connectivity=6)


def test_per_summit_friction_equals_the_cli_per_summit_node(asperity_bin, tmp_path):
    from conftest import CONTACT_STUDY

    study = tmp_path / "summits.yaml"
    node = "  ridges:\n    friction:\n      method: per_summit\n      contact: squeeze\n      lower_material: s235jr\n"
    study.write_text(CONTACT_STUDY.replace("outputs:", node + "outputs:"))
    cli = run_cli(asperity_bin, "run", str(study), "--out", "out", "--cache", "cache", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    friction = pl.read_parquet(tmp_path / "out" / "friction.parquet")
    contacts = pl.read_parquet(tmp_path / "out" / "contacts.parquet")
    surfaces = pl.read_parquet(tmp_path / "out" / "surfaces.parquet")
    t = asperity.synthetic_surface(
        C["grid"], C["size"], sq=C["sq"], hurst=C["hurst"], correlation_length=C["correlation_length"], seed=4
    )
    heights, dx, dy = t.heights, t.dx, t.dy
    c = asperity.contact(t, nominal_pressures=C["pressures"], lower_material=C["material"], tolerance=C["tolerance"])
    summits = asperity.per_summit_friction(c, heights, dx, dy, model="kogut_etsion", material=C["material"])
    key = surfaces.filter(pl.col("seed") == 4)["key"][0]
    contact_key = contacts.filter(pl.col("lower_key") == key)["key"][0]
    row = friction.filter((pl.col("contact_key") == contact_key) & (pl.col("method") == "per_summit"))
    assert len(row) == 1
    # The same summits, interferences and laws: the same sums, so μ_s to rounding.
    assert summits["mu_s_computed"] == pytest.approx(row["mu_s_computed"][0], rel=1e-12)
    assert summits["mu_s"] == pytest.approx(row["mu_s"][0], rel=1e-12, abs=0.0)
    assert summits["mu_s_floored"] == row["mu_s_floored"][0]
    assert summits["summit_count"] == len(summits["summit_radius_m"]) > 0
    assert sum(summits["summit_normal_force_N"]) == pytest.approx(summits["normal_load_N"])
    with pytest.raises(ValueError, match="single-asperity"):
        asperity.per_summit_friction(c, heights, dx, dy, model="junction_shear", material=C["material"])
    with pytest.raises(TypeError, match="deformation_lower"):
        asperity.per_summit_friction({"pressure": c["pressure"], "gap": c["gap"]}, heights, dx, dy)


TWO_BODY_STUDY = """\
study: py-ploughing
nodes:
  lower:
    surface:
      synthetic: {grid: [64, 48], size: [0.32 mm, 0.24 mm], sq: 0.8 um, hurst: 0.7,
                  correlation_length: 40 um, seed: 5}
  upper:
    surface:
      synthetic: {grid: [64, 48], size: [0.32 mm, 0.24 mm], sq: 0.5 um, hurst: 0.8,
                  correlation_length: 30 um, seed: 6}
  pair:
    contact:
      lower: lower
      upper: upper
      lower_material: s235jr
      upper_material: aisi52100
      nominal_pressures: [20 MPa]
      tolerance: 1e-8
      fields: true
  ploughing:
    friction:
      model: {ploughing: {deformation: MODE, sliding_direction: 30 deg}}
      contact: pair
      lower_material: s235jr
      upper_material: aisi52100
  stick:
    friction: {method: per_spot, model: full_stick, contact: pair, lower_material: s235jr,
               upper_material: aisi52100}
  shear:
    friction: {model: junction_shear, contact: pair, lower_material: s235jr,
               upper_material: aisi52100}
outputs: [friction]
"""


@pytest.mark.parametrize("mode", ["groove", "cone", "sphere"])
def test_per_spot_friction_of_two_bodies_equals_the_study_row(asperity_bin, tmp_path, mode):
    study = tmp_path / "ploughing.yaml"
    study.write_text(TWO_BODY_STUDY.replace("MODE", mode))
    cli = run_cli(asperity_bin, "run", str(study), "--out", "out", "--cache", "cache", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    friction = pl.read_parquet(tmp_path / "out" / "friction.parquet")
    surface = dict(grid=(64, 48), size=(0.32e-3, 0.24e-3))
    lower, dx, dy = asperity.synthetic_surface(surface["grid"], surface["size"], sq=0.8e-6, hurst=0.7, correlation_length=40e-6, seed=5)
    upper, _, _ = asperity.synthetic_surface(surface["grid"], surface["size"], sq=0.5e-6, hurst=0.8, correlation_length=30e-6, seed=6)
    c = asperity.contact(
        lower, dx, dy, upper=upper, nominal_pressures=20e6, lower_material="s235jr", upper_material="aisi52100", tolerance=1e-8
    )
    bodies = dict(material="s235jr", upper_material="aisi52100", upper_height=upper)
    plough = asperity.per_spot_friction(
        c, lower + upper, dx, dy, model="ploughing", parameters={"deformation": mode, "sliding_direction": 0.5235987755982988}, **bodies
    )
    row = friction.filter(pl.col("model") == "ploughing")
    assert len(row) == 1
    # The one call of the numerics on the same fields: the study's row to rounding.
    assert plough["mu_s"] == pytest.approx(row["mu_s_computed"][0], rel=1e-12)
    assert plough["mu_deformation"] == pytest.approx(row["mu_deformation"][0], rel=1e-12)
    assert plough["mu_deformation_slope_baseline"] == pytest.approx(row["mu_deformation_slope_baseline"][0], rel=1e-12)
    # The harder bearing steel is the upper body: it ploughs.
    assert plough["ploughing_body"] == row["ploughing_body"][0] == "upper"
    assert plough["mu_deformation"] > 0
    for model in ("full_stick", "junction_shear"):
        spots = asperity.per_spot_friction(c, lower + upper, dx, dy, model=model, **bodies)
        other = friction.filter(pl.col("model") == model)
        assert spots["mu_s"] == pytest.approx(other["mu_s_computed"][0], rel=1e-12), model
