"""Bad input at the edges of the API is refused with an InputError naming the argument, point or symbol.

Each case asserts the error's type and the words of its message that say
what is wrong and where; a point written as a string is checked against the
four-bar's closed form (two circles intersected, in test_input_mistakes).
"""

from __future__ import annotations

import copy
import math
import os
import re
import subprocess
import sys
import textwrap

import numpy as np
import pytest
import sympy as sp

from numkin import Loop, Mechanism, kernel_cache, linkages, outputs
from numkin.compare import compare, quantities
from numkin.errors import InputError
from numkin.scene import SceneError, load_scene, run_scene
from test_input_mistakes import four_bar_closed_form, loops_scene

T2, T3, T4 = sp.symbols("theta2 theta3 theta4", real=True)
A, B, C, D = sp.symbols("a b c d", positive=True)
VALUES = {A: 4.0, B: 1.0, C: 3.0, D: 3.0}
GUESS = {"theta3": 0.5, "theta4": 1.5}


def four_bar(**options):
    loop = Loop.from_vectors([(B, T2), (C, T3), (-D, T4), (-A, 0)], [T3, T4], name="O2-A-B-O4")
    return Mechanism([loop], T2, VALUES, name="four-bar", guess=GUESS, **options)


# ------------------------------------------------------------------ load_scene
@pytest.mark.parametrize("given, kind", [(None, "NoneType"), (3, "int"), (b"homework", "bytes"), (["homework"], "list")])
def test_load_scene_names_the_argument_and_what_was_given(given, kind):
    with pytest.raises(InputError, match=rf"^name_or_path must be a built-in scene's name or the path .* got {kind} "):
        load_scene(given)


def test_load_scene_refuses_overrides_that_are_not_a_mapping():
    with pytest.raises(InputError, match=r"^overrides must be a mapping .* got list"):
        load_scene("homework", overrides=[("input", {"step_deg": 5})])


@pytest.mark.parametrize("content, words", [
    (None, "is a directory"),
    ("missing", "not found"),
    ("this is = = not toml", "malformed TOML"),
    (bytes(range(256)), "not a text file"),
])
def test_load_scene_says_what_is_wrong_with_the_file(tmp_path, content, words):
    path = tmp_path / "scene.toml"
    if content is None:
        path.mkdir()
    elif isinstance(content, bytes):
        path.write_bytes(content)
    elif content != "missing":
        path.write_text(content)
    with pytest.raises(SceneError, match=words):
        load_scene(path)


def test_a_scene_file_that_starts_with_a_byte_order_mark_is_read(tmp_path):
    """Some editors start UTF-8 text with a byte-order mark, which TOML does not allow: read past it."""
    from numkin.schema import SCENES_DIR

    path = tmp_path / "homework.toml"
    path.write_bytes(b"\xef\xbb\xbf" + (SCENES_DIR / "homework.toml").read_bytes())
    assert load_scene(path).description == load_scene("homework").description


# ------------------------------------------------------------------- run_scene
@pytest.mark.parametrize("kwargs, words", [
    ({"scene": None}, r"^scene must be a built-in scene's name .* got NoneType None"),
    ({"at": "30"}, r"^at must be an input angle in degrees .* got str '30'"),
    ({"at": float("nan")}, r"^at must be an input angle in degrees"),
    ({"figures": "no"}, r"^figures must be True or False, got 'no'"),
    ({"progress": 3}, r"^progress must be a function"),
    ({"out": 3}, r"^out must be a folder's path .* got int 3"),
    ({"out": ""}, r"^out is empty"),
])
def test_run_scene_checks_its_arguments_before_computing(monkeypatch, kwargs, words):
    from numkin import pipeline

    monkeypatch.setattr(pipeline, "_run", lambda *a, **k: pytest.fail("computed although an argument is bad"))
    kwargs = {"scene": "slider-crank", **kwargs}
    with pytest.raises(InputError, match=words):
        run_scene(**kwargs)


def test_load_and_run_scene_are_the_schema_and_pipeline_functions():
    from numkin import pipeline, schema

    assert load_scene is schema.load_scene and run_scene is pipeline.run_scene


