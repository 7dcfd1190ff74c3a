"""Campaign figure from a merged campaign (tnv-hil campaign report --plot),
read straight from DIR/campaign.sqlite: the distribution of the judged
result per controller (empirical CDF, the limit as a line, the yield in
the legend), and the result against the two inputs it depends on most
(largest |Spearman rho| over all controllers)."""

import json
import math
import sqlite3

import numpy as np

from tnvplot import style


def _ranks(v):
    order = np.argsort(v, kind="stable")
    r = np.empty(len(v))
    i = 0
    while i < len(v):
        j = i
        while j + 1 < len(v) and v[order[j + 1]] == v[order[i]]:
            j += 1
        r[order[i:j + 1]] = (i + j) / 2.0 + 1.0
        i = j + 1
    return r


def spearman(x, y):
    if len(x) < 2:
        return float("nan")
    rx, ry = _ranks(np.asarray(x, float)), _ranks(np.asarray(y, float))
    if rx.std() == 0 or ry.std() == 0:
        return float("nan")
    return float(np.corrcoef(rx, ry)[0, 1])


def read(path, metric="max_um"):
    """{controller: {"metric": [...], "ok": n, "runs": n, "inputs": {name: [...]}}}, inputs, limit."""
    con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    try:
        meta = dict(con.execute("SELECT key, value FROM campaign"))
        inputs = [v["name"] for v in json.loads(meta["vary"])]
        cols = ", ".join('"' + c.replace('"', '""') + '"' for c in [metric] + inputs)
        rows = con.execute(f"SELECT controller, status, {cols} FROM runs ORDER BY run_id").fetchall()
    finally:
        con.close()
    data = {}
    for controller, status, value, *xs in rows:
        d = data.setdefault(controller, {"metric": [], "runs": 0, "inputs": {n: [] for n in inputs}})
        d["runs"] += 1
        if status != "ok" or value is None:
            continue
        d["metric"].append(value)
        for n, x in zip(inputs, xs):
            d["inputs"][n].append(x if isinstance(x, (int, float)) else float("nan"))
    return data, inputs, float(meta.get("limit_um", 5.0))


def draw(path, title="", options=None):
    options = options or {}
    metric = options.get("metric", "max_um")
    data, inputs, limit = read(path, metric)
    if "limit" in options:
        limit = float(options["limit"])
    strength = {}
    for n in inputs:
        rhos = [abs(spearman(d["inputs"][n], d["metric"])) for d in data.values()]
        rhos = [r for r in rhos if not math.isnan(r)]
        if rhos:
            strength[n] = max(rhos)
    top = sorted(strength, key=lambda n: -strength[n])[:2]
    panels = 1 + len(top)
    fig = style.figure(style.DOUBLE_COLUMN_IN, 2.6)
    axes = [fig.add_subplot(1, panels, i + 1) for i in range(panels)]
    ax = axes[0]
    for i, (controller, d) in enumerate(data.items()):
        v = np.sort(np.asarray(d["metric"], float))
        within = int(np.sum(v <= limit))
        yield_pct = 100.0 * within / d["runs"] if d["runs"] else 0.0
        frac = np.arange(1, len(v) + 1) / d["runs"] if d["runs"] else v
        ax.step(v, frac, where="post", color=style.COLORS[i % len(style.COLORS)],
                label=f"{controller}: yield {yield_pct:.1f} % of {d['runs']}")
    ax.axvline(limit, color=style.REFERENCE_COLOR, linestyle="--", linewidth=0.8)
    ax.set_xlabel(style.units(f"{metric} [{style.UM}]") if metric.endswith("_um") else metric)
    ax.set_ylabel("fraction of runs")
    ax.set_ylim(0, 1.02)
    ax.legend(fontsize=6, loc="lower right")
    for ax, n in zip(axes[1:], top):
        for i, (controller, d) in enumerate(data.items()):
            ax.plot(d["inputs"][n], d["metric"], ".", markersize=2.5, color=style.COLORS[i % len(style.COLORS)],
                    label=f"{controller} (rho {spearman(d['inputs'][n], d['metric']):+.2f})")
        ax.axhline(limit, color=style.REFERENCE_COLOR, linestyle="--", linewidth=0.8)
        ax.set_xlabel(n)
        ax.set_ylabel(f"{metric} [{style.UM}]" if metric.endswith("_um") else metric)
        ax.legend(fontsize=6)
    if title:
        style.suptitle(fig, title)
    fig.tight_layout()
    return fig
