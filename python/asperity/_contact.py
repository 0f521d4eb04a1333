"""Materials and the contact solver on arrays."""

from __future__ import annotations

from typing import Any, Dict, Mapping, Optional, Sequence, Tuple, Union, cast

from . import _args, _native
from ._args import F64
from ._plausibility import contact_sentences, stiffness_sentences
from ._results import ContactResult, MaterialConstants
from ._topography import Topography, as_topography
from ._warnings import warn

Material = Union[str, Mapping[str, Any]]
Pressures = Union[float, str, Sequence[Union[float, str]], F64]

#: The keys of a material mapping, as a study's material mapping has them (`name` is a built-in
#: material whose values the others override; `source`, in what :func:`material` returns, is
#: only read by people).
MATERIAL_KEYS = ("name", "youngs_modulus", "poisson_ratio", "hardness", "flow_pressure", "yield_strength", "shear_strength", "source")
_PRESSURE_KEYS = ("youngs_modulus", "hardness", "flow_pressure", "yield_strength", "shear_strength")


def material(name: str) -> MaterialConstants:
    """A built-in material (case-insensitive name or alias): ``name``, ``youngs_modulus`` (Pa),
    ``poisson_ratio``, ``hardness`` (Pa), ``flow_pressure`` (Pa) and ``source``."""
    return cast(MaterialConstants, dict(_native.material(_args.text("name", name, "a material name (str), e.g. 's235jr'"))))


def body(name: str, m: Any) -> Dict[str, Optional[float]]:
    """A material name or mapping as SI constants: ``youngs_modulus``, ``poisson_ratio`` and
    the optional ``hardness``, ``flow_pressure``, ``yield_strength``, ``shear_strength``
    (None when neither given nor built in). Warns of a modulus or strength below 1 MPa."""
    if isinstance(m, str):
        given: Mapping[str, Any] = {"name": m}
    elif isinstance(m, Mapping):
        unknown = [k for k in m if k not in MATERIAL_KEYS]
        if unknown:
            raise ValueError(f"{name}: {unknown[0]!r} is not a material constant; expected: {', '.join(MATERIAL_KEYS)}")
        given = m
    else:
        raise TypeError(f"{name}: expected a material name or a mapping {{youngs_modulus: Pa, poisson_ratio, hardness: Pa, …}}, got {_args.show(m)}")
    values: Dict[str, Any] = {}
    if "name" in given:
        values.update(_native.material(_args.text(f"{name}.name", given["name"], "a material name (str)")))
        values.pop("name")
        values.pop("source")
    values.update({k: v for k, v in given.items() if k not in ("name", "source")})
    for key in ("youngs_modulus", "poisson_ratio"):
        if values.get(key) is None:
            raise ValueError(f"{name}: missing {key!r} ({'Pa' if key == 'youngs_modulus' else 'in [0, 0.5]'}); give it or a built-in 'name'")
    out: Dict[str, Optional[float]] = {
        "poisson_ratio": _args.quantity(f"{name}.poisson_ratio", values["poisson_ratio"], _args.NUMBER, minimum_inclusive=True, maximum=0.5, maximum_inclusive=True)
    }
    for key in _PRESSURE_KEYS:
        out[key] = _args.optional_quantity(f"{name}.{key}", values.get(key), _args.PRESSURE)
        if key in ("youngs_modulus", "hardness", "flow_pressure") and out[key] is not None:
            warn(stiffness_sentences(f"{name}.{key}", cast(float, out[key])))
    return out


def _elastic(b: Dict[str, Optional[float]]) -> Tuple[float, float]:
    """(E in Pa, ν) of a checked body."""
    return cast(float, b["youngs_modulus"]), cast(float, b["poisson_ratio"])


def _pair_topographies(lower: Any, dx: Any, dy: Any, upper: Any) -> Tuple[Topography, Optional[Topography]]:
    lo, _ = as_topography("lower", lower, dx, dy)
    if upper is None:
        return lo, None
    if isinstance(upper, Topography):
        if (upper.dx, upper.dy) != (lo.dx, lo.dy):
            raise ValueError(f"upper: spacing ({upper.dx:g}, {upper.dy:g}) m differs from lower's ({lo.dx:g}, {lo.dy:g}) m")
        up = upper
    else:
        up, _ = as_topography("upper", upper, lo.dx, lo.dy)
    if up.shape != lo.shape:
        raise ValueError(f"upper: shape {up.shape} differs from lower's {lo.shape}")
    return lo, up


