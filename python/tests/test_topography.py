"""Every file of the shared topography folder whose format asperity reads gives its reference Sq."""

import json
import warnings

import numpy as np
import pytest

import asperity

UNITS = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "um": 1e-6, "nm": 1e-9}


# Files of a format asperity reads that its reader refuses although SurfaceTopography reads them,
# with the cause the error must name (none today: the Nanoscope `\Scan size` header and the
# two-column text with a count line are read). A reader that refuses one fails this test until
# the entry is added.
REFUSED: dict = {}


# Files whose own unit line SurfaceTopography does not read (its values are in the file's numbers):
# the unit, in m, that asperity reads from the file.
FILE_UNITS = {"xyz/xy-2.txt": 1e-6}


def reference_sq(entry, height_unit_from_file, name=None):
    """Sq in m from SurfaceTopography's value in the file's unit, or asperity's own reference (m)
    where SurfaceTopography has none; a file without a height unit is compared in its numbers."""
    st = entry.get("SurfaceTopography_1.27.1") or {}
    if "Sq" in st:
        unit = st.get("unit")
        if unit in UNITS:
            return st["Sq"] * UNITS[unit]
        if unit is None and name in FILE_UNITS:
            assert height_unit_from_file, name
            return st["Sq"] * FILE_UNITS[name]
        assert unit is None and not height_unit_from_file, name
        return st["Sq"]
    own = entry.get("own_reader")
    return own["Sq"] if own and "Sq" in own else None


def sq_of(t) -> float:
    z = t.heights
    valid = z[~np.isnan(z)]
    return float(np.sqrt(np.mean((valid - valid.mean()) ** 2)))


def read_any(path, **calibration):
    """An areal map as a Topography, a line scan as a LineScan (read_topography of a line scan
    is deprecated: its warning says which)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        warnings.simplefilter("ignore", asperity.PlausibilityWarning)
        try:
            return asperity.read_topography(path, **calibration)
        except DeprecationWarning as e:
            assert "read_line_scan" in str(e), e
            return asperity.read_line_scan(path, **calibration)


def read(path):
    """The file as the command line reads it; a file without a lateral calibration gets one."""
    try:
        return read_any(path)
    except ValueError as e:
        assert "pixel_size" in str(e) and "not in the file" in str(e), e
        t = read_any(path, pixel_size=1e-6)
        assert t.spacing_source == "given"
        return t


def test_every_readable_file_gives_its_reference_sq(data_dir):
    references = json.loads((data_dir / "reference_values.json").read_text())
    checked, unreadable = [], []
    for name, entry in sorted(references.items()):
        path = data_dir / name
        if asperity.topography_format(path) is None:
            unreadable.append(name)
            continue
        if name in REFUSED:
            with pytest.raises(OSError, match=REFUSED[name]):
                asperity.read_topography(path, pixel_size=1e-6)
            continue
        if "SurfaceTopography_error" in entry and "own_reader" not in entry:
            # Damaged on purpose (SurfaceTopography cannot read it either): it raises.
            with pytest.raises(OSError):
                asperity.read_topography(path, pixel_size=1e-6)
            continue
        t = read(path)
        expected = reference_sq(entry, t.height_unit_source == "file", name)
        assert expected is not None, name
        if isinstance(t, asperity.Topography):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", asperity.PlausibilityWarning)
                assert t.statistics()["sq_m"] == pytest.approx(expected, rel=1e-6), name
        assert sq_of(t) == pytest.approx(expected, rel=1e-6), name
        checked.append(name)
    assert len(checked) >= 20, (checked, unreadable)


@pytest.mark.filterwarnings("ignore:.*stores no height unit:asperity.PlausibilityWarning")
def test_a_map_without_calibration_is_not_given_one(data_dir):
    line = data_dir / "xyz" / "xy-4.txt"
    with pytest.raises(ValueError, match="pixel_size"):
        asperity.read_line_scan(line)
    t = asperity.read_line_scan(line, size=1e-3)
    assert t.x[1] == 1e-3 / len(t.x) and t.spacing_source == "given"
    with pytest.raises(ValueError, match="read_topography"):
        asperity.read_line_scan(data_dir / "x3p" / "x3p-2.x3p")
    calibrated = data_dir / "x3p" / "x3p-2.x3p"
    with pytest.raises(ValueError, match="override_file_spacing"):
        asperity.read_topography(calibrated, pixel_size=1e-3)
    with pytest.warns(asperity.PlausibilityWarning, match="coarser than a millimetre"):
        t = asperity.read_topography(calibrated, pixel_size=(1e-3, 2e-3), override_file_spacing=True)
    assert (t.dx, t.dy) == (1e-3, 2e-3) and t.spacing_source == "given"


@pytest.mark.filterwarnings("ignore:.*stores no height unit:asperity.PlausibilityWarning")
def test_the_old_dict_keys_still_read_with_a_deprecation_warning(data_dir):
    """read_topography returned a dict before; its keys still work, with a DeprecationWarning."""
    t = asperity.read_topography(data_dir / "x3p" / "x3p-2.x3p")
    with pytest.warns(DeprecationWarning, match="t.heights"):
        assert t["heights"] is t.heights and t["dx"] == t.dx and t["spacing_from_file"] is True
    with pytest.warns(DeprecationWarning, match="read_line_scan"):
        line = asperity.read_topography(data_dir / "xyz" / "xy-4.txt", size=1e-3)
    with pytest.warns(DeprecationWarning):
        assert line["x"] is line.x
