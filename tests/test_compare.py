"""Tests for numkin.compare: schemes side by side with the analytic value."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from numkin import derivatives, linkages
from numkin.compare import Comparison, compare, quantities

DEG = np.radians(np.arange(0.0, 361.0))
W_HW = 7.5  # 450 rad/min


@pytest.fixture(scope="module")
def homework():
    return linkages.chained_four_bars().sweep(DEG)


@pytest.fixture(scope="module")
def six_bar():
    return linkages.six_bar().sweep(DEG)


def test_homework_velocity_table(homework):
    c = compare(homework, "450 rad/min", "omega_beta", schemes=("forward", "centred"))
    assert isinstance(c, Comparison)
    assert c.quantity == "omega_beta" and c.unit == "rad/s" and c.periodic
    assert c.h == pytest.approx(math.radians(1))
    row = c.table.loc[100]
    assert row["theta [deg]"] == pytest.approx(100.0)
    assert row["analytic [rad/s]"] == pytest.approx(10.6329, abs=5e-5)
    assert row["centred [rad/s]"] == pytest.approx(10.6330, abs=5e-5)
    assert row["forward [rad/s]"] == pytest.approx(10.59998, abs=1e-5)
    b, h = homework["beta"], math.radians(1)
    assert row["forward [rad/s]"] == pytest.approx(W_HW * (b[101] - b[100]) / h, rel=1e-13)
    err = abs(row["forward [rad/s]"] - row["analytic [rad/s]"])
    assert row["forward abs error [rad/s]"] == pytest.approx(err, rel=1e-12)
    assert row["forward pointwise rel error"] == pytest.approx(err / abs(row["analytic [rad/s]"]), rel=1e-12)
    scale = np.abs(c.table["analytic [rad/s]"]).max()
    assert c.scale == pytest.approx(scale)
    assert row["forward rel error"] == pytest.approx(err / scale, rel=1e-12)
    assert list(c.table.columns) == [
        "theta [deg]", "analytic [rad/s]",
        "forward [rad/s]", "forward abs error [rad/s]", "forward rel error", "forward pointwise rel error",
        "centred [rad/s]", "centred abs error [rad/s]", "centred rel error", "centred pointwise rel error",
    ]


def test_homework_acceleration_defaults(homework):
    c = compare(homework, W_HW, "alpha_beta")
    assert list(c.summary.index) == ["forward_of_forward", "second_difference", "five_point_second", "spectral_second"]
    assert list(c.summary["order"]) == ["1", "2", "4", "spectral"]
    row = c.table.loc[100]
    assert row["analytic [rad/s^2]"] == pytest.approx(-28.3750, abs=5e-5)
    assert row["second_difference [rad/s^2]"] == pytest.approx(-28.3765, abs=5e-5)
    assert row["forward_of_forward [rad/s^2]"] == pytest.approx(-28.1266, abs=5e-5)
    # errors fall with the order
    errors = c.summary["max abs error [rad/s^2]"].to_numpy()
    assert np.all(np.diff(errors) < 0)
    assert errors[-1] < 1e-5


def test_summary_statistics(homework):
    c = compare(homework, W_HW, "omega_phi", schemes=["centred", "five_point"])
    for s in ("centred", "five_point"):
        err = c.table[f"{s} abs error [rad/s]"].to_numpy()
        rel = c.table[f"{s} rel error"].to_numpy()
        summary = c.summary.loc[s]
        assert summary["max abs error [rad/s]"] == pytest.approx(err.max())
        assert summary["rms abs error [rad/s]"] == pytest.approx(np.sqrt(np.mean(err[:-1] ** 2)))  # last row repeats
        assert summary["max rel error"] == pytest.approx(rel.max())
        assert summary["rms rel error"] == pytest.approx(np.sqrt(np.mean(rel[:-1] ** 2)))
        assert summary["max at theta [deg]"] == pytest.approx(float(np.degrees(DEG[np.argmax(err)])))
    assert "centred" in repr(c) and "omega_phi" in repr(c)


def test_open_grid_keeps_all_rows_and_tells_the_end_stencils_apart():
    part = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0.0, 181.0)))
    c = compare(part, "6000 rpm", "a_x")
    assert not c.periodic
    assert "spectral_second" not in c.summary.index
    err = c.table["second_difference abs error [mm/s^2]"].to_numpy()
    assert err.size == 181
    # the second difference's own stencil applies at 1..179 deg; 0 and 180 deg take one-sided stencils
    row = c.summary.loc["second_difference"]
    assert row["rms abs error [mm/s^2]"] == pytest.approx(np.sqrt(np.mean(err[1:-1] ** 2)))
    assert row["max abs error [mm/s^2]"] == pytest.approx(err[1:-1].max())
    assert row["ends abs error [mm/s^2]"] == pytest.approx(max(err[0], err[-1]))
    assert c.table.attrs["ends"]["second_difference"] == (1, 1)
    # leading error terms: h^2/12 times the 4th derivative inside, 11 h^2/12 times it for
    # (2 y0 - 5 y1 + 4 y2 - y3) / h^2 at the ends, where it is largest: about 11 times the interior error
    assert 10.0 < row["ends abs error [mm/s^2]"] / row["max abs error [mm/s^2]"] < 12.0
    with pytest.raises(ValueError, match="one turn"):
        compare(part, 1.0, "v_x", schemes=("spectral",))


def test_points_and_unknowns_agree(six_bar):
    a = compare(six_bar, "-10 rad/s", "vx_D", schemes=("centred",))
    b = compare(six_bar, "-10 rad/s", "v_x", schemes=("centred",))
    assert a.unit == "cm/s"
    np.testing.assert_allclose(a.table["analytic [cm/s]"], b.table["analytic [cm/s]"], rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(a.table["centred [cm/s]"], b.table["centred [cm/s]"], rtol=1e-12, atol=1e-9)
    c = compare(six_bar, "-10 rad/s", "ay_C", schemes=("second_difference",))
    assert c.unit == "cm/s^2" and c.table.columns[0] == "theta2 [deg]"


def test_accelerating_input_uses_the_partner_scheme(homework):
    c = compare(homework, W_HW, "alpha_beta", schemes=("forward_of_forward",), alpha=2.0)
    b, h = homework["beta"], math.radians(1)
    kw = {"periodic": True, "period_offset": b[-1] - b[0]}  # the sample after the last is b[-1]
    expected = W_HW**2 * derivatives.forward_of_forward(b[:-1], h, **kw) + 2.0 * derivatives.forward(b[:-1], h, **kw)
    np.testing.assert_allclose(c.table["forward_of_forward [rad/s^2]"][:-1], expected, rtol=1e-12)


def test_columns_are_labelled(homework):
    """Every column with a dimension names its unit; degrees appear only in '[deg]' columns."""
    c = compare(homework, W_HW, "omega_gamma")
    for col in c.table.columns:
        assert re.search(r"\[[^\]]+\]$", col) or col.endswith("rel error"), col
    assert [col for col in c.table.columns if "deg" in col] == ["theta [deg]"]
    np.testing.assert_allclose(c.table["theta [deg]"], np.arange(0.0, 361.0))


@pytest.mark.parametrize(
    "quantity, schemes, match",
    [
        ("beta", None, r"unknown quantity 'beta'.*use 'omega_beta' or 'alpha_beta'"),
        ("v_beta", None, r"unknown quantity 'v_beta'.*valid: .*'omega_beta'"),
        ("alpha_beta", ("forward",), r"estimates a first derivative.*forward_of_forward"),
        ("omega_beta", ("second_difference",), r"estimates a second derivative"),
        ("omega_beta", (), "at least one"),
    ],
)
def test_errors(homework, quantity, schemes, match):
    with pytest.raises(ValueError, match=match):
        compare(homework, 1.0, quantity, schemes=schemes)


def test_quantities_catalogue():
    q = quantities(linkages.six_bar())
    assert q["omega_theta5"] == (1, "rad/s")
    assert q["a_x"] == (2, "cm/s^2")
    assert q["vx_D"] == (1, "cm/s")


def test_value_columns_carry_their_quantities(homework):
    c = compare(homework, W_HW, "alpha_beta", schemes=("second_difference",))
    q = c.table.attrs["quantities"]
    assert set(q) == {"analytic [rad/s^2]", "second_difference [rad/s^2]"}
    assert q["second_difference [rad/s^2]"].source == "second_difference"
    assert (c.target.name, c.target.order, c.target.unit) == ("alpha_beta", 2, "rad/s^2")
    assert all(v.name == "alpha_beta" for v in q.values())


def test_numkin_run_names_the_end_stencils_of_an_open_grid():
    from numkin.cli import format_result
    from numkin.scene import run_scene

    text = format_result(run_scene("slider-crank"))  # 0..180 deg: an open grid
    at_zero = text.split("check at theta = 0°")[1].split("check at")[0]
    assert "second_difference (one-sided end stencil)" in at_zero and "centred (one-sided end stencil)" in at_zero
    at_ninety = text.split("check at theta = 90°")[1].split("largest error")[0]
    assert "one-sided" not in at_ninety
    assert "ends, one-sided" in text


def test_a_quantity_made_elsewhere_is_refused_not_labelled_with_its_unit():
    """A Quantity is compared only if it is the mechanism's own: one declared with another unit or
    dimension would label the comparison's columns wrongly (a rad/s column as furlong/s)."""
    import dataclasses

    from numkin.quantities import resolve

    mech = linkages.four_bar(4.0, 1.0, 3.0, 3.0)
    sweep = mech.sweep(np.linspace(0.0, 2.0 * np.pi, 73))
    own = resolve(mech, "omega_theta4")
    table = compare(sweep, 10.0, own).table
    assert "analytic [rad/s]" in table.columns
    for foreign in (dataclasses.replace(own, dimension="length", length_unit="furlong"),
                    dataclasses.replace(own, of="theta9"), resolve(mech, "theta4")):
        with pytest.raises(ValueError, match="is not a velocity or acceleration of four-bar"):
            compare(sweep, 10.0, foreign)


