"""A scheme registered at run time goes through every report table and figure by name.

Independent references: the 7-point centred stencil's order of accuracy (6,
from its Taylor expansion) and the textbook optimal step of a first
derivative of order p, eps^(1/(p + 1)).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from numkin import linkages, report, schemes

pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


@pytest.fixture
def seven_point():
    """The 7-point centred first derivative (offsets -3..3), registered for one test."""
    scheme = schemes.register("seven_point_c", range(-3, 4), 1)
    yield scheme
    schemes.unregister("seven_point_c")


def test_convergence_table_gives_order_six(seven_point):
    mech = linkages.slider_crank(80, 200)
    t = report.convergence_table(mech, omega=1.0, quantity="x", grids=(24, 36, 48, 72),
                                 schemes=("seven_point_c",))
    orders = t.loc[t["scheme"] == "seven_point_c", "observed order [-]"].dropna().to_numpy(dtype=float)
    assert orders.size >= 2
    assert orders[-1] == pytest.approx(6.0, abs=0.2)


def test_roundoff_table_gives_a_finite_optimum(seven_point):
    mech = linkages.slider_crank(80, 200)
    t = report.roundoff_table(mech, quantity="x", check_angle=math.radians(40), schemes=("centred", "seven_point_c"))
    row = t.set_index("scheme").loc["seven_point_c"]
    hstar = float(row["measured optimal h [rad]"])
    assert math.isfinite(hstar) and hstar > 0
    # round-off eps/h against truncation h^6: the optimum near eps^(1/7), within a decade
    assert 0.1 < hstar / np.finfo(float).eps ** (1 / 7) < 10


def test_figures_draw_a_registered_scheme(seven_point):
    import matplotlib

    matplotlib.use("Agg")
    from numkin import figures

    mech = linkages.slider_crank(80, 200)
    t = report.convergence_table(mech, omega=1.0, quantity="x", grids=(36, 72), schemes=("centred", "seven_point_c"))
    fig = figures.convergence(t)
    labels = [line.get_label() for ax in fig.axes for line in ax.get_lines()]
    assert any("seven point c" in lab for lab in labels)
    assert figures.registries.family_of("seven_point_c") == "seven_point_c"
    import matplotlib.pyplot as plt

    plt.close(fig)
