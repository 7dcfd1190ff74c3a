"""The plotting package: decimation, clipping, units and every figure kind."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import fixtures
from tnvplot import bode, capture, circle, panels, render, style
from tnvplot.envelope import clip, envelope, envelope_by_index

PACKAGE_DIR = Path(__file__).resolve().parents[1]


def test_envelope_keeps_min_and_max_of_every_bucket():
    rng = np.random.default_rng(1)
    x = np.arange(19000) * 1e-3
    y = rng.normal(size=x.size)
    y[12345] = 40.0  # a single-sample spike
    y[777] = -40.0
    buckets = 300
    xd, yd = envelope(x, y, buckets)
    assert xd.size <= 2 * buckets
    assert 40.0 in yd and -40.0 in yd
    edges = np.minimum(((x - x.min()) / np.ptp(x) * buckets).astype(int), buckets - 1)
    kept = np.minimum(((xd - x.min()) / np.ptp(x) * buckets).astype(int), buckets - 1)
    for b in range(buckets):
        assert y[edges == b].min() in yd[kept == b]
        assert y[edges == b].max() in yd[kept == b]
    assert np.all(np.diff(xd) >= 0)  # still in time order


def test_envelope_leaves_short_traces_alone():
    x, y = np.arange(10.0), np.arange(10.0) ** 2
    xd, yd = envelope(x, y, 100)
    assert np.array_equal(xd, x) and np.array_equal(yd, y)


def test_envelope_by_index_keeps_the_extremes_of_a_polar_trace():
    r = np.ones(10000)
    r[4321] = 9.0
    theta = np.linspace(0, 2 * np.pi, r.size)
    t2, r2 = envelope_by_index(r, [theta, r], 100)
    assert r2.max() == 9.0 and t2[np.argmax(r2)] == theta[4321]


def test_clipping_keeps_out_of_range_points_on_the_edge():
    y = np.array([0.5, 3.0, -2.0, 1.0])
    clipped, count = clip(y, 0.0, 2.0)
    assert clipped.tolist() == [0.5, 2.0, 0.0, 1.0]
    assert count == 2 and clipped.size == y.size


def test_panel_draws_clipped_samples_and_says_so():
    fig = panels.draw(fixtures.panels_data())
    force = fig.axes[0]
    texts = " ".join(t.get_text() for t in force.texts)
    assert "beyond the axis drawn on its edge" in texts
    edge = [line for line in force.get_lines() if line.get_marker() == "|"]
    assert edge and np.all(np.asarray(edge[0].get_ydata()) == 2.0)


def test_units_spell_micrometres():
    assert style.units("contour error (um)") == "contour error (\u00b5m)"
    assert style.units("max 3 um") == "max 3 \u00b5m"
    assert style.units("drum") == "drum"


def test_circle_axes_say_micrometres_and_state_the_suppression():
    fig = circle.draw(fixtures.circle_data())
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert "contour error (\u00b5m)" in labels
    assert "um" not in " ".join(labels).replace("\u00b5m", "")
    polar_note = fig.axes[0].get_xlabel()  # under the polar panel
    assert "99.8 % of R = 6 mm" in polar_note and "500\u00d7" in polar_note and "\u00b5m" in polar_note


def test_circle_time_trace_is_decimated_but_keeps_the_spike():
    fig = circle.draw(fixtures.circle_data(rows=1))
    ax = fig.axes[1]
    assert len(ax.get_lines()[0].get_ydata()) <= style.ENVELOPE_BUCKETS  # the mean per column
    shaded = ax.collections[0].get_paths()[0].vertices[:, 1]  # min to max per column
    assert shaded.max() == pytest.approx(4.0)


@pytest.mark.parametrize("suffix", [".svg", ".png", ".pdf"])
def test_every_kind_renders(tmp_path, suffix):
    made = {
        "circle": [fixtures.write_json(tmp_path / "c.json", fixtures.circle_data())],
        "panels": [fixtures.write_json(tmp_path / "p.json", fixtures.panels_data())],
        "path": [fixtures.path_csv(tmp_path / "path.csv")],
        "capture": [fixtures.capture_csv(tmp_path / "cap.csv", "circle")],
        "bode": [fixtures.write_json(tmp_path / "b.json", fixtures.bode_data())],
    }
    for kind, inputs in made.items():
        out = tmp_path / f"{kind}{suffix}"
        render(kind, [str(p) for p in inputs], str(out), title="a figure")
        head = out.read_bytes()[:200]
        assert out.stat().st_size > 1000
        if suffix == ".svg":
            assert head.startswith(b"<?xml") and b"<svg" in out.read_bytes()[:2000]
        elif suffix == ".png":
            assert head.startswith(b"\x89PNG")
        else:
            assert head.startswith(b"%PDF")


def test_straight_move_capture_has_no_circle_panel(tmp_path):
    table = capture.read_csv(fixtures.capture_csv(tmp_path / "line.csv", "line"))
    assert not capture.is_circle(table)
    fig = capture.draw([table], ["move"], "a straight move")
    assert all(ax.name != "polar" for ax in fig.axes)
    assert any("following error x" in ax.get_ylabel() for ax in fig.axes)


def test_circle_capture_draws_the_polar_plot(tmp_path):
    table = capture.read_csv(fixtures.capture_csv(tmp_path / "c.csv", "circle"))
    assert capture.is_circle(table)
    fig = capture.draw([table, table], ["before", "after"], "two circles")
    assert sum(ax.name == "polar" for ax in fig.axes) == 2


def test_comparing_a_straight_move_is_refused(tmp_path):
    line = capture.read_csv(fixtures.capture_csv(tmp_path / "l.csv", "line"))
    with pytest.raises(ValueError):
        capture.draw([line, line], ["a", "b"])


def test_command_line_names_a_bad_suffix(tmp_path):
    data = fixtures.write_json(tmp_path / "p.json", fixtures.panels_data())
    r = subprocess.run([sys.executable, "-m", "tnvplot", "panels", str(data), str(tmp_path / "x.gif")],
                       cwd=PACKAGE_DIR, capture_output=True, text=True)
    assert r.returncode == 1 and "x.gif" in r.stderr and ".svg" in r.stderr


def test_bode_draws_gain_and_phase_on_log_frequency_with_the_model():
    fig = bode.draw(fixtures.bode_data())
    gain, phase = fig.axes[0], fig.axes[1]
    assert gain.get_xscale() == "log" and phase.get_xscale() == "log"
    assert "dB" in gain.get_ylabel() and "deg" in phase.get_ylabel()
    assert [line.get_label() for line in gain.get_lines()][0] == "model"
    # The phase is unwrapped: no 360-degree jump between neighbouring points.
    offsets = phase.collections[0].get_offsets()
    assert np.max(np.abs(np.diff(offsets[:, 1]))) < 180.0
    # Margins measured and modelled in the title; a missing one shows as '-'.
    title = fig._suptitle.get_text()
    assert "PM 45.0 deg" in title and "crossover 40.0 Hz" in title and "GM -" in title


def test_bode_marks_low_coherence_points_apart():
    fig = bode.draw(fixtures.bode_data(low_coherence_at=5))
    labels = [c.get_label() for c in fig.axes[0].collections]
    assert any("coherence <" in label for label in labels)
    assert len(fig.axes[0].collections[0].get_offsets()) == 29  # the 30th is drawn open
    colors = bode.coherence_colors([1.0, 0.0])
    assert not np.allclose(colors[0], colors[1])


def test_bode_without_points_is_refused():
    with pytest.raises(ValueError):
        bode.draw({"points": []})


def _campaign_db(path, rows):
    """A merged campaign's tables (tools/campaign/merge.cpp), as few columns as the figure reads."""
    import json
    import sqlite3

    con = sqlite3.connect(path)
    con.execute('CREATE TABLE runs (run_id INTEGER PRIMARY KEY, controller TEXT, status TEXT, '
                '"plant.x.gain", "plant.x.backlash_um", max_um REAL)')
    con.execute("CREATE TABLE campaign (key TEXT PRIMARY KEY, value)")
    con.execute("INSERT INTO campaign VALUES ('limit_um', 5.0)")
    con.execute("INSERT INTO campaign VALUES ('vary', ?)",
                (json.dumps([{"name": "plant.x.gain"}, {"name": "plant.x.backlash_um"}]),))
    con.executemany("INSERT INTO runs VALUES (?, ?, ?, ?, ?, ?)", rows)
    con.commit()
    con.close()