def _checked_slope(name: str, t: Topography) -> Optional[float]:
    """The surface node's checks of a map's scale (warnings; a failing spacing raises), and its
    rms slope for the contact node's slope flag."""
    sdq, sentences = _native.scale_checks(t.heights, t.dx, t.dy, t.periodic)
    warn(f"{name}: {s}" for s in sentences)
    return sdq


def contact(
    lower: Union[Topography, F64],
    dx: Optional[Union[float, str]] = None,
    dy: Optional[Union[float, str]] = None,
    *,
    nominal_pressures: Pressures,
    lower_material: Material,
    upper: Optional[Union[Topography, F64]] = None,
    upper_material: Optional[Material] = None,
    flow_pressure: Optional[Union[float, str]] = None,
    periodic: bool = True,
    tolerance: Optional[float] = None,
    fields: str = "final",
) -> ContactResult:
    """Elastic–perfectly-plastic FFT boundary-element contact, as a study's ``contact`` node.

    ``lower`` (and ``upper``) are :class:`Topography` objects or height maps (m) at spacing
    ``dx``, ``dy`` (m); without ``upper`` the counter-body is a rigid flat. Materials are built-in
    names or mappings ``{youngs_modulus: Pa, poisson_ratio, flow_pressure: Pa (optional)}``
    (values in SI or strings such as ``"210 GPa"``); the flow pressure p_lim is
    ``flow_pressure``, else the smaller of the materials', else infinite (elastic).
    ``nominal_pressures`` (Pa, ascending, below p_lim and below the composite modulus) are solved
    as load steps; ``periodic`` surfaces wrap around (the default, as a study's), otherwise the
    DC-FFT of a finite patch is used; ``tolerance`` is the relative error of every convergence
    condition. Implausible inputs (a map's scale, a modulus below 1 MPa) and what would flag the
    node's row (a coarse grid, a composite slope above 0.5) raise :class:`PlausibilityWarning`.

    Returns a dict: the ``contacts`` row of the final step (``area_fraction``,
    ``mean_contact_pressure_Pa``, ``mean_separation_m``, ``approach_m``, ``iterations``,
    ``residual``, …), ``load_curve`` (one dict per step) and the final step's arrays
    ``pressure`` (Pa), ``gap`` (m), ``deformation_lower``/``deformation_upper`` (m) and
    ``plastic_penetration`` (m). Signs: ``gap`` is the separation of the deformed surfaces, > 0
    out of contact, 0 in elastic contact and < 0 where the surfaces interpenetrate by plastic
    flow (p = p_lim; −gap is the plastic penetration there); deformations are positive into
    each body.

    ``fields="all"`` also returns ``steps``, one dict per load step (the last is the final
    step): ``nominal_pressure_Pa``, ``area_fraction`` and the step's maps under the same names,
    derived for the earlier steps from the step's pressure as a study's contact node derives
    them for its friction nodes (equal to the solver's maps to round-off). Pass a step to
    :func:`per_spot_friction` or :func:`per_summit_friction` with ``step=i`` (or the step's dict
    as ``result``) for the friction at that load, the row of the study's ``friction_curve``.
    ``fields="final"`` (the default) keeps the final step's maps only.
    """
    if fields not in ("final", "all"):
        raise ValueError(f"fields: {fields!r} is not one of 'final', 'all' (the maps of the final load step, or of every step)")
    lo, up = _pair_topographies(lower, dx, dy, upper)
    slopes = [s for s in (_checked_slope("lower", lo), None if up is None else _checked_slope("upper", up)) if s is not None]
    lower_body = body("lower_material", lower_material)
    upper_body = None if upper_material is None else body("upper_material", upper_material)
    if flow_pressure is not None:
        p_lim = _args.quantity("flow_pressure", flow_pressure, _args.PRESSURE)
    else:
        flows = [f for b in (lower_body, upper_body if up is not None else None) if b is not None for f in (b["flow_pressure"],) if f is not None]
        p_lim = min(flows) if flows else float("inf")
    pressures = _args.quantities("nominal_pressures", nominal_pressures, _args.PRESSURE)
    tol = _args.optional_quantity("tolerance", tolerance, _args.NUMBER)
    result, flags = _native.contact(
        lo.heights,
        lo.dx,
        lo.dy,
        _elastic(lower_body),
        pressures,
        p_lim,
        None if up is None else up.heights,
        None if upper_body is None else _elastic(upper_body),
        _args.boolean("periodic", periodic),
        tol,
        slopes,
        fields == "all",
    )
    warn(flags)
    warn(contact_sentences(result["area_fraction"], lo.nx * lo.ny, pressures[-1]))
    return cast(ContactResult, dict(result))