def test_run_scene_refuses_an_out_that_is_a_file_or_under_one(tmp_path):
    file = tmp_path / "notes.txt"
    file.write_text("a file")
    with pytest.raises(InputError, match=rf"^out: '{re.escape(str(file))}' is a file, not a folder"):
        run_scene("slider-crank", out=file)
    with pytest.raises(InputError, match=rf"cannot make the folder '{re.escape(str(file / 'tables' / 'x'))}': "
                                         rf"'{re.escape(str(file))}' is a file"):
        run_scene("slider-crank", out=file / "tables" / "x")


# ------------------------------------------------------------------- writers
@pytest.fixture(scope="module")
def slider_crank():
    return run_scene("slider-crank")


@pytest.mark.parametrize("result", ["x", None, 3])
def test_tables_names_the_result_argument(result):
    with pytest.raises(InputError, match=rf"^result must be the SceneResult of run_scene\(\) .* got {type(result).__name__}"):
        outputs.tables(result)


def test_tables_of_the_stability_suite_say_it_has_no_mechanism(monkeypatch):
    from numkin.pipeline import SceneResult

    result = SceneResult(scene=load_scene("stability"))
    with pytest.raises(InputError, match="the stability suite's result"):
        outputs.tables(result)


@pytest.mark.parametrize("which, value, words", [
    ("scene", "slider-crank", r"^scene must be a numkin.scene.Scene .* got str 'slider-crank'"),
    ("tables", "positions", r"^tables must be a mapping name -> pandas.DataFrame, got str"),
    ("tables", {"positions": "a frame"}, r"^tables\['positions'\] must be a pandas.DataFrame .* got str"),
    ("out", 3, r"^out must be a folder's path .* got int 3"),
    ("out", None, r"^out must be a folder's path .* got NoneType None"),
])
def test_write_tables_names_the_argument(tmp_path, slider_crank, which, value, words):
    args = {"scene": slider_crank.scene, "tables": slider_crank.tables, "out": tmp_path / "out", which: value}
    with pytest.raises(InputError, match=words):
        outputs.write_tables(**args)
    assert not (tmp_path / "out").exists()


def test_write_tables_names_the_file_in_the_way_and_makes_missing_folders(tmp_path, slider_crank):
    file = tmp_path / "results"
    file.write_text("a file")
    with pytest.raises(InputError, match=rf"^out: cannot make the folder '{re.escape(str(file / 'a' / 'b'))}': "
                                         rf"'{re.escape(str(file))}' is a file, not a folder"):
        outputs.write_tables(slider_crank.scene, slider_crank.tables, file / "a" / "b")
    written = outputs.write_tables(slider_crank.scene, slider_crank.tables, tmp_path / "new" / "deeper")
    assert written and all(p.parent == tmp_path / "new" / "deeper" and p.is_file() for p in written)


def test_the_library_writers_name_the_file_in_the_way(tmp_path):
    import pandas as pd

    from numkin import figures
    from numkin.animate import animate
    from numkin.report.writers import write_tables

    file = tmp_path / "results"
    file.write_text("a file")
    sweep = linkages.slider_crank(80, 200).sweep(np.radians(np.arange(0.0, 361.0, 10.0)))
    in_the_way = rf"cannot make the folder '{re.escape(str(file / 'a'))}': '{re.escape(str(file))}' is a file, not a folder"
    with pytest.raises(InputError, match=rf"^out_dir: {in_the_way}"):
        write_tables({"t": pd.DataFrame({"h [deg]": [1.0]})}, file / "a")
    with pytest.raises(InputError, match=rf"^path_stem: {in_the_way}"):
        figures.save(figures.position(sweep, ["x"]), file / "a" / "x", ["png"])
    with pytest.raises(InputError, match=rf"^path: {in_the_way}"):
        animate(sweep, file / "a" / "m.gif", frames=2)
    assert file.read_text() == "a file"


@pytest.mark.parametrize("comparisons, words", [
    ("x", r"^comparisons must be a mapping name -> numkin.compare.Comparison, got str"),
    ({"omega_theta3": 1.0}, r"^comparisons\['omega_theta3'\] must be a numkin.compare.Comparison .* got float"),
])
def test_error_summary_names_the_entry(comparisons, words):
    with pytest.raises(InputError, match=words):
        outputs.error_summary(comparisons)


