"""Friction on numbers and contact results: statistical, per spot and per summit, through the
law registry. The laws a docstring names are the registry's (:func:`friction_laws`), filled in
when the module is imported, so a new law appears in ``help()`` without an edit here."""

from __future__ import annotations

from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union, cast

from . import _args, _native
from ._args import F64
from ._contact import Material, Pressures, body
from ._plausibility import summit_sentences
from ._results import MOMENT_KEYS, FrictionLaw, PerSpotResult, PerSummitResult, StaticFrictionRow
from ._topography import Topography, as_topography
from ._warnings import warn

LawParameters = Mapping[str, Union[float, str]]
Quantity = Union[float, str]

#: The methods of the registry, as studies write them.
STATISTICAL, PER_SUMMIT, PER_SPOT = "statistical", "per_summit", "per_spot"


def friction_laws() -> List[FrictionLaw]:
    """Every friction law of the registry, in its order (the first is a study's default model):
    ``name``, ``summary``, ``basis`` (how far its constants are confirmed), ``methods``
    (``statistical``, ``per_summit``, ``per_spot``; the first is its default) and
    ``parameters``, each with ``name``, ``kind`` (``number`` or ``choice``), ``default``,
    ``unit`` (SI symbol), ``range``, ``options`` and ``description``."""
    return cast(List[FrictionLaw], _native.friction_laws())


def law_names(method: str) -> List[str]:
    """The registered laws that support ``method``."""
    return [law["name"] for law in friction_laws() if method in law["methods"]]


def _named_laws(method: str) -> str:
    return ", ".join(f'``"{name}"``' for name in law_names(method))


def _model(model: Any) -> str:
    return _args.text("model", model, f"a friction law's name (str), one of: {', '.join(law['name'] for law in friction_laws())}")


def _friction_material(
    material: Optional[Material], composite_modulus: Any, hardness: Any, poisson_ratio: Any
) -> Tuple[float, float, float, Optional[float], Optional[float]]:
    """E* (Pa), H (Pa), ν and the material's yield and shear strengths (Pa, or None) of a body
    against a rigid flat: from a material (E* = E/(1 − ν²)) or as given."""
    if material is not None:
        if any(v is not None for v in (composite_modulus, hardness, poisson_ratio)):
            raise ValueError("material: give a material or composite_modulus, hardness and poisson_ratio, not both")
        b = body("material", material)
        h = b["hardness"]
        if h is None:
            raise ValueError("material: needs a hardness (Pa) for the friction laws; give 'hardness' or a built-in 'name'")
        e, nu = cast(float, b["youngs_modulus"]), cast(float, b["poisson_ratio"])
        return e / (1.0 - nu * nu), h, nu, b["yield_strength"], b["shear_strength"]
    if composite_modulus is None or hardness is None or poisson_ratio is None:
        missing = [n for n, v in (("composite_modulus", composite_modulus), ("hardness", hardness), ("poisson_ratio", poisson_ratio)) if v is None]
        raise ValueError(f"material: give a material, or composite_modulus, hardness and poisson_ratio (missing: {', '.join(missing)})")
    return (
        _args.quantity("composite_modulus", composite_modulus, _args.PRESSURE),
        _args.quantity("hardness", hardness, _args.PRESSURE),
        _args.quantity("poisson_ratio", poisson_ratio, _args.NUMBER, minimum_inclusive=True, maximum=0.5, maximum_inclusive=True),
        None,
        None,
    )


def _adhesion(adhesion_energy: Any, equilibrium_distance: Any) -> Tuple[float, float]:
    """Δγ (N/m, ≥ 0) and ε (m, > 0), the study's defaults when not given."""
    return (
        _native.DEFAULT_ADHESION_ENERGY
        if adhesion_energy is None
        else _args.quantity("adhesion_energy", adhesion_energy, _args.SURFACE_ENERGY, minimum_inclusive=True),
        _native.DEFAULT_EQUILIBRIUM_DISTANCE if equilibrium_distance is None else _args.quantity("equilibrium_distance", equilibrium_distance, _args.LENGTH),
    )


