"""Small inputs of every figure kind, made the way the tools write them."""

import json

import numpy as np


def circle_row(label="rdvsc", n=19000, radius_mm=6.0, spike_at=5000):
    t = np.arange(n) * 1e-3
    a = 2 * np.pi * t / t[-1]
    error_mm = 1e-3 * (0.5 + 0.3 * np.sin(7 * a))
    error_mm[spike_at] = 0.004
    x, y = (radius_mm + error_mm) * np.cos(a), (radius_mm + error_mm) * np.sin(a)
    contour = np.abs(error_mm) * 1000.0
    return {"label": label, "stats": {"max_um": contour.max(), "mean_um": contour.mean(), "std_um": contour.std()},
            "t_s": t.tolist(), "x_mm": x.tolist(), "y_mm": y.tolist(), "ref_x_mm": (radius_mm * np.cos(a)).tolist(),
            "ref_y_mm": (radius_mm * np.sin(a)).tolist(), "contour_um": contour.tolist()}


def circle_data(rows=2):
    return {"kind": "circle", "title": "S1 circle, cut-1500 (seed 0)", "radius_mm": 6.0, "suppressed": 0.998,
            "rows": [circle_row(f"run {i}") for i in range(rows)]}


def panels_data():
    t = np.linspace(0, 10, 20000)
    return {"kind": "panels", "title": "S3 ARSC", "x_label": "time (s)", "vlines": {"x": [2.0], "label": "wrap"},
            "panels": [
                {"y_label": "force f (normalised)", "y_range": [0.0, 2.0], "band": [0.9, 1.1], "band_label": "f* +-10%",
                 "series": [{"label": "f", "x": t.tolist(), "y": (1 + 0.5 * np.sin(40 * t) + (t > 9.9) * 5).tolist()},
                            {"label": "f*", "x": [0, 10], "y": [1, 1], "style": "dashed"}]},
                {"y_label": "position error at rest (um)", "series": [
                    {"label": "X", "x": [0, 1, 2], "y": [0.1, -0.2, 0.3], "style": "dots"},
                    {"label": "ref", "x": [0, 1, 2], "y": [0, 0, 0], "style": "reference"},
                    {"label": "steps", "x": [0, 1, 2], "y": [1, 1, 2], "style": "steps"},
                    {"label": "bars", "x": [0, 1, 2], "y": [0.2, 0.4, 0.1], "style": "bars", "width": 0.3}]},
                {"y_label": "residual (%)", "log_y": True, "series": [{"label": "zv", "x": [1, 2, 3], "y": [0.01, 1, 100]}]}]}


def write_json(path, data):
    path.write_text(json.dumps(data))
    return path


def path_csv(path, n=3000):
    t = np.arange(n) * 1e-3
    x = np.where(t < 1.5, t * 10, 15.0)
    y = np.where(t < 1.5, 0.0, (t - 1.5) * 10)
    lines = ["t_s,x_ref_mm,y_ref_mm,x_mm,y_mm,contour_um,path_speed_mm_s,z_ref_mm,z_mm"]
    for k in range(n):
        lines.append(f"{t[k]:.3f},{x[k]:.6f},{y[k]:.6f},{x[k]:.6f},{y[k] + 1e-4:.6f},{0.1 + (k == 1500) * 3:.5f},10,-150,-150")
    path.write_text("\n".join(lines) + "\n")
    return path


def capture_csv(path, kind="circle", n=4000):
    t = np.arange(n) * 1e-3
    tick = np.arange(n) - 100
    if kind == "circle":
        a = 2 * np.pi * np.clip(tick, 0, None) / (n - 100)
        rx, ry = 6 * np.cos(a), 6 * np.sin(a)
        px, py = 6.0005 * np.cos(a), 6.0005 * np.sin(a)
    else:  # a straight move along x
        rx = np.clip(tick, 0, None) * 0.01
        ry = np.zeros(n)
        px, py = rx - 0.002, ry
    contour = np.abs(np.hypot(px, py) - 6) * 1000 if kind == "circle" else np.zeros(n)
    lines = ["t_s,pos_x_mm,pos_y_mm,ref_x_mm,ref_y_mm,contour_um,motion_tick"]
    for k in range(n):
        lines.append(f"{t[k]:.3f},{px[k]:.6f},{py[k]:.6f},{rx[k]:.6f},{ry[k]:.6f},{contour[k]:.9g},{tick[k]}")
    path.write_text("\n".join(lines) + "\n")
    return path


def bode_data(low_coherence_at=None):
    """A freq-response JSON of an integrator-plus-lag loop, margins included."""
    import cmath
    import math

    pts = []
    for i in range(30):
        f = 1.0 * (300.0 ** (i / 29))
        s = 2j * math.pi * f
        h = 300.0 / (s * (0.005 * s + 1.0)) * cmath.exp(-s * 1e-3)
        coherence = 0.5 if low_coherence_at is not None and i == low_coherence_at else 0.999
        pts.append({"freq_hz": f, "gain_db": 20 * math.log10(abs(h)), "phase_deg": math.degrees(cmath.phase(h)),
                    "coherence": coherence, "model_gain_db": 20 * math.log10(abs(h)) + 0.1,
                    "model_phase_deg": math.degrees(cmath.phase(h)) + 1.0})
    margins = {"gain_db": 8.0, "phase_deg": 45.0, "crossover_hz": 40.0, "phase_crossover_hz": 150.0,
               "bandwidth_hz": 70.0}
    return {"axis": "x", "loop": "open", "excitation": "multisine", "points": pts, "margins": margins,
            "model_margins": dict(margins, gain_db=None)}
