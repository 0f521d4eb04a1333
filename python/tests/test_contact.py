"""The contact solver from Python gives the command line's contact node's numbers bit for bit.

The one exception is the spectral statistics of a synthetic surface: a study computes them from
the surface's synthesized modes (no transform of its heights), Python from a transform of the
heights it is given; the two agree to round-off (relative 1e-12 here), the contact bit for bit."""

import math

import numpy as np
import polars as pl
import pytest

import asperity
from conftest import CONTACT_INPUTS as C
from conftest import run_cli


def same_bits(a, b) -> bool:
    return np.float64(a).tobytes() == np.float64(b).tobytes()


def same_to_round_off(a, b) -> bool:
    """Equal bits, or (floats) equal to 1e-12 relative: see the module's docstring."""
    if same_bits(a, b):
        return True
    return isinstance(a, float) and isinstance(b, float) and abs(a - b) <= 1e-12 * max(abs(a), abs(b))


@pytest.mark.parametrize("seed", [3, 4])
def test_python_contact_equals_the_cli_contact_bit_for_bit(asperity_bin, contact_study, tmp_path, seed):
    cli = run_cli(asperity_bin, "run", str(contact_study), "--out", "out", "--cache", "cache", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    t = asperity.synthetic_surface(
        C["grid"], C["size"], sq=C["sq"], hurst=C["hurst"], correlation_length=C["correlation_length"], seed=seed
    )
    surfaces = pl.read_parquet(tmp_path / "out" / "surfaces.parquet").filter(pl.col("seed") == seed)
    stats = t.statistics()
    assert asperity.surface_statistics(t.heights, t.dx, t.dy, periodic=True) == stats
    common = [c for c in surfaces.columns if c in stats]
    assert len(common) >= 30, common
    for column in common:
        assert same_to_round_off(stats[column], surfaces[column][0]), column
    ours = asperity.contact(t, nominal_pressures=C["pressures"], lower_material=C["material"], tolerance=C["tolerance"])
    arrays = asperity.contact(t.heights, t.dx, t.dy, nominal_pressures=C["pressures"], lower_material=C["material"], tolerance=C["tolerance"])
    assert same_bits(arrays["approach_m"], ours["approach_m"]) and np.array_equal(arrays["pressure"], ours["pressure"])
    key = surfaces["key"][0]
    row = pl.read_parquet(tmp_path / "out" / "contacts.parquet").filter(pl.col("lower_key") == key)
    assert len(row) == 1
    compared = [c for c in row.columns if c in ours]
    assert len(compared) >= 14, compared
    for column in compared:
        assert same_bits(ours[column], row[column][0]), (column, ours[column], row[column][0])
    curve = pl.read_parquet(tmp_path / "out" / "contacts_load_curve.parquet").filter(pl.col("key") == row["key"][0])
    for column in ("nominal_pressure_Pa", "area_fraction", "mean_separation_m", "approach_m"):
        assert [s[column] for s in ours["load_curve"]] == curve[column].to_list(), column
    pressure = ours["pressure"]
    assert pressure.shape == (48, 64) and (pressure >= 0).all()
    assert math.isclose(pressure.mean(), C["pressures"][-1], rel_tol=1e-6)
    assert ours["iterations"] > 0 and 0 <= ours["residual"] < C["tolerance"] * 10


def test_two_surfaces_and_explicit_materials(tmp_path):
    a = asperity.synthetic_surface(64, 1e-4, sq=0.5e-6, hurst=0.8, correlation_length=2e-5, seed=1)
    b = asperity.synthetic_surface(64, 1e-4, sq=0.5e-6, hurst=0.8, correlation_length=2e-5, seed=2)
    steel = {"youngs_modulus": 210e9, "poisson_ratio": 0.3}
    pair = asperity.contact(a, upper=b, nominal_pressures=[20e6], lower_material=steel, upper_material="s235jr")
    assert 0 < pair["area_fraction"] < 1
    assert pair["deformation_upper"].shape == a.shape
    mixed = asperity.contact(a.heights, a.dx, upper=b.heights, nominal_pressures=[20e6], lower_material=steel, upper_material="s235jr")
    assert mixed["area_fraction"] == pair["area_fraction"]
    with pytest.raises(ValueError, match="upper: spacing"):
        wide = asperity.Topography(b.heights, 2 * b.dx)
        asperity.contact(a, upper=wide, nominal_pressures=[1e6], lower_material=steel, upper_material="s235jr")
    flat = asperity.contact(a, nominal_pressures=20e6, lower_material=steel)
    assert flat["composite_modulus_Pa"] == pytest.approx(210e9 / (1 - 0.3**2))