def _law_options(parameters: Any, yield_strength: Any, shear_strength: Any, material_yield: Optional[float], material_shear: Optional[float]) -> Tuple[Dict[str, Union[float, str]], Optional[float], Optional[float]]:
    """A law's parameter overrides (checked by the registry in the native call) and the softer
    body's strengths (Pa): given, else the material's, else None (the laws' default rules)."""
    if parameters is None:
        parameters = {}
    if not isinstance(parameters, Mapping) or not all(isinstance(k, str) for k in parameters):
        raise TypeError(f"parameters: expected a mapping {{name: number (SI) or string (a choice, or a quantity such as '90 deg')}}, got {_args.show(parameters)}")
    for name, v in parameters.items():
        if not (isinstance(v, str) or _args.is_number(v)):
            raise TypeError(f"parameters.{name}: expected a number (SI) or a string (a choice, or a quantity such as '90 deg'), got {_args.show(v)}")
    return (
        {k: (v if isinstance(v, str) else float(v)) for k, v in parameters.items()},
        material_yield if yield_strength is None else _args.quantity("yield_strength", yield_strength, _args.PRESSURE),
        material_shear if shear_strength is None else _args.quantity("shear_strength", shear_strength, _args.PRESSURE),
    )


def _roughness(moments: Any, summits: Any, surface: Any, nominal_area: Any) -> Tuple[Optional[Tuple[float, float, float]], Optional[Tuple[float, float, float]], float]:
    given = [n for n, v in (("moments", moments), ("summits", summits), ("surface", surface)) if v is not None]
    if len(given) != 1:
        raise ValueError(f"moments: give one of moments (m0, m2, m4), summits (sigma_s, radius, density) or surface (a Topography), got {len(given)}: {', '.join(given) or 'none'}")
    m = s = None
    area = None if nominal_area is None else _args.quantity("nominal_area", nominal_area, _args.AREA)
    if surface is not None:
        if not isinstance(surface, Topography):
            raise TypeError(f"surface: expected a Topography, got {_args.show(surface)}")
        stats = cast(Mapping[str, Any], surface.statistics())
        if not all(key in stats for key in MOMENT_KEYS):
            raise ValueError(f"surface: the map has {surface.missing_points} missing point(s) and so no spectral moments: fill them first (asperity.fill_missing)")
        m0, m2, m4 = (float(stats[key]) for key in MOMENT_KEYS)
        m = (m0, m2, m4)
        if area is None:
            area = surface.size[0] * surface.size[1]
    elif moments is not None:
        m = _args.triple("moments", moments, "the isotropic spectral moments", (("m0", _args.AREA), ("m2", _args.NUMBER), ("m4", _args.INVERSE_AREA)))
    else:
        s = _args.triple("summits", summits, "the summit statistics", (("sigma_s", _args.LENGTH), ("radius", _args.LENGTH), ("density", _args.INVERSE_AREA)))
    if area is None:
        raise ValueError("nominal_area: required with moments or summits: the nominal contact area in m^2 (or a string such as '1 mm^2')")
    return m, s, area