# -------------------------------------------------------- points: their names
@pytest.mark.parametrize("point", [
    (B * sp.cos(T2) + sp.Symbol("q", real=True), 0),
    ("b*cos(theta2) + c*cos(theta33)", "b*sin(theta2) + c*sin(theta3)"),
])
def test_a_point_naming_what_the_mechanism_does_not_have_is_refused_when_built(point):
    with pytest.raises(InputError) as caught:
        four_bar(points={"B": point})
    message = str(caught.value)
    assert message.startswith("four-bar: point 'B' names ['")
    strange = "q" if not isinstance(point[0], str) else "theta33"
    assert f"names ['{strange}'], which the mechanism does not have" in message
    assert "the unknowns ['theta3', 'theta4'], the input theta2 and the parameters ['a', 'b', 'c', 'd']" in message


def test_a_point_and_a_derived_quantity_are_refused_in_the_same_words():
    with pytest.raises(InputError) as point:
        four_bar(points={"B": ("theta33", 0)})
    with pytest.raises(InputError) as quantity:
        four_bar(quantities={"B": ("theta33", "angle")})
    assert str(point.value).replace("point", "quantity") == str(quantity.value)


@pytest.mark.parametrize("points, words", [
    (["B"], r"^four-bar: points must be a mapping name -> \(x, y\), got list"),
    ({"B": "b*cos(theta2)"}, r"^four-bar: point 'B' must be a pair \(x, y\) of expressions"),
    ({"B": (1, 2, 3)}, r"^four-bar: point 'B' must be a pair"),
    ({3: (0, 0)}, r"^four-bar: point 3: a point's name is an identifier"),
    ({"B": ("b*cos(theta2) +", 0)}, r"^four-bar: point 'B' x: cannot read the expression"),
    ({"B": (0, "1/(b - b)")}, r"^four-bar: point 'B' y: '1/\(b - b\)' is not a finite real expression"),
    ({"B": (0, "sqrt(-b)")}, r"^four-bar: point 'B' y: 'sqrt\(-b\)' is not a finite real expression"),
    ({"B": (None, 0)}, r"^four-bar: point 'B' x: None is not an expression"),
    ({"B": ("theta2 < 1", 0)}, r"^four-bar: point 'B' x: the expression 'theta2 < 1' is not arithmetic"),
    ({"B": ("__import__('os').getcwd()", 0)}, r"^four-bar: point 'B' x: the expression .* is not arithmetic"),
])
def test_a_point_that_is_not_a_pair_of_expressions_is_named(points, words):
    """(sqrt(-b) of b declared positive is i*sqrt(b): refused when built.)"""
    with pytest.raises(InputError, match=words):
        four_bar(points=points)


def test_a_point_written_as_strings_means_the_loops_own_symbols():
    """Names in a string are the loops' symbols (declared real or positive), not new ones sympy makes."""
    mech = four_bar(points={"B": ("b*cos(theta2) + c*cos(theta3)", "b*sin(theta2) + c*sin(theta3)")})
    inputs = np.radians([0.0, 37.0, 100.0])
    xy = mech.sweep(inputs).points()["B"]
    for k, t2 in enumerate(inputs):
        theta3, _ = four_bar_closed_form(float(t2))
        expected = (math.cos(t2) + 3 * math.cos(theta3), math.sin(t2) + 3 * math.sin(theta3))
        np.testing.assert_allclose(xy[:, k], expected, rtol=0, atol=1e-12)


# ---------------------------------------------------- points: the kernel cache
def _model(point):
    def model():
        t, x = sp.symbols("t x", real=True)
        r = sp.Symbol("r", positive=True)
        return [Loop([x - r * sp.cos(t)], [x], name="shadow")], t, [r], {"P": (point, 0)}

    return model


def test_from_model_refuses_a_bad_point_every_time_with_a_cache(tmp_path, monkeypatch):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path / "kernels"))
    for _ in range(2):  # nothing kept by the first refusal for the second to find
        with pytest.raises(InputError, match=r"^shadow: point 'P' names \['tt'\], which the mechanism does not have"):
            Mechanism.from_model("a shadow with a misspelt point", _model("r*cos(tt)"), [2.0], name="shadow",
                                 guess={"x": 1.0})


