"""Figures of the TNV-40 host tools, drawn with matplotlib.

Each figure kind reads what the tools write (a plot-data JSON, a path or
capture CSV) and saves SVG, PNG or PDF by the output file's suffix:

    python3 -m tnvplot circle  DATA.json     OUT.svg
    python3 -m tnvplot panels  DATA.json     OUT.pdf
    python3 -m tnvplot path    PATH.csv      OUT.png [--title T]
    python3 -m tnvplot capture A.csv [B.csv] OUT.svg [--label L ...] [--title T]
    python3 -m tnvplot bode    RESPONSE.json OUT.svg   (freq-response JSON)

or from Python: ``tnvplot.render(kind, inputs, output, title=..., labels=...)``.
"""

KINDS = ("circle", "panels", "path", "capture", "bode", "campaign")


def render(kind, inputs, output, title="", labels=None, options=None):
    """Draws `kind` from `inputs` into `output` (.svg, .png or .pdf); `options`: a figure's own settings."""
    # matplotlib is imported on first use, so `python3 -m tnvplot` can say
    # which Debian package is missing.
    from tnvplot.render import render as _render

    return _render(kind, inputs, output, title, labels, options)
