"""The registry of ready-made linkages: every spec against the builder it describes, and the recipe
for adding a linkage (one spec, registered in one place, run through a scene).

The table ``EXPECTED`` below is written by hand from the builders' docstrings: a change of a
dimension's name or kind, of an unknown, of the input or of the length unit shows up here.
The added linkage is checked against circle intersections computed in this file.
"""

from __future__ import annotations

import inspect
import math
import textwrap

import numpy as np
import pytest

from numkin import linkages
from numkin.linkages import Dimension, LinkageSpec
from numkin.scene import SceneError, load_scene, run_scene

# name -> (dimensions as (name, kind), input, unknowns as (name, kind), length unit, named points)
EXPECTED = {
    "four_bar": (
        [("ground", "length"), ("crank", "length"), ("coupler", "length"), ("rocker", "length")],
        "theta2", [("theta3", "angle"), ("theta4", "angle")], "mm", ["O2", "A", "B", "O4"],
    ),
    "slider_crank": (
        [("crank", "length"), ("rod", "length"), ("offset", "signed")],
        "theta", [("theta3", "angle"), ("x", "length")], "mm", ["O", "A", "P"],
    ),
    "quick_return": (
        [("r1", "length"), ("r2", "length"), ("r6", "length")],
        "theta2", [("r3", "length"), ("theta3", "angle"), ("r4", "length"), ("r5", "length")], "mm",
        ["O1", "O2", "A", "B", "C"],
    ),
    "six_bar": (
        [("crank", "length"), ("coupler", "length"), ("o4b", "length"), ("bc", "length"), ("o4c", "length"),
         ("rod", "length"), ("o4", "pair"), ("slider_y", "signed")],
        "theta2", [("theta3", "angle"), ("theta4", "angle"), ("theta5", "angle"), ("x", "length")], "cm",
        ["O2", "A", "O4", "B", "C", "D"],
    ),
    "chained_four_bars": (
        [("fixed1", "length"), ("input1", "length"), ("coupler1", "length"), ("output1", "length"),
         ("fixed2", "length"), ("input2", "length"), ("coupler2", "length"), ("output2", "length"),
         ("offset", "angle")],
        "theta", [("phi", "angle"), ("psi", "angle"), ("beta", "angle"), ("gamma", "angle")], "in",
        ["C", "B", "A", "D", "E", "F", "G"],
    ),
}
#: Dimensions for the linkages whose builders have no defaults.
SAMPLE = {"four_bar": dict(ground=4, crank=1, coupler=3, rocker=3), "slider_crank": dict(crank=80, rod=200)}


def test_the_registry_holds_the_five_ready_made_linkages():
    assert list(EXPECTED) == list(linkages.SPECS)[:5]


@pytest.mark.parametrize("name", list(EXPECTED))
def test_spec_states_the_dimensions_units_and_unknowns(name):
    dims, input_name, unknowns, unit, points = EXPECTED[name]
    spec = linkages.spec(name)
    assert [(d.name, d.kind) for d in spec.dimensions] == dims
    assert spec.input == input_name and list(spec.unknowns) == unknowns
    assert spec.length_unit == unit and list(spec.points) == points
    for d in spec.dimensions:
        assert d.unit(unit) == ("rad" if d.kind == "angle" else unit)
        assert d.scene_key == (f"{d.name}_deg" if d.kind == "angle" else d.name)


@pytest.mark.parametrize("name", list(linkages.SPECS))
def test_spec_describes_its_builder(name):
    """Every registered linkage, a new one included: its spec agrees with its builder's signature and with
    the mechanism it builds (built from its defaults, or from SAMPLE where it has none)."""
    spec = linkages.spec(name)
    params = inspect.signature(spec.build).parameters
    # the dimensions are the builder's leading keywords, with the spec's defaults
    assert list(params)[: len(spec.dimensions)] == [d.name for d in spec.dimensions]
    for d in spec.dimensions:
        default = params[d.name].default
        assert (d.default is None) == (default is inspect.Parameter.empty)
        if d.default is not None:
            assert tuple(np.atleast_1d(default)) == pytest.approx(tuple(np.atleast_1d(d.default)))
    assert params["length_unit"].default == spec.length_unit
    assert ("branch" in params) == bool(spec.branches)
    if spec.branches:
        assert params["branch"].default == spec.branches[0]
    assert getattr(linkages, name) is spec.build
    if name not in SAMPLE and any(d.default is None for d in spec.dimensions):
        return  # no dimensions to build it from: the signature alone is checked
    mech = spec.build(**SAMPLE.get(name, {}))
    assert linkages.spec_of(mech) is spec
    assert tuple(mech.unknowns) == spec.unknown_names and tuple(mech.angles) == spec.angles
    assert str(mech.input_symbol) == spec.input and mech.length_unit == spec.length_unit
    assert list(mech.points) == list(spec.points)
    assert [tuple(link) for link in mech.links] == [tuple(link) for link in spec.links]
    assert tuple(mech.ground) == tuple(spec.ground)


def test_spec_lookup_suggests_the_nearest_name():
    with pytest.raises(ValueError, match="did you mean 'four_bar'"):
        linkages.spec("four_bars")
    assert linkages.spec_of(object()) is None


