"""The Topography object: its PSD, ACF, material ratio curve and summits are a study's long tables
bit for bit; every array function takes it and returns one for one; it owns read-only heights,
and the old call forms still work with a DeprecationWarning."""

import warnings

import numpy as np
import polars as pl
import pytest

import asperity
from conftest import CONTACT_INPUTS as C
from conftest import run_cli


def test_spectra_and_material_ratio_are_the_study_tables(asperity_bin, contact_study, tmp_path):
    cli = run_cli(asperity_bin, "run", str(contact_study), "--out", "out", "--cache", "cache", "-q", cwd=tmp_path)
    assert cli.returncode == 0, cli.stderr
    surfaces = pl.read_parquet(tmp_path / "out" / "surfaces.parquet").filter(pl.col("seed") == 3)
    key = surfaces["key"][0]
    t = asperity.synthetic_surface(C["grid"], C["size"], sq=C["sq"], hurst=C["hurst"], correlation_length=C["correlation_length"], seed=3)
    for table, ours in (("psd", t.psd()), ("acf", t.acf()), ("material_ratio", t.material_ratio()), ("summits", t.summits())):
        theirs = pl.read_parquet(tmp_path / "out" / f"surfaces_{table}.parquet").filter(pl.col("key") == key)
        assert set(ours) == set(theirs.columns) - {"key"}, table
        for column, values in ours.items():
            # A study's spectra (and the ACF, their transform) of a synthetic surface come from its
            # synthesized modes, Python's from a transform of its heights: equal to round-off.
            if table in ("psd", "acf"):
                assert np.allclose(values, theirs[column].to_numpy(), rtol=1e-12, atol=0.0), (table, column)
            else:
                assert np.array_equal(values, theirs[column].to_numpy()), (table, column)


def test_array_functions_take_a_topography_and_return_one():
    t = asperity.synthetic_surface(32, 64e-6, sq=0.2e-6, hurst=0.8, correlation_length=20e-6, seed=2)
    level, rms = asperity.remove_form(t, degree=1)
    assert isinstance(level, asperity.Topography) and level.periodic and (level.dx, level.dy) == (t.dx, t.dy)
    heights, rms_arrays = asperity.remove_form(t.heights, t.dx, degree=1)
    assert isinstance(heights, np.ndarray) and np.array_equal(heights, level.heights) and rms == rms_arrays
    smooth = asperity.gaussian_filter(t, kind="low", cutoff="8 um")
    assert isinstance(smooth, asperity.Topography)
    assert np.array_equal(smooth.heights, asperity.gaussian_filter(t.heights, t.dx, kind="low", cutoff=8e-6))
    holes = np.array(t.heights)
    holes[4, 4] = np.nan
    filled, count = asperity.fill_missing(asperity.Topography(holes, t.dx))
    assert count == 1 and filled.missing_points == 0
    assert asperity.surface_statistics(t) == t.statistics()
    with pytest.raises(TypeError, match="omit dx"):
        asperity.surface_statistics(t, t.dx)
    with pytest.raises(TypeError, match="dx: required with a height array"):
        asperity.surface_statistics(t.heights)


def test_a_topography_owns_read_only_heights_and_says_what_it_is():
    z = np.random.default_rng(3).normal(size=(16, 24)) * 1e-7
    t = asperity.Topography(z, "0.5 um", metadata={"instrument": "test"})
    z[0, 0] = 1.0  # the caller's array is copied
    assert t.heights[0, 0] != 1.0 and not t.heights.flags.writeable
    assert (t.nx, t.ny, t.shape) == (24, 16, (16, 24)) and t.size == (24 * 0.5e-6, 16 * 0.5e-6)
    assert t.dx == t.dy == 0.5e-6 and not t.periodic and t.height_unit == "m"
    assert t.metadata["instrument"] == "test" and t.spacing_source == t.height_unit_source == "given"
    assert repr(t) == "Topography(24×16, dx=5e-07 m, dy=5e-07 m, size=1.2e-05×8e-06 m, spacing_source='given', height_unit_source='given')"
    with pytest.raises(ValueError, match="missing point"):
        holes = np.array(t.heights)
        holes[1, 1] = np.nan
        asperity.Topography(holes, 1e-6).psd()


def test_synthetic_surface_unpacks_as_before_with_a_deprecation_warning():
    t = asperity.synthetic_surface(16, 1e-4, sq=1e-6, hurst=0.8, correlation_length=2e-5)
    with pytest.warns(DeprecationWarning, match="t.heights, t.dx, t.dy"):
        heights, dx, dy = t
    assert heights is t.heights and (dx, dy) == (t.dx, t.dy)


def test_the_repr_of_a_run_result_is_short(contact_study, tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", asperity.PlausibilityWarning)
        result = asperity.run(contact_study, out=tmp_path / "out", cache=tmp_path / "cache", jobs=1)
    text = repr(result)
    assert len(text) < 600 and "contacts 2×" in text and "computed=8" in text, text