def test_a_mechanism_from_the_kernel_cache_refuses_a_point_in_the_same_words(tmp_path, monkeypatch):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path / "kernels"))
    with pytest.raises(InputError) as built:
        Mechanism.from_model("a misspelt point", _model("r*cos(tt)"), [2.0], name="shadow", guess={"x": 1.0})
    key = "a shadow and its point"
    good = Mechanism.from_model(key, _model("r*cos(t)"), [2.0], name="shadow", guess={"x": 1.0})
    good.point_coordinates(np.array([[2.0]]), np.array([0.0]))  # its point kernel kept too
    real = kernel_cache.load_bundle
    found = real(key)
    assert found is not None, "the first build kept no bundle"
    kept, functions = found
    kept = copy.deepcopy(kept)
    kept["point_symbols"]["P"] = ["r", "tt"]  # a bundle that names what the mechanism does not have
    monkeypatch.setattr(kernel_cache, "load_bundle", lambda k: (kept, functions) if k == key else real(k))
    with pytest.raises(InputError) as cached:
        Mechanism.from_model(key, _model("r*cos(t)"), [2.0], name="shadow", guess={"x": 1.0})
    assert str(cached.value) == str(built.value)
    assert str(built.value).startswith("shadow: point 'P' names ['tt'], which the mechanism does not have")


# ---------------------------------------------------------- points: a scene
def test_numkin_run_of_a_scene_with_a_bad_point_exits_2_in_one_line(tmp_path):
    path = loops_scene(tmp_path, output='points = ["B"]', edits=[("[input]\n", textwrap.dedent("""\
        [mechanism.points]
        A = ["r2*cos(theta2)", "r2*sin(theta2)"]
        B = ["r2*cos(theta2) + r3*cos(theta33)", "r2*sin(theta2) + r3*sin(theta3)"]
        [input]
        """))])
    env = dict(os.environ, NUMKIN_CACHE_DIR=str(tmp_path / "kernels"))
    for _ in range(2):  # the second with whatever the first kept
        proc = subprocess.run([sys.executable, "-m", "numkin", "run", path], capture_output=True, text=True,
                              timeout=300, env=env)
        assert proc.returncode == 2 and proc.stdout == "", proc.stderr
        lines = proc.stderr.strip().splitlines()
        assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
        assert lines[0].startswith("numkin: error: loops.toml: [mechanism.points] B:")
        assert "'theta33'" in lines[0] and "did you mean 'theta3'" in lines[0]


# ------------------------------------------------------ Mechanism's arguments
@pytest.mark.parametrize("options, words", [
    ({"links": 3}, r"^links must be a list of links, each a list of point names, got 3"),
    ({"links": "AB"}, r"^links must be a list of links"),
    ({"links": [3]}, r"^each of links must be a list of point names, got 3"),
    ({"ground": "O2"}, r"^ground must be a list of point names, got 'O2'"),
    ({"length_scale": "x"}, r"^length_scale = 'x' is not a number"),
    ({"assembly_check": 3}, r"^assembly_check must be a function of the inputs, got 3"),
    ({"branch": 3}, r"^branch must be a non-empty string, got 3"),
    ({"guess_input": "x"}, r"^guess_input \(rad\) = 'x' is not a number"),
])
def test_mechanism_names_a_bad_keyword(options, words):
    with pytest.raises(InputError, match=words):
        four_bar(**options)


@pytest.mark.parametrize("loops", [None, 3, "a loop", []])
def test_mechanism_names_loops_that_are_not_loops(loops):
    with pytest.raises(InputError, match=r"^`loops` must be a non-empty sequence of numkin.Loop, got "):
        Mechanism(loops, T2, VALUES)


def test_mechanism_refuses_a_name_or_guess_that_is_a_string_of_the_wrong_kind():
    loop = Loop.from_vectors([(B, T2), (C, T3), (-D, T4), (-A, 0)], [T3, T4])
    with pytest.raises(InputError, match=r"^name must be a non-empty string, got None"):
        Mechanism([loop], T2, VALUES, name=None)
    with pytest.raises(InputError, match=r"^guess must be a mapping name -> value, .* got '30, 120'"):
        Mechanism([loop], T2, VALUES, guess="30, 120")


# ------------------------------------------------------------------ compare
@pytest.fixture(scope="module")
def sweep():
    return linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0.0, 361.0, 10.0)))


def test_compare_names_a_quantity_that_is_not_a_name(sweep):
    with pytest.raises(InputError, match=r"^quantity must be a name such as 'omega_theta3', got int 3; valid: "):
        compare(sweep, 1.0, 3)


def test_compare_names_a_scheme_that_is_not_a_name(sweep):
    with pytest.raises(InputError, match=r"unknown finite-difference method 3"):
        compare(sweep, 1.0, "omega_theta3", schemes=3)


