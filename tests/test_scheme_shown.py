"""How a scheme is shown -- its table label, caption prose, figure style and marker, default membership -- is
read from its Scheme, so a scheme registered at run time is shown by the same rules as a built-in one.

Independent references: the lists that numkin.compare, the round-off table and the figures wrote out by hand
before these facts were put on the schemes, and the end points of a stencil counted from its offsets.
"""

from __future__ import annotations

import importlib
import math

import pytest

from numkin import compare, linkages, report, schemes, stability
from numkin.derivatives import SCHEMES

style = importlib.import_module("numkin.figures.style")
registries = importlib.import_module("numkin.figures.registries")


@pytest.fixture
def registered():
    """Names registered by one test, unregistered after it (second derivatives first)."""
    names = []
    yield names
    for name in sorted(names, key=lambda n: -schemes.REGISTRY[n].derivative):
        schemes.unregister(name)


# ------------------------------------------------------------------ the defaults, derived from `default` and partners
def test_the_derived_defaults_are_the_lists_written_out_before():
    assert compare.DEFAULT_SCHEMES[1] == ("forward", "centred", "five_point")
    assert compare.DEFAULT_SCHEMES[2] == ("forward_of_forward", "second_difference", "five_point_second")
    assert schemes.default_schemes(1, periodic=True)[-1] == "spectral"
    assert schemes.default_schemes(2, periodic=True)[-1] == "spectral_second"
    assert report.ROUNDOFF_SCHEMES == ("forward", "centred", "five_point", "second_difference", "complex_step")
    assert report.ROUNDOFF_SCHEMES[:4] == ("forward", "centred", "five_point", "second_difference")


def test_a_default_scheme_joins_every_default_list_until_it_is_unregistered(registered):
    registered.append(schemes.register("seven_point", range(-3, 4), 1, default=True).name)
    assert compare.DEFAULT_SCHEMES[1][-1] == "seven_point"
    assert schemes.default_schemes(1, periodic=True)[-2:] == ("seven_point", "spectral")  # periodic-only last
    assert report.ROUNDOFF_SCHEMES[-2:] == ("complex_step", "seven_point")
    schemes.unregister(registered.pop())
    assert "seven_point" not in compare.DEFAULT_SCHEMES[1] and "seven_point" not in report.ROUNDOFF_SCHEMES


def test_a_registered_first_derivative_after_its_second_pairs_them_in_the_defaults(registered):
    """A first-derivative scheme registered after a second-derivative one of its span and order takes it as
    partner, and so brings it into the defaults of an acceleration."""
    second = schemes.register("wide_second", (-3, 0, 3), 2, partner="centred")
    registered.append(second.name)
    first = schemes.register("wide_first", (-3, 0, 3), 1, default=True)
    registered.append(first.name)
    assert first.partner == "wide_second"
    assert compare.DEFAULT_SCHEMES[2][-1] == "wide_second"


def test_a_scheme_not_marked_default_is_in_no_default_list(registered):
    registered.append(schemes.register("seven_point", range(-3, 4), 1).name)
    assert "seven_point" not in compare.DEFAULT_SCHEMES[1] and "seven_point" not in report.ROUNDOFF_SCHEMES


# ------------------------------------------------------------------ labels: tables write them, figures read them back
def test_the_complex_step_is_labelled_once_and_found_by_its_label():
    cs = schemes.REGISTRY["complex_step"]
    assert cs.label == "complex step" and schemes.by_label("complex step") is cs
    assert schemes.by_label("complex_step") is cs and schemes.by_label("analytic") is None
    assert all(s.label == s.name for s in SCHEMES.values())  # the tables show the others by name
    assert registries.family_of("complex step") == registries.family_of("complex_step") == "complex_step"


def test_tables_write_a_schemes_label_and_the_figure_reads_it_back(registered):
    registered.append(schemes.register("seven_point", range(-3, 4), 1, label="seven-point (7 samples)").name)
    mech = linkages.slider_crank(80, 200)
    ro = report.roundoff_table(mech, quantity="x", check_angle=math.radians(40),
                               schemes=("seven_point", "complex_step"))
    assert list(ro["scheme"]) == ["seven-point (7 samples)", "complex step"]
    assert set(ro.attrs["scan"]) == {"h [rad]", "seven-point (7 samples)", "complex step"}
    assert style.source_style("seven-point (7 samples)", 2) == style.source_style("seven_point", 2)
    wp = report.work_precision_table(mech, omega=1.0, quantity="x", grids=(36,), schemes=("seven_point",))
    assert list(wp["method"]) == ["analytic", "complex step", "seven-point (7 samples)", "analytic", "complex step"]


def test_a_label_names_one_scheme_only(registered):
    with pytest.raises(ValueError, match="names scheme 'complex_step'"):
        schemes.register("seven_point", range(-3, 4), 1, label="complex step")
    with pytest.raises(ValueError, match="names scheme 'centred'"):
        schemes.register("seven_point", range(-3, 4), 1, label="centred")
    with pytest.raises(ValueError, match="style must be a mapping"):
        schemes.register("seven_point", range(-3, 4), 1, style="red")
    with pytest.raises(ValueError, match="marker must be"):
        schemes.register("seven_point", range(-3, 4), 1, marker=("o", 4))
    assert "seven_point" not in schemes.REGISTRY


# ------------------------------------------------------------------ figure styles, read from the schemes
def test_a_registered_scheme_gets_a_style_and_marker_of_its_own(registered):
    registered.append(schemes.register("seven_point", range(-3, 4), 1).name)
    fixed = {s["color"] for s in style.SOURCE_STYLE.values()}
    st = style.source_style("seven_point", 0)
    assert st == {"color": style.SOURCE_CYCLE[0], "linestyle": "-.", "linewidth": 1.5}
    assert st["color"] not in fixed and "seven_point" not in style.SOURCE_STYLE
    assert style.SOURCE_MARKERS["seven_point"] == ("o", 4.5, True)