def test_a_scene_leaves_out_dimensions_with_defaults_in_its_own_unit(tmp_path):
    path = tmp_path / "six-bar-mm.toml"
    path.write_text('[scene]\ndescription = "d"\n[mechanism]\nlinkage = "six_bar"\nunit = "mm"\n'
                    '[input]\nstop_deg = 10\n')
    scene = load_scene(path)
    # the defaults are the builder's, in cm: 10 mm per cm
    assert scene.dimensions["crank"] == pytest.approx(10.0) and scene.dimensions["o4"] == pytest.approx((37.0, -20.0))
    x_mm = run_scene(scene).sweep["x"]
    x_cm = linkages.six_bar().sweep(np.radians(np.arange(0.0, 11.0)))["x"]
    np.testing.assert_allclose(x_mm, 10.0 * x_cm, rtol=1e-12, atol=1e-12)


# ------------------------------------------------------- recipe: add a linkage
def offset_crank_rocker(crank, coupler, rocker, o4, *, branch="open", length_unit="mm"):
    """A four-bar whose rocker pivot O4 is anywhere: ``r2 e^{i t2} + r3 e^{i t3} - r4 e^{i t4} - O4 = 0``."""
    import sympy as sp

    from numkin import Loop, Mechanism
    from numkin.linkages.base import finish, finite, length
    from numkin.linkages.four_bar import closed_form

    r2, r3, r4 = length("crank", crank), length("coupler", coupler), length("rocker", rocker)
    ox, oy = finite("o4[0]", o4[0]), finite("o4[1]", o4[1])
    sign = 1.0 if branch == "open" else -1.0
    t2, t3, t4 = sp.symbols("theta2 theta3 theta4", real=True)
    R2, R3, R4, OX, OY = sp.symbols("r2 r3 r4 o4x o4y", real=True)
    loop = Loop.from_vectors([(R2, t2), (R3, t3), (-R4, t4), (-OX, 0), (-OY, sp.pi / 2)], [t3, t4], name="O2-A-B-O4")
    tilt, ground = math.atan2(oy, ox), math.hypot(ox, oy)

    def guess(theta2):  # the four-bar's closed form, turned by the ground's angle
        a, b = closed_form(theta2 - tilt, ground, r2, r3, r4, sign)
        return {"theta3": float(a) + tilt, "theta4": float(b) + tilt}

    return finish(Mechanism(
        [loop], t2, {R2: r2, R3: r3, R4: r4, OX: ox, OY: oy}, name="offset crank-rocker", guess=guess,
        length_unit=length_unit,
        points={"O2": (0, 0), "A": (R2 * sp.cos(t2), R2 * sp.sin(t2)),
                "B": (OX + R4 * sp.cos(t4), OY + R4 * sp.sin(t4)), "O4": (OX, OY)},
        links=OFFSET_SPEC.links, ground=OFFSET_SPEC.ground,
    ), OFFSET_SPEC)


OFFSET_SPEC = LinkageSpec(
    name="offset_crank_rocker", build=offset_crank_rocker,
    summary="four-bar with its rocker pivot O4 at (x, y)",
    dimensions=(Dimension("crank", "length"), Dimension("coupler", "length"), Dimension("rocker", "length"),
                Dimension("o4", "pair", "rocker pivot (x, y)")),
    input="theta2", unknowns=(("theta3", "angle"), ("theta4", "angle")), branches=("open", "crossed"),
    points=("O2", "A", "B", "O4"), links=(("O2", "A"), ("A", "B"), ("B", "O4")), ground=("O2", "O4"),
)


@pytest.fixture
def offset_linkage():
    linkages.register(OFFSET_SPEC)
    try:
        yield OFFSET_SPEC
    finally:
        linkages.SPECS.pop(OFFSET_SPEC.name, None)


def circle_intersection(c1, r1, c2, r2, side):
    """The point at r1 from c1 and r2 from c2, left (side +1) or right (-1) of c1 -> c2."""
    delta = c2 - c1
    d = np.hypot(delta[0], delta[1])
    u = delta / d
    along = (r1**2 - r2**2 + d**2) / (2 * d)
    h = np.sqrt(r1**2 - along**2)
    return c1 + along * u + side * h * np.array([-u[1], u[0]])


