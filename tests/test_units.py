"""Tests for numkin.units."""

from __future__ import annotations

import math

import numpy as np
import pytest

from numkin.errors import InputError
from numkin.units import (
    UnitError,
    angular_acceleration,
    angular_speed,
    convert_length,
    length_factor,
)

PI = math.pi


@pytest.mark.parametrize(
    "text, rad_per_s",
    [
        ("450 rad/min", 7.5),
        ("6000 rpm", 200 * PI),
        ("-10 rad/s", -10.0),
        ("10 rad/sec", 10.0),
        ("3 rev/s", 6 * PI),
        ("100 deg/s", 100 * PI / 180),
        ("2.5 rps", 5 * PI),
        ("1e3 rpm", 1000 * 2 * PI / 60),
        ("-10rad/s", -10.0),
        ("+10 rad/s", 10.0),
        (".5 rad/s", 0.5),
        ("  60 RPM  ", 2 * PI),
        ("30 rev/min", PI),
        ("60 deg/min", PI / 180),
        ("10 rad / s", 10.0),
        ("10 radians/second", 10.0),
        ("90 \N{DEGREE SIGN}/s", PI / 2),
        ("\N{MINUS SIGN}10 rad/s", -10.0),
        ("12", 12.0),
    ],
)
def test_angular_speed_strings(text, rad_per_s):
    assert angular_speed(text) == pytest.approx(rad_per_s, rel=1e-15)


def test_angular_speed_exact_examples():
    assert angular_speed("450 rad/min") == 7.5
    assert angular_speed("-10 rad/s") == -10.0
    assert angular_speed("6000 rpm") == pytest.approx(200 * PI, rel=1e-15)


@pytest.mark.parametrize("number", [10, 10.0, -3.5, np.float64(2.0), np.int64(4)])
def test_angular_speed_numbers_are_rad_per_s(number):
    result = angular_speed(number)
    assert isinstance(result, float)
    assert result == float(number)


@pytest.mark.parametrize(
    "text, dimension",
    [
        ("10 mm", "length"),
        ("5 m/s", "linear speed"),
        ("3 rad/s^2", "angular acceleration"),
    ],
)
def test_angular_speed_wrong_dimension(text, dimension):
    with pytest.raises(UnitError) as info:
        angular_speed(text)
    message = str(info.value)
    assert repr(text) in message
    assert dimension in message
    assert "rad/s" in message and "rpm" in message


@pytest.mark.parametrize(
    "text",
    ["", "   ", "fast", "rpm", "10 furlongs", "10 rad/s/s", "1.2.3 rpm", "ten rpm", "nan rad/s"],
)
def test_angular_speed_garbage(text):
    with pytest.raises(UnitError) as info:
        angular_speed(text)
    message = str(info.value)
    assert repr(text) in message
    for unit in ("rad/s", "rad/min", "rpm", "rev/s", "deg/s"):
        assert unit in message


def test_unit_error_is_value_error():
    assert issubclass(UnitError, ValueError)
    with pytest.raises(ValueError):
        angular_speed("10 mm")


@pytest.mark.parametrize("value", [math.inf, math.nan, "1e400 rpm"])
def test_angular_speed_not_finite(value):
    with pytest.raises(UnitError):
        angular_speed(value)


@pytest.mark.parametrize("value", [None, True, [10.0], b"10 rpm"])
def test_angular_speed_wrong_type(value):
    with pytest.raises(TypeError):
        angular_speed(value)


@pytest.mark.parametrize(
    "text, rad_per_s2",
    [
        ("-4 rad/s^2", -4.0),
        ("4 rad/s2", 4.0),
        ("4 rad/s**2", 4.0),
        ("4 rad/s\N{SUPERSCRIPT TWO}", 4.0),
        ("4 rad/sec^2", 4.0),
        ("60 rpm/s", 2 * PI),
        ("180 deg/s^2", PI),
        ("3600 rad/min^2", 1.0),
        ("7200 rad/min2", 2.0),
        ("0.5 rev/s^2", PI),
        ("2.5", 2.5),
    ],
)
def test_angular_acceleration_strings(text, rad_per_s2):
    assert angular_acceleration(text) == pytest.approx(rad_per_s2, rel=1e-15)