def static_friction(
    *,
    model: str,
    nominal_pressures: Pressures,
    nominal_area: Optional[Quantity] = None,
    material: Optional[Material] = None,
    composite_modulus: Optional[Quantity] = None,
    hardness: Optional[Quantity] = None,
    poisson_ratio: Optional[float] = None,
    moments: Optional[Tuple[float, float, float]] = None,
    summits: Optional[Tuple[Quantity, Quantity, Quantity]] = None,
    surface: Optional[Topography] = None,
    adhesion_energy: Optional[Quantity] = None,
    equilibrium_distance: Optional[Quantity] = None,
    parameters: Optional[LawParameters] = None,
    yield_strength: Optional[Quantity] = None,
    shear_strength: Optional[Quantity] = None,
) -> List[StaticFrictionRow]:
    """Statistical static friction coefficient μ_s of a rough surface against a rigid flat, as a
    study's statistical ``friction`` node computes it. ``model`` is a law of the registry with
    single-asperity laws: <<laws:statistical>> (equations in docs/friction-models.md);
    ``parameters`` overrides its parameters (SI numbers, choices by name, or quantities such as
    ``"90 deg"``), which are otherwise at the registry's defaults, as in a study: for
    ``"kogut_etsion"`` the literal KE 2004 polynomial (``static_friction_form: "literal"``),
    whose total can come out negative at a high plasticity index (``mu_s`` is then 0 and the
    model's value is in ``mu_s_computed``, as the tables report it); ``parameters=
    {"static_friction_form": "clipped"}`` clips it per asperity, as the quickstart study does.
    ``yield_strength`` Y (default: the material's, else Tabor's H/2.8) and ``shear_strength`` k
    (default: the material's, else Y/√3) are the softer body's, in Pa.

    Roughness, one of: a ``surface`` (a :class:`Topography`: its spectral moments, and its
    size as the default ``nominal_area``), the isotropic spectral ``moments`` (m0 in m², m2,
    m4 in 1/m², as :func:`surface_statistics` reports them), or ``summits`` (σ_s in m, radius R
    in m, density η in 1/m²). Material: a built-in name or mapping (``youngs_modulus``,
    ``poisson_ratio``, ``hardness``; the composite modulus against a rigid flat is
    E/(1 − ν²)), or the explicit ``composite_modulus``, ``hardness`` (Pa) and ``poisson_ratio``.
    Loads: ``nominal_pressures`` (Pa, at most H) over ``nominal_area`` (m²). Adhesion: Δγ in N/m
    and ε in m (defaults as in a study).

    Returns one dict per pressure: ``mu_s`` (never negative; None at a non-compressive load),
    ``mu_s_computed`` and ``mu_s_floored``, the forces ``normal_load_N``, ``external_load_N``,
    ``adhesion_force_N`` and ``friction_force_N``, ``real_area_m2``, ``d_star``, ``separation_m``,
    ``plasticity_index``, the number of contacting summits ``contacts`` and the share of the
    load beyond the friction law's validated range ``load_share_beyond_fit`` (the names of the
    ``friction`` table).
    """
    e, h, nu, y, k = _friction_material(material, composite_modulus, hardness, poisson_ratio)
    m, s, area = _roughness(moments, summits, surface, nominal_area)
    energy, distance = _adhesion(adhesion_energy, equilibrium_distance)
    rows = _native.static_friction(
        _model(model),
        e,
        h,
        nu,
        _args.quantities("nominal_pressures", nominal_pressures, _args.PRESSURE),
        area,
        m,
        s,
        energy,
        distance,
        *_law_options(parameters, yield_strength, shear_strength, y, k),
    )
    for row in rows:
        warn(summit_sentences(row["contacts"], row["nominal_pressure_Pa"]))
    return cast(List[StaticFrictionRow], rows)


def _at_step(result: Any, step: Optional[int]) -> Any:
    """``result`` itself (``step=None``), or its load step ``step`` (0 for the first, negative
    from the last) of a :func:`contact` result computed with ``fields="all"``."""
    if step is None:
        return result
    if not isinstance(result, Mapping) or "steps" not in result:
        raise ValueError(f"step: {step!r} needs the maps of every load step: run asperity.contact(..., fields='all')")
    steps = result["steps"]
    if isinstance(step, bool) or not isinstance(step, int):
        raise TypeError(f"step: expected a load step index (int), got {_args.show(step)}")
    if not -len(steps) <= step < len(steps):
        raise ValueError(f"step: {step} is out of range: the result has {len(steps)} load steps (0 to {len(steps) - 1})")
    return steps[step]


def _contact_fields(result: Any, keys: Sequence[str]) -> Dict[str, F64]:
    if not isinstance(result, Mapping):
        raise TypeError(f"result: expected the dict asperity.contact returns, got {_args.show(result)}")
    for key in keys:
        if key not in result:
            raise TypeError(f"result: expected the dict asperity.contact returns, with '{key}' (got keys: {', '.join(map(str, result))})")
    return {key: _args.heights(f"result['{key}']", result[key]) for key in keys}


def _friction_body(name: str, m: Material) -> Tuple[Tuple[float, float, float], Optional[float], Optional[float]]:
    """(E (Pa), ν, H (Pa)) of a material name or mapping with a hardness, and its yield and shear
    strengths (Pa, or None)."""
    b = body(name, m)
    if b["hardness"] is None:
        raise ValueError(f"{name}: needs a hardness (Pa) for the friction laws; give 'hardness' or a built-in 'name'")
    constants = (cast(float, b["youngs_modulus"]), cast(float, b["poisson_ratio"]), b["hardness"])
    return constants, b["yield_strength"], b["shear_strength"]


