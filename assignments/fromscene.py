"""A homework master generated from a numkin scene: ``python assignments/build.py new my-linkage.toml``.

The scene's loop-closure equations are written out as plain numpy code in
``linkage.py`` (the residual ``F``, its Jacobian ``J`` and ``F_theta`` = ∂F/∂θ),
shipped with the homework next to ``kincheck/``, so students and the autograder
need no numkin.  The master asks for

* q1 — the position over the scene's sweep by Newton with continuation, and the
  output at the check angle;
* q2 — the output's rate by the centred difference, and exactly at the check angle
  (from J · dx/dθ = −∂F/∂θ);
* q3 — the output's second rate by the centred second difference;
* q4 — the error of the centred difference against the step at the check angle,
  and the observed order.

The output is the scene's ``[report] quantity`` (default: the last unknown), the
check angle the first ``[[check]]`` (default: 100° or the middle of the sweep).
Reference values are computed by numkin: the sweep (``Mechanism.sweep``), its
finite differences (``numkin.derivatives``) and the exact rates
(``numkin.analytic.kinematics``).
"""

from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

__all__ = ["generate", "expected", "SCENE_FILE"]

SCENE_FILE = "scene.toml"
STEPS_DEG = (4.0, 2.0, 1.0, 0.5)


def _setup(scene_path: Path):
    import numpy as np
    from numkin.scene import load_scene

    scene = load_scene(scene_path)
    if scene.kind == "stability":
        raise SystemExit(f"{scene_path}: a homework needs a scene with a [mechanism]")
    if not scene.speed:
        raise SystemExit(f"{scene_path}: [input] speed is needed for the velocity questions")
    mech = scene.build_mechanism()
    output = scene.report.get("quantity") or mech.unknowns[-1]
    if output not in mech.unknowns:
        raise SystemExit(f"{scene_path}: [report] quantity {output!r} is not one of {list(mech.unknowns)}")
    inputs_deg = np.degrees(scene.inputs())
    if scene.checks:
        check = float(scene.checks[0]["at_deg"])
    else:
        check = 100.0 if inputs_deg[0] + 5 <= 100.0 <= inputs_deg[-1] - 5 else float(inputs_deg[len(inputs_deg) // 2])
    k = int(np.argmin(np.abs(inputs_deg - check)))
    if abs(inputs_deg[k] - check) > 1e-9 or k < 1 or k > len(inputs_deg) - 2:
        raise SystemExit(f"{scene_path}: the check angle {check:g}° must be an interior angle of the sweep")
    return scene, mech, output, inputs_deg, check, k


def _name(scene_path: Path) -> str:
    return "hw_" + re.sub(r"\W+", "_", Path(scene_path).stem).strip("_").lower()


def expected(folder: Path) -> dict:
    """Reference values of a generated homework, computed by numkin from its scene."""
    import numpy as np
    from numkin import analytic, derivatives

    scene, mech, output, inputs_deg, check, k = _setup(Path(folder) / SCENE_FILE)
    sweep = mech.sweep(scene.inputs(), guess=scene.guess_values(mech))
    q = np.asarray(sweep[output], dtype=float)
    h = math.radians(scene.step_deg)
    w = scene.speed
    kin = analytic.kinematics(sweep, omega=w)
    angle = output in mech.angles
    rate = kin[("omega_" if angle else "v_") + output].to_numpy()
    accel = kin[("alpha_" if angle else "a_") + output].to_numpy()
    picks = sorted({int(i) for i in np.linspace(1, len(q) - 2, 12).round()} | {k})
    picks = [i for i in picks if float(inputs_deg[i]).is_integer()]
    at = lambda y: {int(inputs_deg[i]): float(y[i]) for i in picks}  # noqa: E731
    wrap = (lambda a: np.mod(a, 2 * np.pi)) if angle else (lambda a: a)
    base = {name: float(sweep[name][k]) for name in mech.unknowns}
    errors = []
    for step in STEPS_DEG:
        hs = math.radians(step)
        ends = [mech.solve(math.radians(check) + s * hs, guess=base).x for s in (-1, 1)]
        i = mech.unknowns.index(output)
        errors.append(abs(w * (ends[1][i] - ends[0][i]) / (2 * hs) - rate[k]))
    return {
        "q": at(wrap(q)),
        "q_check": float(wrap(q)[k]),
        "rate_centred": at(w * derivatives.centred(q, h)),
        "rate_forward": at(w * derivatives.forward(q, h)),
        "rate_exact": float(rate[k]),
        "accel_second": at(w**2 * derivatives.second_difference(q, h)),
        "accel_forward_twice": at(w**2 * derivatives.forward_of_forward(q, h)),
        "accel_exact": float(accel[k]),
        "errors": [float(e) for e in errors],
    }


def _numpy_code(exprs, mech, names) -> list[str]:
    """numpy source for each sympy expression, parameters replaced by their values."""
    import sympy as sp
    from sympy.printing.numpy import NumPyPrinter

    printer = NumPyPrinter({"fully_qualified_modules": True})
    subs = {sym: sp.Float(value, 15) for sym, value in mech.parameters.items()}
    subs.update({u: sp.Symbol(n) for u, n in zip(mech.unknown_symbols, names)})
    subs[mech.input_symbol] = sp.Symbol("theta")
    return [printer.doprint(sp.sympify(e).xreplace(subs)).replace("numpy.", "np.") for e in exprs]


def _linkage_module(scene, mech) -> str:
    import sympy as sp

    names = list(mech.unknowns)
    residuals = [r for lp in mech.loops for r in lp.residuals]
    jac = [[sp.diff(r, u) for u in mech.unknown_symbols] for r in residuals]
    f_theta = [sp.diff(r, mech.input_symbol) for r in residuals]
    unpack = f"    {', '.join(names)}{',' if len(names) == 1 else ''} = u\n"
    rows = _numpy_code(residuals, mech, names)
    dtheta = _numpy_code(f_theta, mech, names)
    jrows = [_numpy_code(row, mech, names) for row in jac]
    units = ", ".join(f"{n} ({'rad' if n in mech.angles else mech.length_unit})" for n in names)
    fline = ",\n        ".join(rows)
    tline = ",\n        ".join(dtheta)
    jline = ",\n        ".join("[" + ", ".join(r) + "]" for r in jrows)
    return f'''"""Loop-closure equations of the linkage of this homework (scene "{scene.name}").

Unknowns u = ({units}); input angle theta in rad. Written out from the scene by
numkin; nothing here needs numkin.
"""

import numpy as np

UNKNOWNS = {tuple(names)!r}


def F(u, theta):
    """Loop-closure residual: zero when u closes the loops at the input angle theta."""
{unpack}    return np.array([
        {fline},
    ], dtype=float)


def J(u, theta):
    """Jacobian dF/du."""
{unpack}    return np.array([
        {jline},
    ], dtype=float)


def F_theta(u, theta):
    """dF/dtheta at fixed u."""
{unpack}    return np.array([
        {tline},
    ], dtype=float)
'''


def _fmt(x: float) -> str:
    return f"{x:.12g}"


def generate(scene_path: Path, root: Path) -> Path:
    """Write ``root/hw_<scene>/``: the master, linkage.py, scene.toml and mistakes.toml.

    Run ``build.py expected`` on the folder afterwards (``new`` does) to fill in
    the reference values.
    """
    import numpy as np

    scene_path = Path(scene_path)
    scene, mech, output, inputs_deg, check, k = _setup(scene_path)
    name = _name(scene_path)
    folder = Path(root) / name
    folder.mkdir(parents=True, exist_ok=True)
    shutil.copy(scene_path, folder / SCENE_FILE)
    (folder / "linkage.py").write_text(_linkage_module(scene, mech))

    sweep = mech.sweep(scene.inputs(), guess=scene.guess_values(mech))
    start = [float(sweep[u][0]) for u in mech.unknowns]
    guess = [round(v, 1) if u in mech.angles else round(v, 0) for u, v in zip(mech.unknowns, start)]
    angle = output in mech.angles
    unit = "rad" if angle else mech.length_unit
    kinds = ["rad" if u in mech.angles else mech.length_unit for u in mech.unknowns]
    if len(set(kinds)) == 1:  # all angles, or all lengths
        guess_units = f"in {kinds[0]}"
    else:
        guess_units = ", ".join(f"{u} in {k}" for u, k in zip(mech.unknowns, kinds))
    out_i = mech.unknowns.index(output)
    n = len(inputs_deg)
    grid = (float(inputs_deg[0]), float(inputs_deg[-1]), float(scene.step_deg))
    values = dict(
        name=name, title=scene.description, scene=scene.name, output=output, unit=unit,
        rate_unit=f"{unit}/s", accel_unit=f"{unit}/s²", n=n, out_i=out_i,
        start=_fmt(grid[0]), stop=_fmt(grid[1]), step=_fmt(grid[2]), check=_fmt(check),
        omega=repr(float(scene.speed)), speed=scene.speed_text or f"{scene.speed:g} rad/s",
        guess=repr(guess), guess_units=guess_units, unknowns=", ".join(mech.unknowns), grid=repr(grid),
        angle=repr(angle), steps=repr(list(STEPS_DEG)), m=len(mech.unknowns),
        angle_columns=repr([i for i, u in enumerate(mech.unknowns) if u in mech.angles]),
        unit_text=mech.length_unit,
    )
    if not float(check).is_integer():
        raise SystemExit(f"{scene_path}: the check angle must be a whole number of degrees")
    template = (Path(__file__).with_name("fromscene_master.py.txt")).read_text()
    (folder / f"{name}.py").write_text(template.format(**values))
    (folder / "mistakes.toml").write_text(MISTAKES.format(**values) + (ANGLE_MISTAKES if angle else ""))
    return folder


MISTAKES = '''# Deliberate mistakes of this generated homework (see assignments/README.md). Rubric:
# one point per check, 11 in all (q1: 4, q2: 3, q3: 2, q4: 2).

[[mistake]]
name = "forward-where-centred"
about = "the forward difference where the centred one is asked"
score = 10  # fails only the hidden check of `rate_c`; the public check recomputes the rate from `X`
feedback = ["`rate_c`: this matches the forward difference; the question asks for centred"]

[[mistake.edit]]
find = "rate_c = OMEGA * centred_difference(q, h)"
replace = "rate_c = OMEGA * forward_difference(q, h)"

[[mistake]]
name = "plus-F-theta"
about = "the exact rate solved from J dx/dθ = +∂F/∂θ, the minus sign dropped"
score = 7  # fails the two checks of `rate_exact` (q2) and both of q4, whose errors are taken against it
feedback = ["{rate_unit}: the sign is flipped: check the minus sign in J dx/dθ = −∂F/∂θ"]
not_feedback = ["sense of rotation"]

[[mistake.edit]]
find = "rate_exact = OMEGA * np.linalg.solve(J(xk, tk), -F_theta(xk, tk))[OUT]"
replace = "rate_exact = OMEGA * np.linalg.solve(J(xk, tk), F_theta(xk, tk))[OUT]"

[[mistake]]
name = "step-in-degrees"
about = "the second difference divided by h² with h = 1 (degree) where radians are asked"
score = 9  # fails the two checks of `accel_c` (q3); nothing else uses it
feedback = ["`accel_c`: off by a factor 1/3283 (= (π/180)²)"]

[[mistake.edit]]
find = "accel_c = OMEGA**2 * second_difference(q, h)"
replace = "accel_c = OMEGA**2 * second_difference(q, np.degrees(h))"
'''

ANGLE_MISTAKES = '''
[[mistake]]
name = "q-check-degrees"
about = "the output at the check angle handed in in degrees where radians are asked"
score = 10  # fails only the hidden check of `q_check`; `X` and `q` stay in rad
feedback = ["degrees where radians are asked? (expected"]
not_feedback = ["off by +", "off by -"]

[[mistake.edit]]
find = "q_check = q[k_check]"
replace = "q_check = np.degrees(q[k_check])"
'''