def test_compare_quantities_name_the_mechanism_argument():
    with pytest.raises(InputError, match=r"^mechanism must be a numkin.Mechanism, got str 'four_bar'"):
        quantities("four_bar")



# ------------------------------------------- point and derived rates, loops
def test_point_and_derived_rates_name_an_argument_that_is_not_names():
    from numkin import analytic

    mech = linkages.slider_crank(80, 200).add_quantities({"gap": ("x - r*cos(theta)", "length")})
    sweep = mech.sweep(np.radians([0.0, 10.0, 20.0]))
    with pytest.raises(InputError, match=r"^points must be a name or a list of names of the points .* got int 3"):
        analytic.point_kinematics(sweep, 1.0, points=3)
    with pytest.raises(InputError, match=r"^names must be a name or a list of names of the derived .* got int 3"):
        analytic.derived_kinematics(sweep, 1.0, names=3)


@pytest.mark.parametrize("build, words", [
    (lambda: Loop(None, [T3]), r"^a loop: residuals must be a list, got NoneType None"),
    (lambda: Loop(["theta3 - 1"], "theta3", name="L"), r"^loop 'L': unknowns must be a list, got str"),
    (lambda: Loop(["__import__('os').getcwd()"], [T3], name="L"), r"^loop 'L': equation 1: the expression .* is not arithmetic"),
    (lambda: Loop([sp.Eq(T3, 1)], [T3], name="L"), r"^loop 'L': equation 1: .* is not a number-valued expression"),
    (lambda: Loop.from_vectors(3, [T3], name="L"), r"^loop 'L': vectors must be a list of \(length, angle\) pairs"),
    (lambda: Loop.from_vectors([("r.real", T3), (1, 0)], [T3], name="L"),
     r"^vector 0 of loop 'L': its length: the expression 'r.real' is not arithmetic"),
])
def test_a_loop_names_what_is_not_an_expression(build, words):
    with pytest.raises(InputError, match=words):
        build()


def test_a_point_undefined_where_the_linkage_is_is_warned_of_by_name():
    """sqrt(b - a), b = 1 and a = 4: not refused when built (its sign is the values'), warned of when computed."""
    mech = four_bar(points={"B": ("sqrt(b - a)", "b*sin(theta2)")})
    sweep = mech.sweep(np.radians([0.0, 10.0]))
    with pytest.warns(RuntimeWarning, match=r"^four-bar: x_B is not finite at 2 of 2 inputs, first at input 0°"):
        xy = sweep.points()["B"]
    assert np.isnan(xy[0]).all()
    np.testing.assert_allclose(xy[1], np.sin(np.radians([0.0, 10.0])), rtol=0, atol=1e-15)


# ------------------------------------------------------------- the command's --out
@pytest.mark.parametrize("command", [["run", "homework"], ["report", "homework"], ["figures", "homework"]])
def test_an_out_that_is_a_file_is_refused_before_any_work(capsys, tmp_path, monkeypatch, command):
    from numkin import pipeline, report
    from test_cli import one_line_error, run

    monkeypatch.setattr(pipeline, "run_scene", lambda *a, **k: pytest.fail("computed although --out is a file"))
    monkeypatch.setattr(report, "scene_report", lambda *a, **k: pytest.fail("computed although --out is a file"))
    file = tmp_path / "results"
    file.write_text("a file")
    code, out, err = run(capsys, *command, "--out", str(file / "tables"))
    assert code == 2 and out == ""
    assert one_line_error(err) == f"numkin: error: --out: cannot make the folder '{file / 'tables'}': '{file}' is a file, not a folder"


def test_animate_refuses_a_folder_for_its_gif(capsys, tmp_path):
    from test_cli import one_line_error, run

    folder = tmp_path / "mechanism.gif"
    folder.mkdir()
    code, _, err = run(capsys, "animate", "slider-crank", "--out", str(folder))
    assert code == 2
    assert one_line_error(err) == f"numkin: error: --out: '{folder}' is a folder; give the path of a .gif file"