def test_campaign_reads_the_merged_table_and_counts_unfinished_runs_out(tmp_path):
    from tnvplot import campaign

    rows = []
    for i in range(20):
        backlash = 0.5 * i
        rows.append((2 * i + 1, "pid", "ok", 1.0 + 0.01 * (i % 3), backlash, 2.0 + backlash))
        rows.append((2 * i + 2, "rdvsc", "fault" if i == 0 else "ok", 1.0, backlash, None if i == 0 else 1.0 + backlash))
    db = tmp_path / "campaign.sqlite"
    _campaign_db(db, rows)
    data, inputs, limit = campaign.read(db)
    assert inputs == ["plant.x.gain", "plant.x.backlash_um"]
    assert limit == 5.0
    assert data["pid"]["runs"] == 20 and len(data["pid"]["metric"]) == 20
    assert data["rdvsc"]["runs"] == 20 and len(data["rdvsc"]["metric"]) == 19  # the faulted run has no result
    assert campaign.spearman(data["pid"]["inputs"]["plant.x.backlash_um"], data["pid"]["metric"]) == pytest.approx(1.0)
    assert campaign.spearman([1, 1, 2, 3], [1, 2, 3, 4]) == pytest.approx(0.9486832980505138)
    out = tmp_path / "c.svg"
    render("campaign", [str(db)], str(out), options={"limit": "4"})
    assert "<svg" in out.read_text()
