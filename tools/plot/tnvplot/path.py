"""tnv-hil path --plot: the programmed path with where the contour error is
largest, the contour error and the planner's path speed against time.

Reads the path CSV (tools/hil/path_csv.hpp): t_s, x_ref_mm, y_ref_mm,
x_mm, y_mm, contour_um, path_speed_mm_s, then z_ref_mm, z_mm (not drawn).
"""

import numpy as np

from tnvplot import style
from tnvplot.envelope import envelope


def read_csv(path):
    table = np.genfromtxt(path, delimiter=",", names=True, dtype=float)
    return {name: np.atleast_1d(table[name]) for name in table.dtype.names}


def draw(table, title=""):
    fig = style.figure(style.DOUBLE_COLUMN_IN, 6.4)
    style.suptitle(fig, style.units(title))
    grid = fig.add_gridspec(3, 1, height_ratios=[2.4, 1.0, 1.0])
    xy = fig.add_subplot(grid[0])
    contour = np.asarray(table["contour_um"])
    xy.plot(table["x_ref_mm"], table["y_ref_mm"], color=style.REFERENCE_COLOR, lw=1.6, label="reference path")
    worst = float(contour.max()) if contour.size else 0.0
    hot = contour >= 0.9 * worst if worst > 0 else np.zeros(contour.size, dtype=bool)
    xy.plot(table["x_mm"][hot], table["y_mm"][hot], ls="none", marker="o", ms=3.5, mfc="none", mec="#c0392b",
            mew=0.8, label=f"contour error within 10 % of its maximum ({worst:.3f} {style.UM})")
    xy.set_aspect("equal", adjustable="datalim")
    xy.set_xlabel("x (mm)")
    xy.set_ylabel("y (mm)")
    style.legend_above(xy, 2)
    t = table["t_s"]
    err = fig.add_subplot(grid[1])
    te, e = envelope(t, contour, style.ENVELOPE_BUCKETS)
    err.plot(te, e, color="#c0392b", lw=0.7)
    err.set_ylabel(f"contour error ({style.UM})")
    err.set_ylim(bottom=0.0)
    speed = fig.add_subplot(grid[2], sharex=err)
    ts, v = envelope(t, table["path_speed_mm_s"], style.ENVELOPE_BUCKETS)
    speed.plot(ts, v, color="#1f5fa8", lw=0.8)
    speed.set_ylabel("path speed (mm/s)")
    speed.set_xlabel("time (s)")
    speed.set_ylim(bottom=0.0)
    if t.size:
        err.set_xlim(0.0, max(float(t.max()), 1e-3))
    return fig
