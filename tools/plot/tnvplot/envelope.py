"""Dense traces and out-of-range values.

envelope(): a trace of many samples becomes, per bucket of the x range,
the bucket's smallest and largest sample in their time order, so every
peak survives and the line does not turn into a solid band.

clip(): values beyond an axis range move to its edge (and are counted),
rather than being dropped.
"""

import numpy as np


def envelope(x, y, buckets):
    """(x, y) reduced to the min and max of each of `buckets` equal parts of
    the x range, in x order. Traces no longer than 2 * buckets come back whole."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if x.size <= 2 * buckets or x.size == 0:
        return x, y
    lo, hi = np.nanmin(x), np.nanmax(x)
    if not hi > lo:
        return x, y
    bucket = np.minimum(((x - lo) / (hi - lo) * buckets).astype(int), buckets - 1)
    order = np.lexsort((np.arange(x.size), bucket))
    b_sorted = bucket[order]
    starts = np.flatnonzero(np.r_[True, b_sorted[1:] != b_sorted[:-1]])
    keep = []
    for s, e in zip(starts, np.r_[starts[1:], b_sorted.size]):
        idx = order[s:e]
        vals = y[idx]
        finite = np.isfinite(vals)
        if not finite.any():
            keep.append(idx[0])
            continue
        i_min = idx[np.flatnonzero(finite)[np.argmin(vals[finite])]]
        i_max = idx[np.flatnonzero(finite)[np.argmax(vals[finite])]]
        keep.extend(sorted({i_min, i_max}))
    keep = np.asarray(keep)
    return x[keep], y[keep]


def envelope_by_index(key, arrays, buckets):
    """Arrays sampled together (the polar trace's angle and radius), reduced
    by sample index: per bucket of consecutive samples, the two where `key`
    is smallest and largest. Short traces come back whole."""
    key = np.asarray(key, dtype=float)
    if key.size <= 2 * buckets:
        return [np.asarray(a, dtype=float) for a in arrays]
    edges = np.linspace(0, key.size, buckets + 1).astype(int)
    keep = []
    for s, e in zip(edges[:-1], edges[1:]):
        if e > s:
            seg = key[s:e]
            keep.extend(sorted({s + int(np.nanargmin(seg)), s + int(np.nanargmax(seg))}))
    keep = np.asarray(keep, dtype=int)
    return [np.asarray(a, dtype=float)[keep] for a in arrays]


def clip(y, lo, hi):
    """y with values below lo set to lo and above hi set to hi, and how
    many were moved. Nothing is dropped: the result is as long as y."""
    y = np.asarray(y, dtype=float)
    below = y < lo
    above = y > hi
    return np.clip(y, lo, hi), int(below.sum() + above.sum())