def test_a_declared_style_and_marker_are_used_as_declared(registered):
    registered.append(schemes.register("seven_point", range(-3, 4), 1, style={"color": "#123456", "linewidth": 2.0},
                                       marker=("P", 6.0, False)).name)
    assert style.source_style("seven_point", 4) == {"color": "#123456", "linewidth": 2.0}
    assert style.SOURCE_STYLE["seven_point"] == {"color": "#123456", "linewidth": 2.0}
    mk = style.marker_style("seven_point", "red")
    assert (mk["marker"], mk["markersize"], mk["markerfacecolor"]) == ("P", 6.0, "none")


def test_the_family_partner_is_drawn_in_the_familys_colour_and_dashed():
    for first in ("forward", "centred", "five_point", "spectral"):
        second = SCHEMES[first].partner
        one, two = style.source_style(first, 0), style.source_style(second, 1)
        assert two["color"] == one["color"]
        assert style.SOURCE_MARKERS[second][0] == style.SOURCE_MARKERS[first][0]
    assert style.source_style("five_point_second", 0)["linestyle"] == style.SECOND_DASH
    assert style.source_style("second_difference", 0)["linestyle"] == "-"  # declared: solid, as centred


def test_a_registered_second_derivative_beside_its_familys_partner_has_a_colour_of_its_own(registered):
    """A second derivative of the centred family other than the second difference is not drawn in centred's
    colour (it would be told from the second difference only by its dashes, which a legend's handles hide)."""
    registered.append(schemes.register("wide_second", (-3, 0, 3), 2, partner="centred").name)
    names = [n for n, s in SCHEMES.items() if s.derivative == 2]
    colours = [style.source_style(n, k)["color"] for k, n in enumerate(names)]
    assert len(set(colours)) == len(colours), dict(zip(names, colours))
    assert style.source_style("wide_second", 0)["linestyle"] == style.SECOND_DASH


def test_a_scheme_declared_in_built_in_alone_gets_a_style(monkeypatch):
    monkeypatch.setitem(schemes.BUILT_IN, "centred_seven", dict(offsets=tuple(range(-3, 4)), derivative=1))
    monkeypatch.setattr(schemes, "_REGISTRY", {})
    monkeypatch.setattr(schemes, "_LOADED", False)
    assert style.source_style("centred_seven", 1)["color"] == style.SOURCE_CYCLE[1]
    assert style.SOURCE_MARKERS["centred_seven"] == ("o", 4.5, True)


def test_the_cycle_has_none_of_the_declared_colours():
    declared = {dict(s.style)["color"] for s in schemes.REGISTRY.values() if "color" in dict(s.style)}
    assert declared and not declared & set(style.SOURCE_CYCLE)


# ------------------------------------------------------------------ the stability caption's end points
@pytest.mark.parametrize("offsets, words", [
    ((-3, -2, -1, 0, 1, 2, 3), "three at each end for seven point"),
    ((0, 1, 2, 3), "the last three for seven point"),
    ((-1, 0, 1, 2), "the first and the last two for seven point"),
    ((-2, -1, 0), "the first two for seven point"),
])
def test_the_stability_caption_counts_a_schemes_end_points_from_its_offsets(registered, offsets, words):
    registered.append(schemes.register("seven_point", offsets, 1).name)
    table = stability.run_suite(["cannot assemble (10, 6, 1, 1)"], schemes=["centred", "seven_point"])
    caption = table.attrs["caption"]
    assert "the first and last for centred" in caption and words in caption


def test_the_stability_caption_names_a_family_together_only_where_it_shares_one_reach():
    text = stability._ends_text([SCHEMES[n] for n in ("five_point", "five_point_second", "centred")])
    assert text == " (the first and last for centred, two at each end for the five-point schemes)"
    text = stability._ends_text([SCHEMES[n] for n in ("forward", "forward_of_forward", "spectral")])
    assert text == " (the last for forward, the last two for forward of forward)"
    assert stability._ends_text([SCHEMES["spectral"]]) == ""


def test_the_stability_caption_names_a_scheme_by_its_prose(registered):
    registered.append(schemes.register("seven_point", range(-3, 4), 1, prose="the seven-point difference").name)
    text = stability._ends_text([SCHEMES["seven_point"]])
    assert text == " (three at each end for the seven-point difference)"


def test_default_second_derivative_schemes_are_shown_once():
    """A default first-derivative scheme whose partner is already shown adds no second entry, and a
    second-derivative scheme registered as a default is shown; the lists add to tuples and pickle."""
    import pickle

    from numkin import schemes
    from numkin.compare import DEFAULT_SCHEMES

    before = tuple(DEFAULT_SCHEMES[2])
    schemes.register("wide_centred_test", offsets=(-1, 0, 1), derivative=1, default=True, partner="second_difference")
    schemes.register("wide_second_test", offsets=(-2, 0, 2), derivative=2, default=True, partner="centred")
    try:
        assert tuple(DEFAULT_SCHEMES[2]) == before + ("wide_second_test",)
        assert DEFAULT_SCHEMES[1] + ("spectral",) == tuple(DEFAULT_SCHEMES[1]) + ("spectral",)
        assert pickle.loads(pickle.dumps(DEFAULT_SCHEMES[2])) == tuple(DEFAULT_SCHEMES[2])
    finally:
        schemes.unregister("wide_centred_test")
        schemes.unregister("wide_second_test")
    assert tuple(DEFAULT_SCHEMES[2]) == before
