"""What a scene calls the quantities it computes: names, units and the order of its tables.

An angle's position is written in degrees at the edges, so a scene calls
it ``<name>_deg`` (``theta3_deg``) and gives its unit as ``deg``; every
other quantity keeps its :class:`~numkin.quantities.Quantity` name and unit
(``omega_theta3`` [rad/s], ``x_P`` [mm]). :func:`scene_quantities` lists
what a scene computes, as its tables and checks take it.

Examples
--------
>>> from numkin.schema import load_scene
>>> from numkin.assemble import build_mechanism
>>> scene = load_scene("homework")
>>> list(scene_quantities(scene, build_mechanism(scene)))[:3]
['phi_deg', 'omega_phi', 'alpha_phi']
"""

from __future__ import annotations

__all__ = ["scene_key", "scene_unit", "scene_quantities", "quantity_names", "scene_quantity"]


def scene_key(quantity) -> str:
    """A :class:`~numkin.quantities.Quantity`'s name in a scene: an angle's position is ``<u>_deg``.

    Examples
    --------
    >>> from numkin.quantities import Quantity
    >>> scene_key(Quantity("theta3", 0, "angle")), scene_key(Quantity("theta3", 1, "angle"))
    ('theta3_deg', 'omega_theta3')
    """
    return f"{quantity.name}_deg" if quantity.in_degrees else quantity.name


def scene_unit(quantity) -> str:
    """The unit of a quantity's values in a scene's output: degrees for an angle's position, else its own."""
    return "deg" if quantity.in_degrees else quantity.unit


def scene_quantities(scene, mech, *, all_unknowns: bool = False, all_points: bool = False,
                     orders=None) -> dict:
    """Scene name -> :class:`~numkin.quantities.Quantity` of what the scene computes, in table order.

    Per unknown its position, velocity and acceleration (those the scene
    wants), then the same per derived quantity, then per point its x, y
    coordinates and their derivatives.
    """
    from .quantities import catalogue
    from .schema import QUANTITIES

    unknowns = mech.unknowns if all_unknowns or scene.unknowns is None else scene.unknowns
    points = tuple(mech.points) if all_points else scene.points
    if orders is None:
        orders = [k for k, kind in enumerate(QUANTITIES) if scene.wants(kind)]
    every = catalogue(mech, sorted(orders), points=bool(points)).values()  # by order, then unknown or point
    out = {}
    derived = [(d, False) for d in mech.derived]
    for of, is_point in [(u, False) for u in unknowns] + derived + [(p, True) for p in points]:
        for q in every:
            if q.of == of and q.is_point == is_point:
                out.setdefault(scene_key(q), q)
    return out


def quantity_names(scene, mech, *, all_unknowns: bool = False) -> list[str]:
    """Names of the quantities the scene computes (see :mod:`numkin.scene`)."""
    return list(scene_quantities(scene, mech, all_unknowns=all_unknowns))


def scene_quantity(scene, mech, key: str):
    """The :class:`~numkin.quantities.Quantity` a scene name denotes (any order, unknown or point), or None."""
    return scene_quantities(scene, mech, all_unknowns=True, all_points=True, orders=(0, 1, 2)).get(key)
