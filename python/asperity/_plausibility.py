"""Plausibility of the quantities the array functions take as plain SI numbers, where a unit
mistake (heights or spacings in µm, a modulus in GPa, a pressure in MPa) would otherwise give a
number without a word.

Besides these, every map goes through the surface node's own checks (``nodes::scale_checks``,
``nodes::surface_artifact``: the spacing, heights beyond the field of view, an rms slope Sdq
outside [1e-4, 10]) and every contact through the contact node's (a nominal pressure not below
the composite modulus fails; a coarse grid or a composite slope above 0.5 is flagged). Each rule
is listed, with its reason, in docs/python.md ("Units and plausibility").
"""

from __future__ import annotations

from typing import List

#: Finest plausible sample spacing (m): optical and stylus instruments sample at 0.05–10 µm,
#: an AFM at nanometres; a finer spacing is a spacing converted twice (µm → m → m).
MIN_SPACING = 1e-9

#: Coarsest plausible sample spacing of a roughness map (m): 1 mm, a hundred times the
#: coarsest instrument sampling; a coarser one is a spacing in µm or mm given as metres.
MAX_SPACING = 1e-3

#: Smallest plausible modulus, hardness or flow pressure (Pa): 1 MPa, below the Young's modulus
#: of soft rubber; a smaller value is one given in GPa or MPa as a plain number in Pa.
MIN_STIFFNESS = 1e6


def spacing_sentences(dx: float, dy: float) -> List[str]:
    """A sentence per sample spacing outside [MIN_SPACING, MAX_SPACING]."""
    out = []
    for name, d in (("dx", dx), ("dy", dy)):
        if d < MIN_SPACING:
            out.append(
                f"{name} = {d:g} m is finer than a nanometre, finer than any instrument samples a "
                "rough surface: was the spacing converted to metres twice? (give it in m, or as a "
                "string such as '0.5 um')"
            )
        elif d > MAX_SPACING:
            out.append(
                f"{name} = {d:g} m is coarser than a millimetre, coarser than a roughness map is "
                "sampled: was it given in um or mm as a plain number? (give it in m, or as a "
                "string such as '0.5 um'; heights too are in m)"
            )
    return out


def stiffness_sentences(name: str, value: float) -> List[str]:
    """A sentence when a modulus, hardness or flow pressure ``value`` (Pa) is below 1 MPa."""
    if value >= MIN_STIFFNESS:
        return []
    return [
        f"{name} = {value:g} Pa is below 1 MPa, softer than rubber: was it given in GPa or MPa as "
        "a plain number? (give it in Pa, or as a string such as '210 GPa')"
    ]


#: Fewest grid points a contact must cover to be resolved: a spot of more than one pixel (2
#: points across) spans 4 points, the reasoning of the contact node's smallest grid (8 points a
#: side). Fewer is what a pressure in MPa given as a plain number in Pa produces (one point in
#: contact, 0 iterations).
MIN_CONTACT_POINTS = 4

#: Fewest contacting summits (expected number over the nominal area) a statistical result
#: describes: the Greenwood–Williamson sums are means over many summits in contact.
MIN_CONTACTING_SUMMITS = 1.0


def contact_sentences(area_fraction: float, points: int, nominal_pressure: float) -> List[str]:
    """A sentence when the final step's contact covers fewer than MIN_CONTACT_POINTS points."""
    touching = area_fraction * points
    if touching >= MIN_CONTACT_POINTS:
        return []
    return [
        f"the contact at {nominal_pressure:g} Pa covers {touching:.3g} grid point(s) (A/A0 = "
        f"{area_fraction:.3g}), fewer than the {MIN_CONTACT_POINTS} a resolved spot needs: the grid "
        "does not resolve it; was the pressure given in MPa as a plain number? (give it in Pa, "
        "or as a string such as '20 MPa')"
    ]


def summit_sentences(contacting_summits: float, nominal_pressure: float) -> List[str]:
    """A sentence when fewer than MIN_CONTACTING_SUMMITS summits are expected in contact."""
    if contacting_summits >= MIN_CONTACTING_SUMMITS:
        return []
    return [
        f"at {nominal_pressure:g} Pa the statistical model expects {contacting_summits:.3g} "
        "contacting summit(s) over the nominal area, fewer than one: its sums over summits "
        "describe no contact; was the pressure given in MPa as a plain number (give it in Pa, or "
        "as a string such as '20 MPa'), or is the nominal area too small?"
    ]
