"""Stacked panels over a shared x axis: the time-series figures (ARSC runs,
soak, shaper moves and jogs), the per-part boring figure and the shaper
sensitivity curves.

Data: {"title", "subtitle", "x_label", "sharex" (default true),
"vlines": {"x": [...], "label", "color"}, "panels": [{"y_label",
"y_range": [lo, hi] (values beyond it are drawn on its edge and counted),
"y_cap": [lo, hi] (the range from the data, but no wider than this),
"log_y", "x_range", "x_label", "band": [lo, hi], "band_label", "note",
"hlines": [{"y", "label"}], "series": [{"label", "x", "y", "style":
"line" | "dashed" | "reference" | "steps" | "dots" | "bars", "color",
"width" (bars)}]}]}. Series are drawn in order, a reference (wide, light)
underneath the rest; every labelled series is in the legend above its
panel.
"""

from matplotlib import ticker
import numpy as np

from tnvplot import style
from tnvplot.envelope import clip, envelope

LINE_STYLES = {"line": "-", "dashed": "--", "reference": "-", "steps": "--"}


def _two_and_five(value, _pos):
    """A minor tick's label on a log axis: only at 2 and 5 times a decade."""
    mantissa = value / 10.0 ** np.floor(np.log10(value) + 1e-9)
    return f"{value:g}" if round(mantissa) in (2, 5) and abs(mantissa - round(mantissa)) < 1e-6 else ""


def _series(ax, s, color, y_range, log_y):
    x = np.asarray(s.get("x", []), dtype=float)
    y = np.asarray(s.get("y", []), dtype=float)
    kind = s.get("style", "line")
    label = style.units(s["label"]) if s.get("label") else None
    clipped = 0
    if y_range is not None:
        y_lo, y_hi = y_range
        inside = np.clip(y, y_lo, y_hi)
        clipped = int(np.count_nonzero(inside != y))
        if clipped and kind != "bars":
            moved = inside != y
            ax.plot(x[moved], inside[moved], ls="none", marker="|", ms=4, color=color, zorder=4, clip_on=False)
        y = inside
    if log_y:
        y = np.where(y > 0, y, np.nan)
    if kind == "bars":
        ax.bar(x + float(s.get("offset", 0.0)), y, width=float(s.get("width", 0.8)), color=color, label=label,
               align="edge" if "offset" in s else "center", zorder=2)
    elif kind == "dots":
        ax.plot(x, y, ls="none", marker="o", ms=2.2, mfc=color, mec=color, label=label, zorder=3)
    elif kind == "rings":
        ax.plot(x, y, ls="none", marker="o", ms=3.2, mfc="none", mec=color, mew=0.7, label=label, zorder=3)
    elif kind == "steps":
        ax.step(x, y, where="mid", color=color, lw=0.9, ls="--", label=label, zorder=2)
    else:
        x, y = envelope(x, y, style.ENVELOPE_BUCKETS)
        width = 2.2 if kind == "reference" else 0.8
        alpha = 0.55 if kind == "reference" else 1.0
        ax.plot(x, y, color=color, lw=width, ls=LINE_STYLES.get(kind, "-"), alpha=alpha, label=label,
                zorder=1 if kind == "reference" else 2)
        if s.get("markers") and x.size <= 200:
            ax.plot(x, y, ls="none", marker="o", ms=2.2, color=color, zorder=3)
    return clipped


def capped_range(panel):
    """The data's range within "y_cap" [lo, hi], with 8 % head room: a value
    beyond the cap is drawn on the edge, not allowed to flatten the rest."""
    lo_cap, hi_cap = panel["y_cap"]
    values = [np.clip(np.asarray(s.get("y", []), dtype=float), lo_cap, hi_cap) for s in panel.get("series", [])]
    values = np.concatenate(values) if values else np.array([])
    values = values[np.isfinite(values)]
    if values.size == 0 or not np.ptp(values) > 0:
        mid = float(values[0]) if values.size else 0.0
        return [mid - 1.0, mid + 1.0]
    pad = 0.08 * float(np.ptp(values))
    return [float(values.min()) - pad, float(values.max()) + pad]


def draw_panel(ax, panel, vlines=None):
    y_range = panel.get("y_range") or (capped_range(panel) if panel.get("y_cap") else None)
    log_y = bool(panel.get("log_y"))
    if panel.get("band"):
        lo, hi = panel["band"]
        ax.axhspan(lo, hi, color="#2ca02c", alpha=0.12, lw=0, label=style.units(panel.get("band_label", "")) or None,
                   zorder=0)
    for h in panel.get("hlines", []):
        ax.axhline(h["y"], color=h.get("color", "#2a7a2a"), lw=0.8, ls=":", label=style.units(h.get("label", "")) or None)
    if vlines and vlines.get("x"):
        for i, x in enumerate(vlines["x"]):
            ax.axvline(x, color=vlines.get("color", "#7b3fa0"), lw=0.7, ls=(0, (4, 3)),
                       label=style.units(vlines.get("label", "")) if i == 0 and vlines.get("label") else None, zorder=1)
    clipped = 0
    for i, s in enumerate(panel.get("series", [])):
        color = s.get("color") or style.COLORS[i % len(style.COLORS)]
        clipped += _series(ax, s, color, y_range, log_y)
    if log_y:
        ax.set_yscale("log")
        # Plain numbers (0.05, not 5e-02) on the decades and on 2 and 5 between them.
        ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
        ax.yaxis.set_minor_formatter(ticker.FuncFormatter(_two_and_five))
    if y_range is not None:
        ax.set_ylim(*y_range)
    elif not log_y:
        lo, hi = ax.get_ylim()
        if hi - lo < 1e-6 * max(1.0, abs(hi)):  # a flat trace: give it room, not rounding noise
            mid = 0.5 * (lo + hi)
            ax.set_ylim(mid - 1.0, mid + 1.0)
    if not log_y:
        ax.ticklabel_format(axis="y", useOffset=False)
    if panel.get("x_range"):
        ax.set_xlim(*panel["x_range"])
    ax.set_ylabel(style.units(panel.get("y_label", "")))
    if panel.get("x_label"):
        ax.set_xlabel(style.units(panel["x_label"]))
    note = style.units(panel.get("note", ""))
    if clipped:
        note = (note + "; " if note else "") + f"{clipped} samples beyond the axis drawn on its edge (|)"
    if note:
        ax.text(0.995, 0.97, note, transform=ax.transAxes, ha="right", va="top", fontsize=8, color="#444",
                bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.75, "pad": 1.0}, zorder=5)
    style.legend_above(ax, panel.get("legend_columns"))


def draw(data):
    panels = data["panels"]
    n = max(len(panels), 1)
    width = style.SINGLE_COLUMN_IN if data.get("width") == "single" else style.DOUBLE_COLUMN_IN
    fig = style.figure(width, 0.7 + 1.75 * n)
    title = style.units(data.get("title", ""))
    if data.get("subtitle"):
        title += "\n" + style.units(data["subtitle"])
    style.suptitle(fig, title)
    axes = fig.subplots(n, 1, sharex=data.get("sharex", True), squeeze=False)[:, 0]
    for ax, panel in zip(axes, panels):
        draw_panel(ax, panel, data.get("vlines"))
    if data.get("x_label"):
        axes[-1].set_xlabel(style.units(data["x_label"]))
    return fig
