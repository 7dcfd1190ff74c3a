"""The S1 circle figure: per run, the polar plot of the path with most of
the radius suppressed (so micrometres of radial error show against the
circle) and the contour error against time, all rows on one error scale.

Data: {"title", "radius_mm", "suppressed": 0.998, "rows": [{"label",
"stats": {"max_um", "mean_um", "std_um"}, "t_s", "x_mm", "y_mm",
"ref_x_mm", "ref_y_mm" (optional: the centre is fitted to them, else
the origin), "contour_um"}]}.
"""

import numpy as np

from tnvplot import style
from tnvplot.envelope import clip, envelope, envelope_by_index

DEFAULT_SUPPRESSED = 0.998


def fit_centre(x, y):
    """Least-squares circle through (x, y): centre and radius."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    a = np.column_stack([x, y, np.ones_like(x)])
    b = x * x + y * y
    (p, q, c), *_ = np.linalg.lstsq(a, b, rcond=None)
    cx, cy = p / 2.0, q / 2.0
    return cx, cy, float(np.sqrt(max(c + cx * cx + cy * cy, 0.0)))


def centre_of(row):
    rx, ry = row.get("ref_x_mm"), row.get("ref_y_mm")
    if rx is not None and ry is not None and len(rx) >= 3 and np.ptp(rx) > 0 and np.ptp(ry) > 0:
        cx, cy, _ = fit_centre(rx, ry)
        return cx, cy
    return 0.0, 0.0


def nice_ceiling(v):
    if not v > 0:
        return 1.0
    p = 10.0 ** np.floor(np.log10(v))
    for m in (1.0, 2.0, 5.0, 10.0):
        if m * p >= v:
            return m * p
    return 10.0 * p


def axis_ceiling(v):
    """A round upper limit at least v: a multiple of a 1-2-5 step near v / 5."""
    if not v > 0:
        return 1.0
    step = nice_ceiling(v / 5.0)
    return float(np.ceil(v / step) * step)


def polar_panel(ax, row, radius_mm, suppressed, color, with_note=True):
    """Radial error about the nominal circle, magnified 1 / (1 - suppressed)."""
    cx, cy = centre_of(row)
    x = np.asarray(row["x_mm"], dtype=float) - cx
    y = np.asarray(row["y_mm"], dtype=float) - cy
    theta = np.arctan2(y, x)
    error_um = (np.hypot(x, y) - radius_mm) * 1000.0
    target_um = (1.0 - suppressed) * radius_mm * 1000.0  # where r = R is drawn
    worst = float(np.max(np.abs(error_um))) if error_um.size else 0.0
    r_max = max(2.0 * target_um, target_um + nice_ceiling(1.1 * worst))
    r_plot, clipped = clip(error_um + target_um, 0.0, r_max)
    theta, r_plot = envelope_by_index(r_plot, [theta, r_plot], 720)
    ax.plot(np.linspace(0, 2 * np.pi, 361), np.full(361, target_um), color=style.REFERENCE_COLOR, lw=0.8, ls="--",
            zorder=1)
    ax.plot(theta, r_plot, color=color, lw=0.4, zorder=2)
    ax.set_ylim(0.0, r_max)
    step = nice_ceiling(r_max / 6.0)
    ticks = [target_um + k * step for k in range(-8, 9) if 0.0 <= target_um + k * step <= r_max + 1e-9]
    ax.set_yticks(ticks)
    ax.set_yticklabels([f"{t - target_um:+g}" if abs(t - target_um) > 1e-9 else "0" for t in ticks])
    ax.set_rlabel_position(67.5)
    ax.tick_params(axis="y", labelsize=7 if len(ticks) > 4 else 8)
    ax.set_xticks(np.deg2rad([0, 90, 180, 270]))
    ax.set_xticklabels(["0\u00b0", "90\u00b0", "180\u00b0", "270\u00b0"])
    magnification = 1.0 / (1.0 - suppressed)
    note = (f"{suppressed * 100:.1f} % of R = {radius_mm:g} mm suppressed:\n"
            f"radial error magnified {magnification:.0f}\u00d7\n"
            f"rings: error in {style.UM}; dashed: nominal")
    if clipped:
        note += f"\n{clipped} samples drawn on the edge"
    if with_note or clipped:
        # Below the panel: above it, the note would meet the figure's title.
        ax.set_xlabel(note, fontsize=7, labelpad=6)
    return clipped


def bucket_stats(t, v, buckets):
    """Per bucket of the time range: its first and last time, min, max and mean."""
    t = np.asarray(t, dtype=float)
    v = np.asarray(v, dtype=float)
    if t.size == 0:
        return (np.array([]),) * 5
    span = max(float(t.max() - t.min()), 1e-12)
    index = np.minimum(((t - t.min()) / span * buckets).astype(int), buckets - 1)
    used = np.unique(index)
    lo = np.array([v[index == b].min() for b in used])
    hi = np.array([v[index == b].max() for b in used])
    mean = np.array([v[index == b].mean() for b in used])
    t_lo = np.array([t[index == b].min() for b in used])
    t_hi = np.array([t[index == b].max() for b in used])
    return t_lo, t_hi, lo, hi, mean


def time_panel(ax, row, y_max_um, color, last=True):
    t = np.asarray(row["t_s"], dtype=float)
    e = np.asarray(row["contour_um"], dtype=float)
    e, clipped = clip(e, 0.0, y_max_um)
    # Per pixel column: the min-max range shaded (every peak kept) and the mean as a line.
    t_lo, t_hi, lo, hi, mean = bucket_stats(t, e, style.ENVELOPE_BUCKETS // 2)
    centre = 0.5 * (t_lo + t_hi)
    ax.fill_between(centre, lo, hi, color=color, alpha=0.35, lw=0)
    ax.plot(centre, mean, color=color, lw=0.7)
    ax.set_ylim(0.0, y_max_um)
    if t.size:
        ax.set_xlim(0.0, max(float(t.max()), 1e-3))
    if last:
        ax.set_xlabel("time since start of motion (s)\nshaded: min to max per column; line: mean")
    ax.set_ylabel(f"contour error ({style.UM})")
    s = row.get("stats") or {}
    title = row["label"]
    if s:
        stats = f"max {s['max_um']:.3f} {style.UM}, mean {s['mean_um']:.3f} {style.UM}, std {s['std_um']:.3f} {style.UM}"
        one_line = f"{title}: {stats}"
        # The statistics on a line of their own when the label and they do not fit on one.
        fits = style.wrap(one_line, ax.get_position().width * ax.figure.get_figwidth(), 8) == one_line
        title = one_line if fits else f"{title}\n{stats}"
    width_in = ax.get_position().width * ax.figure.get_figwidth()
    ax.set_title(style.wrap(title, width_in, 8), fontsize=8, loc="left", color=color)
    return clipped


def draw(data):
    rows = data["rows"]
    radius_mm = float(data["radius_mm"])
    suppressed = float(data.get("suppressed", DEFAULT_SUPPRESSED))
    n = max(len(rows), 1)
    fig = style.figure(style.DOUBLE_COLUMN_IN, 0.5 + 3.0 * n)
    style.suptitle(fig, style.units(data.get("title", "")), fontsize=10)
    worst = max((float(np.max(r["contour_um"])) for r in rows if len(r["contour_um"])), default=0.0)
    y_max = axis_ceiling(1.05 * worst)
    grid = fig.add_gridspec(n, 2, width_ratios=[1.0, 1.6])
    for i, row in enumerate(rows):
        color = style.COLORS[i % len(style.COLORS)]
        polar_panel(fig.add_subplot(grid[i, 0], projection="polar"), row, radius_mm, suppressed, color, i == 0)
        time_panel(fig.add_subplot(grid[i, 1]), row, y_max, color, i + 1 == len(rows))
    return fig