def per_spot_friction(
    result: Mapping[str, Any],
    composite_height: Union[Topography, F64],
    dx: Optional[Quantity] = None,
    dy: Optional[Quantity] = None,
    *,
    model: str,
    material: Optional[Material] = None,
    composite_modulus: Optional[Quantity] = None,
    hardness: Optional[Quantity] = None,
    poisson_ratio: Optional[float] = None,
    upper_material: Optional[Material] = None,
    upper_height: Optional[Union[Topography, F64]] = None,
    periodic: bool = True,
    connectivity: int = 4,
    adhesion_energy: Optional[Quantity] = None,
    equilibrium_distance: Optional[Quantity] = None,
    parameters: Optional[LawParameters] = None,
    yield_strength: Optional[Quantity] = None,
    shear_strength: Optional[Quantity] = None,
    step: Optional[int] = None,
) -> PerSpotResult:
    """Static friction of a :func:`contact` result spot by spot, in the one call a study's
    ``per_spot`` friction node makes: the connected contact spots of ``result["pressure"]``
    (``connectivity`` 4 or 8, wrapping around when ``periodic``), each with its load, area and
    paraboloid radius fitted to ``composite_height`` (a :class:`Topography` or heights in m at
    ``dx``, ``dy``: the lower heights against a flat, lower + upper for two surfaces), and the
    law ``model`` per spot, any law of the registry: <<laws:per_spot>> (parameters as in
    :func:`static_friction`; a junction's shear strength τ_s = c·k with ``shear_strength`` k in
    Pa); the Lennard-Jones adhesion across ``result["gap"]``. μ_s = ΣQ_i / (ΣP_i − F_a).

    Bodies: ``material`` is the lower body (a built-in name or a mapping with
    ``youngs_modulus``, ``poisson_ratio``, ``hardness``); with ``upper_material`` the upper body
    and ``upper_height`` its heights z₂ (m, measured towards the lower body, as passed to
    :func:`contact`; omitted: a flat), its deformation read from ``result["deformation_upper"]``;
    without it a rigid flat. Or, for one body against a rigid flat, the explicit
    ``composite_modulus``, ``hardness`` (Pa) and ``poisson_ratio``. The law ``"ploughing"``
    reads the harder body's deformed surface on each spot's loaded front, the upper body sliding
    along ``parameters["sliding_direction"]`` (an angle with its unit, e.g. ``"30 deg"``).

    Returns ``mu_s`` (never negative; None without a compressive net force), ``mu_s_computed``,
    ``mu_s_floored``, ``mu_deformation``, the totals ``normal_load_N``, ``friction_force_N``,
    ``deformation_force_N``, ``real_area_m2`` and ``adhesion_force_N``, the shares of the load
    beyond the law's validated range, without a radius, on merged spots and beyond the ploughing
    regime (``load_share_beyond_fit``, ``load_share_without_radius``, ``load_share_merged``,
    ``load_share_outside_regime``), for ploughing ``ploughing_body`` and ``mu_deformation_slope_baseline``, and per spot
    ``spot_normal_force_N``, ``spot_area_m2``, ``spot_radius_m`` (None without a convex fit),
    ``spot_summits``, ``spot_friction_force_N`` and ``spot_deformation_force_N``.

    ``step=i``: the friction at load step ``i`` of a result of ``contact(..., fields="all")``
    (negative counts from the last), the row ``i`` of a study's ``friction_curve``; by default
    the final step's maps (or those of the step dict given as ``result``).
    """
    result = _at_step(result, step)
    fields = _contact_fields(result, ("pressure", "gap", "deformation_lower", "plastic_penetration"))
    t, _ = as_topography("composite_height", composite_height, dx, dy)
    if t.heights.shape != fields["pressure"].shape:
        raise ValueError(
            f"composite_height: shape {t.heights.shape} differs from result['pressure']'s shape {fields['pressure'].shape}; pass the heights the contact was solved on"
        )
    connectivity = _args.integer("connectivity", connectivity, 4, "4 or 8 (neighbours)")
    if connectivity not in (4, 8):
        raise ValueError(f"connectivity: {connectivity!r} is out of range: expected 4 or 8 (neighbours)")
    if material is not None and all(v is None for v in (composite_modulus, hardness, poisson_ratio)):
        lower, y, k = _friction_body("material", material)
    else:
        e, h, nu, y, k = _friction_material(material, composite_modulus, hardness, poisson_ratio)
        lower = (e * (1.0 - nu * nu), nu, h)
    upper = None if upper_material is None else _friction_body("upper_material", upper_material)[0]
    if upper is None and upper_height is not None:
        raise ValueError("upper_height: give upper_material with it (the upper body's material)")
    z2 = None if upper_height is None else as_topography("upper_height", upper_height, t.dx, t.dy)[0].heights
    u2 = None if upper is None or result.get("deformation_upper") is None else _args.heights("result['deformation_upper']", result["deformation_upper"])
    energy, distance = _adhesion(adhesion_energy, equilibrium_distance)
    out = _native.per_spot_friction(
        fields["pressure"],
        fields["gap"],
        t.heights,
        fields["deformation_lower"],
        fields["plastic_penetration"],
        t.dx,
        t.dy,
        _model(model),
        lower,
        upper,
        z2,
        u2,
        _args.boolean("periodic", periodic),
        connectivity == 8,
        energy,
        distance,
        *_law_options(parameters, yield_strength, shear_strength, y, k),
    )
    return cast(PerSpotResult, dict(out))