@pytest.mark.parametrize("branch, side", [("open", 1.0), ("crossed", -1.0)])
def test_an_added_linkage_runs_through_a_scene(offset_linkage, tmp_path, branch, side):
    path = tmp_path / "offset.toml"
    path.write_text(textwrap.dedent(f"""
        [scene]
        description = "crank-rocker with a raised rocker pivot"
        [mechanism]
        linkage = "offset_crank_rocker"
        unit = "cm"
        branch = "{branch}"
        [mechanism.dimensions]
        crank = "10 mm"
        coupler = 3
        rocker = 3
        o4 = [3.2, 2.4]
        [input]
        step_deg = 2
        [output]
        points = ["B"]
        tables = ["positions"]
    """))
    result = run_scene(path, out=tmp_path / "out")
    sweep = result.sweep
    inputs = sweep.inputs
    a = np.array([np.cos(inputs), np.sin(inputs)])
    o4 = np.array([[3.2], [2.4]])
    b = circle_intersection(a, 3.0, o4, 3.0, side)
    theta3 = np.arctan2(b[1] - a[1], b[0] - a[0])
    theta4 = np.arctan2(b[1] - o4[1], b[0] - o4[0])
    for got, ref in ((sweep["theta3"], theta3), (sweep["theta4"], theta4)):
        np.testing.assert_allclose(np.angle(np.exp(1j * (got - ref))), 0.0, atol=1e-10)
    np.testing.assert_allclose(sweep.points()["B"], b, atol=1e-10)
    assert (tmp_path / "out" / "offset-positions.csv").is_file()


def test_a_registered_linkage_is_validated_like_the_others(offset_linkage, tmp_path):
    path = tmp_path / "offset.toml"
    path.write_text('[scene]\ndescription = "d"\n[mechanism]\nlinkage = "offset_crank_rocker"\n'
                    '[mechanism.dimensions]\ncrank = 1\ncoupler = 3\nrocker = 3\n')
    with pytest.raises(SceneError, match="missing dimension 'o4' of offset_crank_rocker"):
        load_scene(path)
    with pytest.raises(ValueError, match="already registered"):
        linkages.register(LinkageSpec(**{**OFFSET_SPEC.__dict__, "summary": "another"}))


def test_register_refuses_a_spec_whose_drawing_names_no_point():
    bad = LinkageSpec(**{**OFFSET_SPEC.__dict__, "name": "bad_linkage", "ground": ("O2", "Q")})
    with pytest.raises(ValueError, match="'Q'"):
        linkages.register(bad)
    assert "bad_linkage" not in linkages.SPECS


def test_a_linkage_module_dropped_into_the_package_is_found_with_its_builder(tmp_path, monkeypatch):
    """The README's recipe: one module in numkin/linkages/ whose builder is then numkin.linkages.<name>
    (not the module of that name) and whose spec scenes find; positions against circle intersections."""
    import importlib
    import sys
    import types

    source = textwrap.dedent('''
        import sympy as sp
        from numkin import Loop, Mechanism
        from .base import Dimension, LinkageSpec, finish, length

        def dropped_four_bar(ground, crank, coupler, rocker, *, length_unit="mm"):
            r1, r2, r3, r4 = (length(n, v) for n, v in
                              (("ground", ground), ("crank", crank), ("coupler", coupler), ("rocker", rocker)))
            t2, t3, t4 = sp.symbols("theta2 theta3 theta4", real=True)
            R1, R2, R3, R4 = sp.symbols("r1 r2 r3 r4", positive=True)
            loop = Loop.from_vectors([(R2, t2), (R3, t3), (-R4, t4), (-R1, 0)], [t3, t4], name="O2-A-B-O4")
            return finish(Mechanism([loop], t2, {R1: r1, R2: r2, R3: r3, R4: r4}, name="dropped",
                                    guess={"theta3": 0.5, "theta4": 2.0}, length_unit=length_unit,
                                    points={"O2": (0, 0), "A": (R2 * sp.cos(t2), R2 * sp.sin(t2)),
                                            "B": (R1 + R4 * sp.cos(t4), R4 * sp.sin(t4)), "O4": (R1, 0)},
                                    links=SPEC.links, ground=SPEC.ground), SPEC)

        SPEC = LinkageSpec(
            name="dropped_four_bar", build=dropped_four_bar, summary="a four-bar dropped in as a module",
            dimensions=tuple(Dimension(n, "length") for n in ("ground", "crank", "coupler", "rocker")),
            input="theta2", unknowns=(("theta3", "angle"), ("theta4", "angle")),
            points=("O2", "A", "B", "O4"), links=(("O2", "A"), ("A", "B"), ("B", "O4")), ground=("O2", "O4"),
        )
    ''')
    (tmp_path / "dropped_four_bar.py").write_text(source)
    monkeypatch.setattr(linkages, "__path__", [*linkages.__path__, str(tmp_path)])
    try:
        linkages._discover()
        assert not isinstance(linkages.dropped_four_bar, types.ModuleType)
        mech = linkages.dropped_four_bar(4.0, 1.0, 3.0, 3.0)
        assert linkages.spec_of(mech).name == "dropped_four_bar"
        t = np.radians([0.0, 60.0, 90.0])
        s = mech.sweep(t)
        for k, theta in enumerate(t):
            a = np.array([math.cos(theta), math.sin(theta)])
            b = circle_intersection(a, 3.0, np.array([4.0, 0.0]), 3.0, 1.0)
            assert math.atan2(*(b - np.array([4.0, 0.0]))[::-1]) == pytest.approx(s["theta4"][k], abs=1e-12)
    finally:
        linkages.SPECS.pop("dropped_four_bar", None)
        if hasattr(linkages, "dropped_four_bar"):
            delattr(linkages, "dropped_four_bar")
        sys.modules.pop("numkin.linkages.dropped_four_bar", None)
        importlib.invalidate_caches()
