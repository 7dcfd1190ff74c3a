"""Bode figure of a frequency-response JSON (tnvctl / tnv-hil freq-response
--plot): gain (dB) and phase (deg) against log frequency, the measured
points with their coherence as colour (low coherence fades toward grey,
below 0.9 an open marker), the model's curve through the same points, and
the margins measured vs the model in the title block."""

import math

import numpy as np

from tnvplot import style

LOW_COHERENCE = 0.9


def _unwrap_deg(values):
    return np.degrees(np.unwrap(np.radians(np.asarray(values, dtype=float))))


def _margin_text(label, m):
    if not m:
        return f"{label}: -"

    def fmt(key, unit, digits=2):
        v = m.get(key)
        return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.{digits}f} {unit}"

    return (f"{label}: GM {fmt('gain_db', 'dB')}, PM {fmt('phase_deg', 'deg', 1)}, "
            f"crossover {fmt('crossover_hz', 'Hz', 1)}")


def coherence_colors(coherence):
    """RGBA per point: the measured colour at coherence 1, grey toward 0."""
    import matplotlib.colors as mcolors

    measured = np.array(mcolors.to_rgba(style.COLORS[1]))
    grey = np.array(mcolors.to_rgba(style.REFERENCE_COLOR))
    c = np.clip(np.asarray(coherence, dtype=float), 0.0, 1.0)[:, None]
    return c * measured + (1.0 - c) * grey


def draw(data):
    points = data.get("points") or []
    if not points:
        raise ValueError("a frequency response without points")
    f = np.array([p["freq_hz"] for p in points], dtype=float)
    gain = np.array([p["gain_db"] for p in points], dtype=float)
    phase = _unwrap_deg([p["phase_deg"] for p in points])
    coherence = np.array([p["coherence"] for p in points], dtype=float)
    fig = style.figure(style.DOUBLE_COLUMN_IN, 4.6)
    ax_gain, ax_phase = fig.subplots(2, 1, sharex=True)
    colors = coherence_colors(coherence)
    low = coherence < LOW_COHERENCE
    has_model = all("model_gain_db" in p and "model_phase_deg" in p for p in points)
    if has_model:
        model_gain = np.array([p["model_gain_db"] for p in points], dtype=float)
        model_phase = _unwrap_deg([p["model_phase_deg"] for p in points])
        # The model's phase on the measured branch (the same multiple of 360 at the first point).
        model_phase += 360.0 * np.round((phase[0] - model_phase[0]) / 360.0)
        ax_gain.semilogx(f, model_gain, color=style.REFERENCE_COLOR, label="model")
        ax_phase.semilogx(f, model_phase, color=style.REFERENCE_COLOR, label="model")
    for ax, y in ((ax_gain, gain), (ax_phase, phase)):
        ax.scatter(f[~low], y[~low], s=10, c=colors[~low], label="measured", zorder=3)
        if low.any():
            ax.scatter(f[low], y[low], s=14, facecolors="none", edgecolors=colors[low],
                       label=f"coherence < {LOW_COHERENCE}", zorder=3)
        ax.set_xscale("log")
    ax_gain.set_ylabel("gain (dB)")
    ax_phase.set_ylabel("phase (deg)")
    ax_phase.set_xlabel("frequency (Hz)")
    measured = data.get("margins") or {}
    if data.get("loop") in ("open", "closed") or measured.get("crossover_hz") is not None:
        xc = measured.get("crossover_hz")
        if xc is not None and f.min() <= xc <= f.max():
            for ax in (ax_gain, ax_phase):
                ax.axvline(xc, color=style.COLORS[0], linewidth=0.6, linestyle="--")
    style.legend_above(ax_gain)
    lines = [_margin_text("measured", measured), _margin_text("model", data.get("model_margins"))]
    title = f"axis {data.get('axis', '?')}, {data.get('loop', '?')} loop ({data.get('excitation', '?')})"
    fig.suptitle("\n".join([title] + lines))
    return fig
