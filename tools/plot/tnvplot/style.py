"""House style: sizes readable at a paper's column width, units spelled
right, one way to make and save a figure."""

from pathlib import Path
import textwrap

import matplotlib

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

# A single column is 3.5 in wide, a double column 7 in.
SINGLE_COLUMN_IN = 3.5
DOUBLE_COLUMN_IN = 7.0
# The width of an axes in output pixels is about this many buckets: the
# envelope decimation keeps the min and max of each.
ENVELOPE_BUCKETS = 1200

MICRO = "\u00b5"
UM = MICRO + "m"

COLORS = ["#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"]
REFERENCE_COLOR = "#8a8a8a"
FORMATS = {".svg": "svg", ".png": "png", ".pdf": "pdf"}

RC = {
    "font.size": 8,
    "axes.titlesize": 9,
    "axes.labelsize": 8,
    "xtick.labelsize": 8,
    "ytick.labelsize": 8,
    "legend.fontsize": 8,
    "figure.titlesize": 10,
    "axes.grid": True,
    "grid.color": "#e4e4e4",
    "grid.linewidth": 0.5,
    "axes.linewidth": 0.6,
    "lines.linewidth": 0.9,
    "legend.frameon": False,
    "svg.fonttype": "none",
    "svg.hashsalt": "tnv",
    "figure.dpi": 100,
    "savefig.dpi": 200,
}


def units(text):
    """Axis and legend text with the micro sign: 'um' as a unit becomes 'µm'."""
    out = []
    for word in str(text).replace("(um)", f"({UM})").split(" "):
        out.append(UM if word == "um" else word)
    return " ".join(out)


def wrap(text, width_in, fontsize):
    """text broken into lines that fit width_in inches at fontsize points
    (an average glyph of the sans-serif font is about half an em wide), each
    given line kept apart."""
    chars = max(int(width_in * 72.0 / (0.5 * fontsize)), 20)
    return "\n".join(textwrap.fill(line, chars) if line else line for line in str(text).split("\n"))


def suptitle(fig, text, fontsize=9):
    """A figure title that never runs off the figure."""
    if text:
        fig.suptitle(wrap(text, fig.get_figwidth() * 0.96, fontsize), fontsize=fontsize)


def figure(width_in, height_in):
    matplotlib.rcParams.update(RC)
    return Figure(figsize=(width_in, height_in), layout="constrained")


def output_format(path):
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(f"{path}: the figure's format comes from its suffix: .svg, .png or .pdf")
    return FORMATS[suffix]


def save(fig, path):
    fig.savefig(path, format=output_format(path), metadata=_metadata(path))


def _metadata(path):
    fmt = output_format(path)
    if fmt == "svg":
        return {"Date": None, "Creator": "tnvplot"}
    if fmt == "pdf":
        return {"CreationDate": None, "Creator": "tnvplot"}
    return {"Software": "tnvplot"}


def legend_above(ax, ncol=None):
    """The legend in a row above the axes, never over the data."""
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return
    ax.legend(handles, labels, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=ncol or min(len(handles), 4),
              borderaxespad=0.2, handlelength=1.8, columnspacing=1.0)
