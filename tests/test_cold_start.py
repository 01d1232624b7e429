"""A second run of a scene is built from the kernel cache's bundle: no sympy, the same numbers.

Each check runs in fresh interpreters with a fresh ``NUMKIN_CACHE_DIR``; the
numbers are compared between runs and with the chained four-bar solved here
by circle intersections (and the source document's exact omega and alpha).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

HOMEWORK = textwrap.dedent(
    """
    import json, sys
    from numkin.pipeline import run_scene
    r = run_scene("homework")
    check = r.checks[0]
    print(json.dumps({"sympy": "sympy" in sys.modules, "values": check.values,
                      "phi": r.sweep["phi"].tolist(), "beta": r.sweep["beta"].tolist()}))
    """
)
# what a scene's run needs of numkin's own stages: the mechanism, its sweep, its rates and its points
SWEEP = textwrap.dedent(
    """
    import json, sys
    import numpy as np
    from numkin.schema import load_scene
    from numkin.compiled import rates
    scene = load_scene({scene!r})
    m = scene.build_mechanism()
    s = m.sweep(scene.inputs(), guess=scene.guess_values(m))
    dq, d2q = rates(m.compiled, m.block_structure, s.values, s.inputs, m.parameter_values)
    xy = m.point_coordinates(s.values, s.inputs) if m.points else {{}}
    print(json.dumps({{"sympy": "sympy" in sys.modules, "q": s.values.tolist(), "dq": dq.tolist(),
                      "d2q": d2q.tolist(), "points": {{k: v.tolist() for k, v in xy.items()}},
                      "input": str(m.input_symbol), "unknowns": list(m.unknowns)}}))
    """
)


def run(code: str, folder: Path) -> dict:
    env = dict(os.environ, NUMKIN_CACHE_DIR=str(folder))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


# ------------------------------------------------------------------ reference
def four_bar_angle(theta, fixed, crank, coupler, output, near):
    """Output angle of ``output e^{i a} + coupler e^{i b} = fixed + crank e^{i theta}``, by circle intersection.

    The output pivot B lies on the circle |B| = output and |B - A| = coupler
    with A = fixed + crank e^{i theta}; of the two intersections, the one
    whose angle is nearer ``near`` (rad).
    """
    ax, ay = fixed + crank * math.cos(theta), crank * math.sin(theta)
    d = math.hypot(ax, ay)
    base = math.atan2(ay, ax)
    spread = math.acos((output**2 + d**2 - coupler**2) / (2 * output * d))
    angles = [base + spread, base - spread]
    return min(angles, key=lambda a: abs(math.remainder(a - near, 2 * math.pi)))


def homework_angles(degrees: int):
    """(phi, beta) of the homework's chained four-bars at theta = 0°, 1°, ..., ``degrees``°: the branch
    of its guesses at theta = 0 (phi 45°, beta 30°), followed by continuity in steps of 1°."""
    phi, beta = math.radians(45.0), math.radians(30.0)
    for k in range(degrees + 1):
        theta = math.radians(k)
        phi = four_bar_angle(theta, 7.0, 1.94, 6.86, 2.36, near=phi)
        beta = four_bar_angle(phi + math.radians(149.0), 1.25, 2.39, 1.87, 1.26, near=beta)
    return phi, beta


def beta_at(theta, near):
    """beta at any input theta (rad), on the branch nearest ``near`` (for differences of the closed form)."""
    phi = four_bar_angle(theta, 7.0, 1.94, 6.86, 2.36, near=math.radians(94.0))
    return four_bar_angle(phi + math.radians(149.0), 1.25, 2.39, 1.87, 1.26, near=near)


def test_reference_is_on_the_homework_branch():
    # the documents' positions at theta = 100° (report 003): phi 94.4375°, beta 214.727°
    phi, beta = homework_angles(100)
    assert math.degrees(phi) == pytest.approx(94.4375, abs=5e-5)
    assert math.degrees(beta) % 360 == pytest.approx(214.727, abs=5e-4)


# ---------------------------------------------------------------------- tests
def test_second_run_of_homework_imports_no_sympy(tmp_path):
    first = run(HOMEWORK, tmp_path / "kernels")
    second = run(HOMEWORK, tmp_path / "kernels")
    assert first["sympy"] is True  # derived once
    assert second["sympy"] is False
    assert second == {**first, "sympy": False}


def test_second_run_of_homework_same_numbers_as_the_closed_form(tmp_path):
    first = run(HOMEWORK, tmp_path / "kernels")
    second = run(HOMEWORK, tmp_path / "kernels")
    assert second["values"] == first["values"] and second["beta"] == first["beta"]
    v = second["values"]
    assert v["omega_beta"] == pytest.approx(10.633, abs=5e-4)   # the document's exact values
    assert v["alpha_beta"] == pytest.approx(-28.375, abs=5e-4)
    # every position of the sweep against circle intersections; omega at 100° by a centred
    # difference of the closed form (450 rad/min = 7.5 rad/s)
    for k in range(0, 361, 15):
        phi, beta = homework_angles(k)
        assert math.remainder(second["phi"][k] - phi, 2 * math.pi) == pytest.approx(0, abs=1e-10)
        assert math.remainder(second["beta"][k] - beta, 2 * math.pi) == pytest.approx(0, abs=1e-10)
    h, t, beta = 1e-6, math.radians(100), homework_angles(100)[1]
    omega = 7.5 * math.remainder(beta_at(t + h, beta) - beta_at(t - h, beta), 2 * math.pi) / (2 * h)
    assert v["omega_beta"] == pytest.approx(omega, abs=1e-6)


def test_linkage_from_the_cache_builds_without_sympy(tmp_path):
    code = SWEEP.format(scene="homework")
    first, second = run(code, tmp_path / "kernels"), run(code, tmp_path / "kernels")
    assert first["sympy"] is True and second["sympy"] is False
    assert second == {**first, "sympy": False}
    assert second["input"] == "theta" and second["unknowns"] == ["phi", "psi", "beta", "gamma"]
    phi, beta = homework_angles(100)
    q = second["q"]
    assert math.remainder(q[2][100] - beta, 2 * math.pi) == pytest.approx(0, abs=1e-10)
    # the drawing's point F = G + output2 e^{i beta}, G = (-1.25, 0)
    fx, fy = second["points"]["F"][0][100], second["points"]["F"][1][100]
    assert (fx, fy) == pytest.approx((-1.25 + 1.26 * math.cos(beta), 1.26 * math.sin(beta)), abs=1e-10)
    assert 7.5 * second["dq"][2][100] == pytest.approx(10.633, abs=5e-4)
    assert 7.5**2 * second["d2q"][2][100] == pytest.approx(-28.375, abs=5e-4)


LOOPS_SCENE = """
[scene]
description = "a slider-crank written as a loop"
[mechanism]
input = "theta"
unit = "mm"
links = [["O", "A", "P"]]
ground = ["O"]
[mechanism.dimensions]
r = 80
l = 200
[[mechanism.loops]]
name = "O-A-P"
unknowns = ["phi", "x"]
vectors = [["r", "theta"], ["l", "phi"], ["-x", "0"]]
[mechanism.points]
O = [0, 0]
A = ["r*cos(theta)", "r*sin(theta)"]
P = ["x", 0]
[input]
start_deg = 0
stop_deg = 180
step_deg = 5
[guess]
phi_deg = 0
x = 280
[output]
quantities = ["position"]
"""


def test_scene_written_as_loops_builds_without_sympy_the_second_time(tmp_path):
    scene = tmp_path / "slider.toml"
    scene.write_text(LOOPS_SCENE)
    code = SWEEP.format(scene=str(scene))
    first, second = run(code, tmp_path / "kernels"), run(code, tmp_path / "kernels")
    assert first["sympy"] is True and second["sympy"] is False
    assert second == {**first, "sympy": False}
    for k, deg in enumerate(range(0, 181, 5)):
        t = math.radians(deg)
        s = 80 * math.sin(t)
        x = 80 * math.cos(t) + math.sqrt(200**2 - s**2)   # the piston by hand
        assert second["q"][1][k] == pytest.approx(x, abs=1e-9)
        assert second["points"]["A"][0][k] == pytest.approx(80 * math.cos(t), abs=1e-12)
        # x' = -r sin(t) - r^2 sin(t) cos(t) / sqrt(l^2 - r^2 sin^2 t)
        dx = -80 * math.sin(t) - 80**2 * math.sin(t) * math.cos(t) / math.sqrt(200**2 - s**2)
        assert second["dq"][1][k] == pytest.approx(dx, abs=1e-9)


@pytest.mark.parametrize("damage", ["one byte", "stale key", "foreign code"])
def test_a_damaged_bundle_is_rebuilt_with_the_same_numbers(tmp_path, damage):
    folder = tmp_path / "kernels"
    code = SWEEP.format(scene="homework")
    first = run(code, folder)
    bundles = [p for p in folder.glob("*.json") if json.loads(p.read_text()).get("kind") == "bundle"]
    assert len(bundles) == 1
    path = bundles[0]
    text = path.read_text()
    if damage == "one byte":  # a digit of the code changed: the checksum no longer holds
        entry = json.loads(text)
        at = next(i for i, c in enumerate(entry["source"]) if c.isdigit())
        digit = str((int(entry["source"][at]) + 1) % 10)
        entry["source"] = entry["source"][:at] + digit + entry["source"][at + 1 :]
        path.write_text(json.dumps(entry))
    elif damage == "stale key":
        entry = json.loads(text)
        entry["key"] = "0" * 64
        path.write_text(json.dumps(entry))
    else:  # code that reaches outside, with a checksum made to match
        from numkin import kernel_cache

        entry = json.loads(text)
        entry["source"] = entry["source"].replace("return", "return ().__class__ or", 1)
        entry["sha256"] = kernel_cache._checksum(entry)
        path.write_text(json.dumps(entry))
    again = run(code, folder)
    assert again["sympy"] is True   # rebuilt, not trusted
    assert again == first
    entry = json.loads(path.read_text())
    assert entry["key"] == path.stem and "__class__" not in entry["source"]
    assert run(code, folder) == {**first, "sympy": False}


def test_cache_off_builds_with_sympy_every_time(tmp_path):
    code = SWEEP.format(scene="homework")
    first, second = run(code, "off"), run(code, "off")
    assert first["sympy"] is True and second["sympy"] is True and second == first


def test_a_cached_mechanism_derives_its_expressions_on_request(tmp_path, monkeypatch):
    import numpy as np
    import sympy as sp

    from numkin import linkages

    monkeypatch.setenv("NUMKIN_CACHE_DIR", str(tmp_path / "kernels"))
    built = linkages.six_bar()            # built with sympy, bundle kept
    cached = linkages.six_bar(crank=1.1)  # from the bundle
    assert "_model" in vars(cached)
    assert [lp.name for lp in cached.loops] == [lp.name for lp in built.loops]
    assert isinstance(cached.input_symbol, sp.Symbol) and cached.input_symbol == built.input_symbol
    assert cached.loops[1].residuals == built.loops[1].residuals
    assert cached.loops[0].angles == built.loops[0].angles
    assert cached.unknown_symbols == built.unknown_symbols
    assert cached.compiled.jacobian_matrix == built.compiled.jacobian_matrix
    assert cached.compiled.args == built.compiled.args
    assert dict(cached.points) == dict(built.points)
    crank = sp.Symbol("l2", real=True)
    assert cached.parameters[crank] == 1.1 and built.parameters[crank] == 1.0
    t = np.radians([0.0, 40.0])
    a, b = built.sweep(t), linkages.six_bar().sweep(t)
    np.testing.assert_array_equal(a.values, b.values)


def test_kernels_compiled_later_join_the_bundle(tmp_path, monkeypatch):
    import numpy as np

    from numkin import kernel_cache, linkages

    monkeypatch.setenv("NUMKIN_CACHE_DIR", str(tmp_path / "kernels"))
    m = linkages.slider_crank(80, 200)
    q = np.array([[np.pi], [280.0]])
    assert "second" not in kernel_cache.load_bundle(_only_bundle_key(tmp_path))[0]["kernels"]
    first = m.compiled._second(*q, 0.0, 0.0, np.zeros(1), *m.parameter_values)   # derived now, then kept
    kept = kernel_cache.load_bundle(_only_bundle_key(tmp_path))[0]["kernels"]
    assert {"F", "J", "F_t", "second"} <= set(kept)
    again = linkages.slider_crank(80, 200)
    assert "_second" not in vars(again.compiled)
    second = again.compiled._second(*q, 0.0, 0.0, np.zeros(1), *again.parameter_values)
    assert [float(v) for v in np.ravel(second)] == [float(v) for v in np.ravel(first)]
    # with q' = 0 only d2F/dt2 is left: the first residual r cos(t) + l cos(phi) - x gives -r cos(0) = -80
    assert float(np.ravel(first)[0]) == -80.0
    # a kernel first compiled on a mechanism from the bundle joins it, with the kernels loaded before
    assert "scalar_F" not in kernel_cache.load_bundle(_only_bundle_key(tmp_path))[0]["kernels"]
    f = again.compiled.scalar_F(0.0, 280.0, 0.0, *again.parameter_values)   # derived with sympy now
    assert f == pytest.approx([0.0, 0.0], abs=1e-12)   # phi = 0, x = r + l at theta = 0 closes the loop
    third = linkages.slider_crank(80, 200)
    assert {"_second", "scalar_F"} <= set(vars(third.compiled)["_loaded"])   # kept, installed on first use
    assert third.compiled.scalar_F(0.0, 280.0, 0.0, *third.parameter_values) == f
    np.testing.assert_array_equal(third.compiled._second(*q, 0.0, 0.0, np.zeros(1), *third.parameter_values), second)


def _only_bundle_key(tmp_path) -> str:
    (path,) = [p for p in (tmp_path / "kernels").glob("*.json") if json.loads(p.read_text()).get("kind") == "bundle"]
    return path.stem


def test_bad_values_are_named_on_the_cached_path_too(tmp_path, monkeypatch):
    import sympy as sp

    from numkin import Loop, Mechanism

    monkeypatch.setenv("NUMKIN_CACHE_DIR", str(tmp_path / "kernels"))

    def model():
        t, phi, x = sp.symbols("t phi x", real=True)
        r, rod, e = sp.Symbol("r", positive=True), sp.Symbol("L"), sp.Symbol("e", real=True)
        loop = Loop.from_vectors([(r, t), (rod, phi), (-x, 0), (-e, sp.pi / 2)], [phi, x], name="O-A-P")
        return [loop], t, [r, rod, e], {"P": (x, e)}

    for attempt in range(2):  # the first builds with sympy, the second from the bundle
        with pytest.raises(ValueError, match="parameter r = -1 is negative, but r is declared non-negative"):
            Mechanism.from_model("slider", model, [-1.0, 3.0, 0.0])
        with pytest.raises(ValueError, match=r"loop 'O-A-P': length L = -3 is negative \(a negative length mirrors"):
            Mechanism.from_model("slider", model, [1.0, -3.0, 0.0])
        with pytest.raises(ValueError, match="parameter e = nan is not finite"):
            Mechanism.from_model("slider", model, [1.0, 3.0, float("nan")])
        with pytest.raises(ValueError, match="2 parameter values for 3"):
            Mechanism.from_model("slider", model, [1.0, 3.0])
        with pytest.raises(ValueError, match=r"links or ground name undefined point\(s\) \['Q'\]"):
            Mechanism.from_model("slider", model, [1.0, 3.0, 0.5], ground=["Q"])
        m = Mechanism.from_model("slider", model, [1.0, 3.0, 0.5], guess={"phi": 0.0, "x": 4.0})
        assert ("_model" in vars(m)) == (attempt == 1)
        x = float(m.solve(0.0).x[1])
        assert x == pytest.approx(1.0 + math.sqrt(9.0 - 0.25), abs=1e-12)


def test_the_input_symbol_of_a_cached_mechanism_before_sympy(tmp_path):
    code = textwrap.dedent(
        """
        import json, sys
        from numkin import linkages
        m = linkages.four_bar(4, 1, 3, 3)
        s = m.input_symbol
        out = {"sympy": "sympy" in sys.modules, "text": f"{s} [deg]", "name": s == "theta2"}
        out["real"] = s.is_real                    # a symbol's attribute: sympy imported now
        import sympy as sp
        t = sp.Symbol("theta2", real=True)
        out["same"] = sp.sympify(s) == t and m.input_symbol == t and isinstance(m.input_symbol, sp.Symbol)
        out["model_derived"] = "_model" not in vars(m)   # the symbol alone derives no loops
        out["residual"] = str(m.loops[0].residuals[0])
        out["derived_now"] = "_model" not in vars(m)
        print(json.dumps(out))
        """
    )
    run(code, tmp_path / "kernels")
    out = run(code, tmp_path / "kernels")
    assert out == {"sympy": False, "text": "theta2 [deg]", "name": True, "real": True, "same": True,
                   "model_derived": False, "derived_now": True,
                   "residual": "-r1 + r2*cos(theta2) + r3*cos(theta3) - r4*cos(theta4)"}