def test_input_columns_read_as_the_grid_was_written():
    """A grid in degrees taken to rad: 30° comes back as 29.999999999999996 from np.degrees; the input columns of the
    sweep's frame and of a comparison hold the grid as written (a filter on 30 finds its row)."""
    degrees = np.arange(20.0, 60.0, 0.5)
    t = np.radians(degrees)
    assert not np.array_equal(np.degrees(t), degrees)  # the round trip's noise, which the columns must not show
    sweep = linkages.four_bar(5, 1.5, 4.5, 3.5).sweep(t)
    assert np.array_equal(sweep.to_frame()["theta2 [deg]"].to_numpy(), degrees)
    table = compare(sweep, 10.0, "omega_theta4", schemes=("centred",)).table
    assert np.array_equal(table["theta2 [deg]"].to_numpy(), degrees)


def test_a_descending_sweep_keeps_its_end_stencils_apart():
    """forward on 0..90° takes the mirrored (backward) stencil at 90°, the grid's last point: on the sweep run from 90°
    down to 0° that point is the first row. The summary leaves it out and names it as the end, whichever way the
    sweep runs; at 0° forward is its own stencil, (x(1°) - x(0°))/h of x = r cos t + sqrt(l^2 - r^2 sin^2 t)."""
    from numkin.figures.ends import frame_ends

    r, l, w = 80.0, 200.0, 10.0
    mech = linkages.slider_crank(r, l)
    t = np.radians(np.arange(0.0, 91.0))
    x = r * np.cos(t) + np.sqrt(l**2 - (r * np.sin(t)) ** 2)
    h = t[1] - t[0]
    up = compare(mech.sweep(t), w, "v_x", schemes=("forward",))
    down = compare(mech.sweep(t[::-1]), w, "v_x", schemes=("forward",))
    own_at_0 = abs(w * (x[1] - x[0]) / h - 0.0)  # v_x(0°) = 0
    mirrored_at_90 = abs(w * (x[90] - x[89]) / h - (-w * r))  # v_x(90°) = -r w (r sin 90° cos 90° = 0)
    for c in (up, down):
        assert c.summary.loc["forward", "ends abs error [mm/s]"] == pytest.approx(mirrored_at_90, rel=1e-6)
        assert c.summary.loc["forward", "max abs error [mm/s]"] == pytest.approx(own_at_0, rel=1e-6)
    assert up.table.attrs["ends"]["forward"] == (0, 1) and down.table.attrs["ends"]["forward"] == (1, 0)
    assert frame_ends("forward", down.table, 1) == (1, 0)