def per_summit_friction(
    result: Mapping[str, Any],
    composite_height: Union[Topography, F64],
    dx: Optional[Quantity] = None,
    dy: Optional[Quantity] = None,
    *,
    model: str = "kogut_etsion",
    material: Optional[Material] = None,
    composite_modulus: Optional[Quantity] = None,
    hardness: Optional[Quantity] = None,
    poisson_ratio: Optional[float] = None,
    periodic: bool = True,
    adhesion_energy: Optional[Quantity] = None,
    equilibrium_distance: Optional[Quantity] = None,
    parameters: Optional[LawParameters] = None,
    yield_strength: Optional[Quantity] = None,
    step: Optional[int] = None,
) -> PerSummitResult:
    """Static friction of a :func:`contact` result summit by summit, as a study's ``per_summit``
    friction node: the summits (8-neighbour maxima, periodic when ``periodic``) of
    ``composite_height`` (a :class:`Topography` or heights in m at ``dx``, ``dy``: the lower
    heights against a flat, lower + upper for two surfaces), each with its radius and its
    interference from the solution (the deformation of both bodies plus the plastic penetration
    where the pressure is positive, minus the gap elsewhere), and the single-asperity laws of
    ``model``, any law with them: <<laws:per_summit>> (parameters as in
    :func:`static_friction`). μ_s = ΣF_f / Σ(F_n − F_a). Material as in
    :func:`static_friction`.

    Returns ``mu_s`` (never negative; None without a compressive net force), ``mu_s_computed``,
    ``mu_s_floored``, the totals ``normal_load_N``, ``adhesion_force_N`` and ``friction_force_N``,
    the share of the load beyond the laws' validated range ``load_share_beyond_fit`` and per summit
    ``summit_radius_m``, ``summit_interference_m`` (m, < 0: a gap), ``summit_normal_force_N``,
    ``summit_friction_force_N`` and ``summit_adhesion_force_N``.

    ``step=i``: the friction at load step ``i`` of a result of ``contact(..., fields="all")``
    (negative counts from the last), the row ``i`` of a study's ``friction_curve``; by default
    the final step's maps (or those of the step dict given as ``result``).
    """
    result = _at_step(result, step)
    fields = _contact_fields(result, ("pressure", "gap", "deformation_lower", "plastic_penetration"))
    deformation = fields["deformation_lower"]
    if result.get("deformation_upper") is not None:
        deformation = deformation + _args.heights("result['deformation_upper']", result["deformation_upper"])
    t, _ = as_topography("composite_height", composite_height, dx, dy)
    e, h, nu, y, _k = _friction_material(material, composite_modulus, hardness, poisson_ratio)
    law_parameters, y_strength, _ = _law_options(parameters, yield_strength, None, y, None)
    energy, distance = _adhesion(adhesion_energy, equilibrium_distance)
    out = _native.per_summit_friction(
        t.heights,
        fields["pressure"],
        fields["gap"],
        deformation,
        fields["plastic_penetration"],
        t.dx,
        t.dy,
        _model(model),
        e,
        h,
        nu,
        _args.boolean("periodic", periodic),
        energy,
        distance,
        law_parameters,
        y_strength,
    )
    return cast(PerSummitResult, dict(out))


def document_laws(functions: Sequence[Callable[..., Any]]) -> None:
    """Fills each ``<<laws:METHOD>>`` of the functions' docstrings with the registry's laws
    that support the method."""
    for f in functions:
        doc = f.__doc__ or ""
        for method in (STATISTICAL, PER_SUMMIT, PER_SPOT):
            doc = doc.replace(f"<<laws:{method}>>", _named_laws(method))
        f.__doc__ = doc


document_laws((static_friction, per_spot_friction, per_summit_friction))
