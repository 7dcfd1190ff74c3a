"""Plots of captures saved by tnvctl capture --csv: a circle capture (the
reference runs on a circle) as the S1 circle figure, anything else (a
straight move, a jog, a force trace) as one time panel per channel.
Several circle captures compare as rows on one contour-error scale.
"""

import numpy as np

from tnvplot import circle, panels, style

UNIT_SUFFIXES = [("_mm_s2", "mm/s\u00b2"), ("_mm_s", "mm/s"), ("_mm", "mm"), ("_um", style.UM), ("_N", "N")]


def read_csv(path):
    table = np.genfromtxt(path, delimiter=",", names=True, dtype=float, deletechars="")
    return {name: np.atleast_1d(table[name]) for name in table.dtype.names}


def label_of(column):
    for suffix, unit in UNIT_SUFFIXES:
        if column.endswith(suffix):
            return f"{column[: -len(suffix)]} ({unit})"
    return column


def in_motion(table):
    tick = table.get("motion_tick")
    if tick is None:
        return np.zeros(len(table["t_s"]), dtype=bool)
    return tick >= 0


def is_circle(table):
    """True when the reference in motion lies on a circle it goes round at
    least half of: a straight move or a jog is not one."""
    if not all(k in table for k in ("motion_tick", "ref_x_mm", "ref_y_mm", "pos_x_mm", "pos_y_mm")):
        return False
    moving = in_motion(table)
    if np.count_nonzero(moving) < 8:
        return False
    x, y = table["ref_x_mm"][moving], table["ref_y_mm"][moving]
    if np.ptp(x) <= 0 or np.ptp(y) <= 0:
        return False
    cx, cy, r = circle.fit_centre(x, y)
    if not (r > 0 and np.isfinite(r)):
        return False
    spread = np.hypot(x - cx, y - cy) - r
    if np.sqrt(np.mean(spread * spread)) > 1e-3 * r or r > 10.0 * max(np.ptp(x), np.ptp(y)):
        return False
    sweep = np.ptp(np.unwrap(np.arctan2(y - cy, x - cx)))
    return sweep >= np.pi


def circle_row(table, label):
    moving = in_motion(table)
    rx, ry = table["ref_x_mm"][moving], table["ref_y_mm"][moving]
    px, py = table["pos_x_mm"][moving], table["pos_y_mm"][moving]
    if "contour_um" in table:
        contour = table["contour_um"][moving]
    else:
        cx, cy, r = circle.fit_centre(rx, ry)
        contour = np.abs(np.hypot(px - cx, py - cy) - r) * 1000.0
    _, _, radius = circle.fit_centre(rx, ry)
    stats = {"max_um": float(contour.max()), "mean_um": float(contour.mean()), "std_um": float(contour.std())}
    row = {"label": label, "stats": stats, "t_s": table["motion_tick"][moving] * 1e-3, "x_mm": px, "y_mm": py,
           "ref_x_mm": rx, "ref_y_mm": ry, "contour_um": contour}
    return row, radius


def channel_data(table, title):
    """One panel per channel; reference and position of an axis share one,
    with the following error (µm) beneath."""
    t = table["t_s"] - table["t_s"][0] if len(table["t_s"]) else table["t_s"]
    out = []
    used = {"t_s"}
    color = 0
    for axis in ("x", "y"):
        ref, pos = f"ref_{axis}_mm", f"pos_{axis}_mm"
        if ref not in table or pos not in table:
            continue
        used |= {ref, pos}
        c = style.COLORS[color % len(style.COLORS)]
        color += 1
        out.append({"y_label": f"{axis} (mm)", "series": [
            {"label": f"ref_{axis} (reference)", "x": t, "y": table[ref], "style": "reference",
             "color": style.REFERENCE_COLOR},
            {"label": f"pos_{axis} (encoder)", "x": t, "y": table[pos], "color": c}]})
        out.append({"y_label": f"following error {axis} ({style.UM})", "note": "ref - pos; positive: the table lags",
                    "series": [{"label": "", "x": t, "y": (table[ref] - table[pos]) * 1000.0, "color": c}]})
    for name in table:
        if name in used:
            continue
        c = style.COLORS[color % len(style.COLORS)]
        color += 1
        out.append({"y_label": label_of(name), "series": [{"label": "", "x": t, "y": table[name], "color": c}]})
    return {"title": title, "x_label": "time since the first sample (s)", "panels": out}


def draw(tables, labels, title=""):
    """tables: capture columns by name, one per CSV; labels: one per table."""
    circles = [is_circle(t) for t in tables]
    if all(circles):
        rows, radius = [], 0.0
        for table, label in zip(tables, labels):
            row, r = circle_row(table, label)
            rows.append(row)
            radius = radius or r
        return circle.draw({"title": title, "radius_mm": radius, "rows": rows})
    if len(tables) > 1:
        raise ValueError("comparing several captures needs circle captures (motion_tick, ref_x/y, pos_x/y on a circle)")
    return panels.draw(channel_data(tables[0], title))
