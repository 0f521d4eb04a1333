"""Every result's keys are those of its TypedDict (asperity/_results.py, the one place they are
spelled): each key returned is declared, each required key is returned, so a type checker sees
what the functions return; and every key of a computed result is a column name of the one
vocabulary (src/vocabulary.rs with its unit suffix), the names the study tables use (#41)."""

import inspect
import typing

import numpy as np
import pytest

import asperity
from asperity import _native

T = asperity.synthetic_surface(64, 64e-6, sq=0.05e-6, hurst=0.8, correlation_length=20e-6)
MISSING = np.array(T.heights)
MISSING[3, 5] = np.nan


def check(result, typed, name):
    declared = set(typing.get_type_hints(typed))
    required = set(typed.__required_keys__)
    undeclared = sorted(set(result) - declared)
    absent = sorted(required - set(result))
    assert not undeclared, f"{name}: keys returned but not declared in {typed.__name__}: {undeclared}"
    assert not absent, f"{name}: required keys of {typed.__name__} not returned: {absent}"


def speaks_the_vocabulary(result, name):
    unknown = sorted(k for k in result if not _native.is_column_name(k))
    assert not unknown, f"{name}: keys outside the vocabulary (src/vocabulary.rs): {unknown}"


def test_the_vocabulary_check_refuses_an_unknown_name():
    assert _native.is_column_name("real_area_m2") and not _native.is_column_name("real_area_m^2")
    assert not _native.is_column_name("total_friction_force_N")


def test_surface_results():
    check(T.statistics(), asperity.SurfaceStatistics, "statistics (complete map)")
    check(asperity.surface_statistics(MISSING, T.dx), asperity.SurfaceStatistics, "surface_statistics (missing points)")
    check(T.psd(), asperity.Psd, "psd")
    check(T.acf(), asperity.Acf, "acf")
    check(T.material_ratio(), asperity.MaterialRatio, "material_ratio")
    check(T.summits(), asperity.Summits, "summits")
    for result in (T.statistics(), asperity.surface_statistics(MISSING, T.dx), T.psd(), T.acf(), T.material_ratio(), T.summits()):
        speaks_the_vocabulary(result, "surface results")
    # Every optional key is returned for some map: the declarations are not stale.
    optional = set(typing.get_type_hints(asperity.SurfaceStatistics)) - set(asperity.SurfaceStatistics.__required_keys__)
    assert optional <= set(T.statistics()), sorted(optional - set(T.statistics()))


def test_contact_and_friction_results():
    c = asperity.contact(T, nominal_pressures=[5e6, 20e6], lower_material="s235jr")
    check(c, asperity.ContactResult, "contact")
    for step in c["load_curve"]:
        check(step, asperity.LoadStep, "contact load_curve")
    every = asperity.contact(T, nominal_pressures=[5e6, 20e6], lower_material="s235jr", fields="all")
    check(every, asperity.ContactResult, "contact, fields='all'")
    for step in every["steps"]:
        check(step, asperity.ContactStep, "contact steps")
    two = asperity.contact(T, upper=T, nominal_pressures=1e6, lower_material="s235jr", upper_material="s235jr")
    check(two, asperity.ContactResult, "contact of two surfaces")
    check(asperity.material("s235jr"), asperity.MaterialConstants, "material")
    for law in asperity.friction_laws():
        check(law, asperity.FrictionLaw, "friction_laws")
        for p in law["parameters"]:
            check(p, asperity.FrictionLawParameter, f"friction_laws {law['name']} parameter")
    for row in asperity.static_friction(model="full_stick", surface=T, nominal_pressures=[5e6, 20e6], material="s235jr"):
        check(row, asperity.StaticFrictionRow, "static_friction")
    spots = asperity.per_spot_friction(c, T, model="full_stick", material="s235jr")
    check(spots, asperity.PerSpotResult, "per_spot_friction")
    summits = asperity.per_summit_friction(c, T, material="s235jr")
    check(summits, asperity.PerSummitResult, "per_summit_friction")
    rows = asperity.static_friction(model="full_stick", surface=T, nominal_pressures=[5e6, 20e6], material="s235jr")
    for result in [c, two, *c["load_curve"], *rows, spots, summits]:
        speaks_the_vocabulary(result, "contact and friction results")


def test_twin_results_speak_the_vocabulary():
    other = asperity.synthetic_surface(64, 64e-6, sq=0.08e-6, hurst=0.8, correlation_length=20e-6, seed=2)
    for spectrum in ("self_affine", "measured"):
        _, _, _, info = asperity.synthetic_twin([T, other], sq="measured", spectrum=spectrum, grid=(64, 64), size=(64e-6, 64e-6), seed=1)
        speaks_the_vocabulary(info, f"synthetic_twin spectrum={spectrum}")


def test_list_columns_are_lists_in_tables_and_results(contact_study, tmp_path):
    """The vocabulary's list columns (`nominal_pressures_Pa`, `nodes`, `twin_warnings`, …) are
    Parquet list columns of their declared type in every table of a run, no other column is a
    list, and a Python result holds them as lists."""
    import polars as pl

    assert _native.list_column("nominal_pressures_Pa") == "float"
    assert _native.list_column("twin_warnings") == "text"
    assert _native.list_column("nominal_pressure_Pa") is None
    result = asperity.run(contact_study, out=tmp_path / "out", cache=tmp_path / "cache")
    expected = {"float": pl.List(pl.Float64), "text": pl.List(pl.String)}
    for table, df in result.tables.items():
        for column, dtype in df.schema.items():
            items = _native.list_column(column)
            if items is not None:
                assert dtype == expected[items], f"{table}.{column}: {dtype}"
            else:
                assert not isinstance(dtype, pl.List), f"{table}.{column}: {dtype} is not a declared list"
    for table in ("contacts", "contacts_by_scenario"):
        pressures = result[table]["nominal_pressures_Pa"].to_list()
        assert pressures and all(p == [5e6, 20e6] for p in pressures), (table, pressures)
    assert result["surfaces"]["nodes"].to_list() == [["rough"], ["rough"]]
    other = asperity.synthetic_surface(64, 64e-6, sq=0.08e-6, hurst=0.8, correlation_length=20e-6, seed=2)
    for spectrum in ("self_affine", "measured"):
        _, _, _, info = asperity.synthetic_twin([T, other], sq="measured", spectrum=spectrum, grid=(64, 64), size=(64e-6, 64e-6), seed=1)
        for key, value in info.items():
            items = _native.list_column(key)
            if items is None:
                assert not isinstance(value, list), f"{key}: {value!r}"
            else:
                assert isinstance(value, list) and all(isinstance(v, {"float": float, "text": str}[items]) for v in value), f"{key}: {value!r}"


def test_study_counts(contact_study):
    check(asperity.validate(contact_study), asperity.StudyCounts, "validate")


@pytest.mark.parametrize("name", [n for n in asperity.__all__ if hasattr(getattr(asperity, n), "__required_keys__")])
def test_every_typed_result_is_returned_by_a_function(name):
    functions = [getattr(asperity, f) for f in asperity.__all__ if inspect.isfunction(getattr(asperity, f))]
    functions += [getattr(asperity.Topography, m) for m in ("statistics", "psd", "acf", "material_ratio", "summits")]
    returned = " ".join(str(inspect.signature(f).return_annotation) for f in functions)
    nested = " ".join(str(typing.get_type_hints(t)) for t in (asperity.ContactResult, asperity.FrictionLaw))
    assert name in returned + " " + nested, f"{name}: no public function returns it"
