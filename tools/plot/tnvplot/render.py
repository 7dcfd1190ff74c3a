"""One entry for every figure kind: read the inputs, draw, save by suffix."""

import json

from tnvplot import KINDS, style


def load_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def draw(kind, inputs, title="", labels=None, options=None):
    if kind == "circle":
        from tnvplot import circle
        return circle.draw(load_json(inputs[0]))
    if kind == "panels":
        from tnvplot import panels
        return panels.draw(load_json(inputs[0]))
    if kind == "path":
        from tnvplot import path
        return path.draw(path.read_csv(inputs[0]), title)
    if kind == "capture":
        from tnvplot import capture
        from pathlib import Path
        labels = list(labels or [])
        labels += [Path(p).stem for p in inputs[len(labels):]]
        return capture.draw([capture.read_csv(p) for p in inputs], labels, title)
    if kind == "bode":
        from tnvplot import bode
        return bode.draw(load_json(inputs[0]))
    if kind == "campaign":
        from tnvplot import campaign
        return campaign.draw(inputs[0], title, options)
    raise ValueError(f"unknown figure kind '{kind}' (one of {', '.join(KINDS)})")


def render(kind, inputs, output, title="", labels=None, options=None):
    """Draws `kind` from `inputs` (file paths) into `output` (.svg, .png or .pdf)."""
    style.output_format(output)
    fig = draw(kind, list(inputs), title, labels, options)
    style.save(fig, output)
    return output