def test_from_model_names_its_arguments_and_says_a_count_alike_from_the_cache(tmp_path, monkeypatch):
    monkeypatch.setenv(kernel_cache.ENV_VAR, str(tmp_path / "kernels"))
    model = _model("r*cos(t)")
    with pytest.raises(InputError, match=r"^key must be a string"):
        Mechanism.from_model(None, model, [2.0])
    with pytest.raises(InputError, match=r"^model must be a function"):
        Mechanism.from_model("k", 3, [2.0])
    with pytest.raises(InputError, match=r"^model\(\) must return \(loops, input, parameter symbols, points\), got 3"):
        Mechanism.from_model("k", lambda: 3, [2.0])
    with pytest.raises(InputError, match=r"^values must be the parameters' values .* got NoneType None"):
        Mechanism.from_model("k", model, None)
    messages = []
    for _ in range(2):  # built from sympy, then (a bundle kept in between) from the cache
        with pytest.raises(InputError) as caught:
            Mechanism.from_model("a shadow", model, [], name="shadow")
        messages.append(str(caught.value))
        Mechanism.from_model("a shadow", model, [2.0], name="shadow", guess={"x": 1.0})
    assert messages[0] == messages[1] == "shadow: 0 parameter values for 1 parameters ['r']"


# ------------------------------------------------------------------- sweeps and rates
@pytest.mark.parametrize("inputs", [None, ["0", "1"], "0.5", [True, False], [0.5j, 1.0j], [0.5, None]])
def test_sweep_inputs_that_are_not_numbers_are_named(inputs):
    with pytest.raises(InputError, match=r"^inputs must be numbers \(input values, rad\), got "):
        linkages.four_bar(4, 1, 3, 3).sweep(inputs)


def test_sweep_inputs_as_sympy_numbers_are_numbers():
    sweep = linkages.four_bar(4, 1, 3, 3).sweep([sp.pi / 4, sp.pi / 2])
    np.testing.assert_allclose(sweep["theta4"], [four_bar_closed_form(math.pi / 4)[1], four_bar_closed_form(math.pi / 2)[1]],
                               atol=1e-12)


@pytest.mark.parametrize("guess", [{"theta3": "x", "theta4": 1.5}, ["a", 1.5], {"theta3": [0.5, 1.0], "theta4": 1.5},
                                   ["0.5", 1.5], {"theta3": 0.5, "theta4": "1.5"}, [True, 1.5], np.array([0.5, 1.5]) > 1])
def test_a_guess_that_is_not_numbers_is_named(guess):
    with pytest.raises(InputError, match=r"^guess must be numbers \(rad for angles\) for \['theta3', 'theta4'\]"):
        linkages.four_bar(4, 1, 3, 3).sweep([0.0, 0.1], guess=guess)


@pytest.mark.parametrize("call, message", [
    (lambda m, s: m.polish("x", [0.0]), r"^polish: x must be numbers \(the positions of \['theta3', 'theta4'\]\), got 'x'"),
    (lambda m, s: m.polish(s.values, "a"), r"^polish: inputs must be numbers \(input values, rad\), got 'a'"),
    (lambda m, s: m.polish(s.values, [True, False]), r"^polish: inputs must be numbers"),
    (lambda m, s: m.polish(s.values, np.radians([0.0, 90.0, 180.0])),
     r"^polish: x must have shape \(unknowns, inputs\) = \(2, 3\) for inputs of shape \(3,\), got \(2, 2\)"),
    (lambda m, s: m.polish(s.values[:1], s.inputs), r"^polish: x must have shape \(unknowns, inputs\) = \(2, 2\) .* got \(1, 2\)"),
    (lambda m, s: m.check_assembly("x"), r"^check_assembly: inputs must be numbers \(input values, rad\), got 'x'"),
    (lambda m, s: m.check_assembly(["1.0"]), r"^check_assembly: inputs must be numbers"),
    (lambda m, s: m.point_coordinates(s.values, "a"), r"^point_coordinates: inputs must be numbers"),
    (lambda m, s: m.point_coordinates([[0.5], ["1"]], [0.0]), r"^point_coordinates: x must be numbers"),
])
def test_positions_and_inputs_given_to_a_mechanism_are_numbers_of_matching_shapes(call, message):
    mech = linkages.four_bar(4, 1, 3, 3)
    sweep = mech.sweep(np.radians([0.0, 90.0]))
    with pytest.raises(InputError, match=message):
        call(mech, sweep)


