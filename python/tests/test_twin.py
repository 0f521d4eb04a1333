"""`synthetic_twin(..., spectrum="measured")`: the twin's periodogram is the measured Hann
periodogram at every mode (scaled to its Sq), the bytes follow the seed, and bad input names the
parameter and the fix."""

import numpy as np
import pytest

import asperity


def measured_map():
    """A 96 x 80 window of an anisotropic synthetic surface: not periodic, with a lay."""
    z, dx, dy = asperity.synthetic_surface(
        grid=(192, 160), size=(0.4e-3, 0.4e-3 * 160 / 192), sq=1e-6, hurst=0.7,
        correlation_length=100e-6, seed=4, anisotropy=(3.0, 0.5),
    )
    return z[30:110, 20:116].copy(), dx, dy


def hann_periodogram(z, dx, dy):
    """C(q) = A |Z_w|^2 / (N^2 <w^2>) with the separable periodic Hann window (asperity's)."""
    ny, nx = z.shape
    wx = np.sin(np.pi * np.arange(nx) / nx) ** 2
    wy = np.sin(np.pi * np.arange(ny) / ny) ** 2
    w = np.outer(wy, wx)
    c = np.abs(np.fft.fft2((z - z.mean()) * w)) ** 2
    area = nx * dx * ny * dy
    return c * area / ((nx * ny) ** 2 * np.mean(wx**2) * np.mean(wy**2))


def test_spectrum_twin_reproduces_the_measured_periodogram_at_every_mode():
    z, dx, dy = measured_map()
    twin, tdx, tdy, info = asperity.synthetic_twin([(z, dx, dy)], sq="measured", spectrum="measured", seed=3)
    assert twin.shape == z.shape and (tdx, tdy) == (dx, dy)
    sq = float(np.sqrt(np.mean((z - z.mean()) ** 2)))
    assert info["twin_sq_m"] == pytest.approx(sq, rel=1e-12)
    assert np.sqrt(np.mean(twin**2)) == pytest.approx(sq, rel=1e-12)
    assert info["twin_spectrum"] == "measured" and info["twin_extrapolation"] == "zero"
    assert info["twin_grid_power_share"] == pytest.approx(1.0, rel=1e-9)  # the map's own grid
    measured = hann_periodogram(z, dx, dy)
    measured[0, 0] = 0.0
    area = z.size * dx * dy
    periodic = np.abs(np.fft.fft2(twin)) ** 2 * area / z.size**2
    scale = (info["twin_sq_m"] / info["twin_spectrum_sq_m"]) ** 2
    np.testing.assert_allclose(periodic, scale * measured, rtol=1e-6, atol=1e-9 * measured.max())


def test_the_seed_decides_the_bytes_and_the_grid_is_the_twins():
    z, dx, dy = measured_map()
    twin = lambda seed, **kw: asperity.synthetic_twin([(z, dx, dy)], sq=0.5e-6, spectrum="measured", seed=seed, **kw)[0]
    a, b, c = twin(7), twin(7), twin(8)
    assert a.tobytes() == b.tobytes() and a.tobytes() != c.tobytes()
    bigger, tdx, _, info = asperity.synthetic_twin(
        [(z, dx, dy)], sq=0.5e-6, spectrum="measured", grid=(192, 160), size=(192 * dx, 160 * dy)
    )
    assert bigger.shape == (160, 192) and tdx == pytest.approx(dx)
    assert np.sqrt(np.mean(bigger**2)) == pytest.approx(0.5e-6, rel=1e-12)
    assert info["twin_modes_longer_than_measured"] > 0


def test_bad_spectrum_twin_input_names_the_parameter_and_the_fix():
    z, dx, dy = measured_map()
    with pytest.raises(ValueError, match="spectrum: 'fitted' is not one of: 'self_affine', 'measured'"):
        asperity.synthetic_twin([(z, dx, dy)], sq=1e-6, grid=16, size=1e-4, spectrum="fitted")
    with pytest.raises(ValueError, match="extrapolation"):
        asperity.synthetic_twin([(z, dx, dy)], sq=1e-6, spectrum="measured", extrapolation="flat")
    with pytest.raises(ValueError, match="2-D array"):
        asperity.synthetic_twin([(z[0], dx, dy)], sq=1e-6, spectrum="measured")
    with pytest.raises(ValueError, match="at least 2 × 2 points"):
        asperity.synthetic_twin([(z[:1], dx, dy)], sq=1e-6, spectrum="measured")
    with pytest.raises(ValueError, match="lateral units"):
        asperity.synthetic_twin([(z, dx, dy), (z, 1e3 * dx, 1e3 * dy)], sq=1e-6, spectrum="measured")
    with pytest.raises(ValueError, match="height units"):
        asperity.synthetic_twin([(z, dx, dy), (1e3 * z, dx, dy)], sq=1e-6, spectrum="measured")
    with pytest.raises(ValueError, match="grid, size: required for a self-affine twin"):
        asperity.synthetic_twin([(z, dx, dy)], sq=1e-6)
