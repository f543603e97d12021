"""`ironbark aero plot`: every curve of a panel table's figure is told apart by its colour.

The shipped Kestrel table has 13 angles of attack and 15 Mach numbers; with Matplotlib's
10-colour default cycle the 0/60, 2/75 and 4/90 deg curves (and Mach 0.05/1.05, ...)
were drawn in the same colour under one legend, so a reader could not tell which
curve was which (README check, session 21).
"""
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ironbark_opt.aero.table import AeroTable  # noqa: E402
from ironbark_opt.cli.aero import table_figure  # noqa: E402

TABLE = Path(__file__).parents[2] / "tables" / "Kestrel.csv"


def test_every_curve_has_its_own_colour():
    table = AeroTable.load(TABLE)
    fig = table_figure(table, "Kestrel")
    try:
        n_alpha, n_mach = len(table.alpha), len(table.mach)
        assert (n_alpha, n_mach) == (13, 15)                    # more curves than the 10-colour cycle
        expected = {(0, 0): n_alpha, (0, 1): n_mach, (1, 0): n_mach, (1, 1): n_alpha - 1}
        for (i, j), count in expected.items():
            lines = fig.axes[2 * i + j].get_lines()
            assert len(lines) == count
            colours = np.array([matplotlib.colors.to_rgb(line.get_color()) for line in lines])
            gaps = np.linalg.norm(colours[:, None] - colours[None, :], axis=-1)
            np.fill_diagonal(gaps, np.inf)
            assert gaps.min() > 0.02, f"panel ({i}, {j}): two curves share a colour"
    finally:
        plt.close(fig)