def test_a_position_polished_from_one_vector_and_complex_positions_are_refined():
    mech = linkages.four_bar(4, 1, 3, 3)
    t3, t4 = four_bar_closed_form(math.pi / 2)
    got = mech.polish([t3 + 1e-6, t4 - 1e-6], math.pi / 2)  # one position: a vector and a number
    np.testing.assert_allclose(got[:, 0], [t3, t4], rtol=0, atol=1e-14)
    # a complex step: the imaginary parts are the derivative times 1e-20, whether arrays or lists are given
    h = 1e-20
    d3, d4 = [(a - b) / 2e-7 for a, b in zip(four_bar_closed_form(math.pi / 2 + 1e-7),
                                             four_bar_closed_form(math.pi / 2 - 1e-7))]
    for x, t in ((np.array([[t3 + 0j], [t4 + 0j]]), np.array([math.pi / 2 + h * 1j])),
                 ([[t3 + 0j], [t4]], [math.pi / 2 + h * 1j])):
        z = mech.polish(x, t)
        assert z.dtype.kind == "c"
        np.testing.assert_allclose(z.real[:, 0], [t3, t4], rtol=0, atol=1e-14)
        np.testing.assert_allclose(z.imag[:, 0] / h, [d3, d4], rtol=1e-6)


def test_masked_arrays_and_other_numbers_are_read_as_numbers():
    from decimal import Decimal
    from fractions import Fraction

    mech = linkages.four_bar(4, 1, 3, 3)
    sweep = mech.sweep(np.ma.array([0.0, 0.5, 1.0], mask=[0, 1, 0]))  # a mask is not a numkin idea: the data
    assert type(sweep.inputs) is np.ndarray and sweep.inputs.tolist() == [0.0, 0.5, 1.0]
    np.testing.assert_allclose(sweep["theta4"][2], four_bar_closed_form(1.0)[1], atol=1e-12)
    t3, t4 = four_bar_closed_form(math.pi / 2)
    got = mech.polish(np.ma.array([[t3], [t4]]), np.ma.array([math.pi / 2]))
    assert type(got) is np.ndarray
    from numkin.units import is_number
    assert all(is_number(v) for v in (Decimal("30"), Fraction(1, 3), sp.pi, np.array(2.0, dtype=object), np.int8(3)))
    assert not any(is_number(v) for v in (sp.Symbol("x"), 1j, np.array([1.0]), np.bool_(True), b"1"))


def test_the_analytic_rates_name_a_mechanism_given_for_a_sweep():
    from numkin import analytic

    mech = linkages.four_bar(4, 1, 3, 3)
    with pytest.raises(InputError, match=r"^sweep must be a numkin Sweep .* got Mechanism: give mechanism.sweep"):
        analytic.derivatives(mech)
    with pytest.raises(InputError, match=r"^sweep must be a numkin Sweep .* got str$"):
        analytic.tangent("sweep")


@pytest.mark.parametrize("kwargs, name", [({"omega": None}, "omega"), ({"omega": 1.0, "alpha": None}, "alpha")])
def test_an_input_rate_of_none_is_named(kwargs, name):
    from numkin import analytic

    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians([0.0, 10.0]))
    with pytest.raises(InputError, match=rf"^{name} must be a number, a string with units or an array of numbers, "
                                         "got None"):
        analytic.kinematics(sweep, **kwargs)


# ------------------------------------------------------------------- difference schemes' arguments
def test_difference_arguments_are_taken_as_written():
    """A 0-d array is the step it holds; periodic is a bool (1 is refused, as differentiate refuses it); complex
    samples are refused, not cast to their real part."""
    from numkin import derivatives, kinematics, linkages

    x = np.linspace(0.0, 1.0, 11)
    np.testing.assert_allclose(derivatives.differentiate(np.sin(x), h=np.array(0.1), method="centred")[1:-1],
                               (np.sin(x[2:]) - np.sin(x[:-2])) / 0.2, rtol=1e-12)
    with pytest.raises(InputError, match=r"y must be real samples, got complex values"):
        derivatives.differentiate(np.sin(x) + 1j, h=0.1, method="centred")
    sweep = linkages.four_bar(4, 1, 3, 3).sweep(np.radians(np.arange(0, 361)))
    with pytest.raises(InputError, match=r"periodic must be 'auto', True or False, got 1"):
        kinematics.finite_difference(sweep, 1.0, periodic=1)
    assert kinematics.finite_difference(sweep, 1.0, periodic=np.bool_(True)).attrs["periodic"] is True