def test_angular_acceleration_number():
    assert angular_acceleration(-3) == -3.0


@pytest.mark.parametrize(
    "text, dimension",
    [("10 rad/s", "angular speed"), ("9.81 m/s^2", "linear acceleration"), ("2 ft", "length")],
)
def test_angular_acceleration_wrong_dimension(text, dimension):
    with pytest.raises(UnitError) as info:
        angular_acceleration(text)
    message = str(info.value)
    assert repr(text) in message
    assert dimension in message
    assert "rad/s^2" in message


@pytest.mark.parametrize("text", ["4 rad/s^3", "fast", "4 rpm/min"])
def test_angular_acceleration_garbage(text):
    with pytest.raises(UnitError, match="rad/s\\^2") as info:
        angular_acceleration(text)
    assert repr(text) in str(info.value)


@pytest.mark.parametrize(
    "unit, metres",
    [("m", 1.0), ("mm", 0.001), ("cm", 0.01), ("km", 1000.0), ("in", 0.0254), ("ft", 0.3048)],
)
def test_length_factor(unit, metres):
    assert length_factor(unit) == pytest.approx(metres, rel=1e-15)


@pytest.mark.parametrize("unit", ["furlong", "", "MM", "mm/s", "rad"])
def test_length_factor_unknown(unit):
    with pytest.raises(UnitError, match="mm") as info:
        length_factor(unit)
    assert repr(unit) in str(info.value)


def test_convert_length_scalars():
    assert convert_length(25.4, "mm", "in") == 1.0
    assert convert_length(1.0, "ft", "in") == pytest.approx(12.0, rel=1e-15)
    assert convert_length(2.5, "km", "m") == 2500.0
    assert convert_length(3, "m", "m") == 3.0
    assert isinstance(convert_length(1.0, "m", "cm"), float)


def test_convert_length_array():
    result = convert_length([100.0, 250.0], "mm", "m")
    np.testing.assert_allclose(result, [0.1, 0.25], rtol=1e-15)
    assert result.shape == (2,)


def test_convert_length_round_trip():
    values = np.linspace(0.0, 3.0, 7)
    there = convert_length(values, "in", "cm")
    np.testing.assert_allclose(convert_length(there, "cm", "in"), values, rtol=1e-15)


def test_convert_length_unknown_unit():
    with pytest.raises(UnitError, match="parsec"):
        convert_length(1.0, "parsec", "m")


# --------------------------------------------------------------------------- input rates
def test_input_rate_is_the_one_parser():
    from numkin import analytic
    from numkin.units import input_rate, input_rates

    assert input_rate("450 rad/min") == 7.5
    assert input_rate(-10) == -10.0
    np.testing.assert_array_equal(input_rate("2 rad/s^2", "acceleration", count=3), [2.0, 2.0, 2.0])
    np.testing.assert_array_equal(input_rate([1.0, 2.0], count=2), [1.0, 2.0])
    assert analytic.input_rates is input_rates


@pytest.mark.parametrize(
    "value, kind, count, error, match",
    [
        ("2 rad/s^2", "speed", None, UnitError, r"omega: .*angular acceleration, not an angular speed"),
        ("10 rad/s", "acceleration", None, UnitError, r"alpha: .*angular speed"),
        ([1.0, 2.0], "speed", 3, ValueError, r"shape \(3,\)"),
        ([1.0, np.nan], "speed", 2, ValueError, r"omega\[1\] is not finite"),
        (None, "speed", None, InputError, "omega must be"),
        (True, "speed", None, InputError, "omega must be"),
        ("1 rad/s", "jerk", None, ValueError, "kind"),
    ],
)
def test_input_rate_errors_name_the_parameter(value, kind, count, error, match):
    from numkin.units import input_rate

    with pytest.raises(error, match=match):
        input_rate(value, kind, count)
