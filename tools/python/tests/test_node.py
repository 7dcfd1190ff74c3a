"""The tnv module against the emulated node (and tnv-fw over unix:)."""

import math

import numpy as np
import pytest

import tnv

GAMMA = "x.sliding.gamma"


def test_params_read_set_stage_commit_round_trip(node):
    assert GAMMA in node.params
    assert "x.no.such" not in node.params
    assert len(node.params) == len(list(node.params.keys())) > 50
    before = node.params[GAMMA]
    assert isinstance(before, float)

    node.params[GAMMA] = 0.375
    assert node.params[GAMMA] == 0.375

    assert node.params.stage(GAMMA, 0.25) == 0.25
    assert node.params.staged == [GAMMA]
    assert node.params[GAMMA] == 0.375  # staged, not applied
    assert node.params.commit() == {GAMMA: 0.25}
    assert node.params[GAMMA] == 0.25

    node.params.stage(GAMMA, 0.5)
    with pytest.raises(tnv.Error, match="staged set is pending"):
        node.params[GAMMA] = 0.125
    node.params.discard()
    assert node.params.staged == []
    assert node.params[GAMMA] == 0.25

    # Enumerations by name, several changes as one set.
    assert node.params.set({"x.controller": "pid", GAMMA: 0.3}) == {"x.controller": "pid", GAMMA: pytest.approx(0.3)}
    assert node.params["x.controller"] == "pid"

    info = node.params.info(GAMMA)
    assert info["name"] == GAMMA and info["type"] == "f32" and info["access"] == "rw"
    assert info["min"] <= 0.3 <= info["max"] and info["description"]


def test_refusal_raises_refused_with_the_limit_and_changes_nothing(node):
    before = node.params["x.limits.following_floor_mm"]
    info = node.params.info("x.limits.following_floor_mm")
    assert info["safety"]
    with pytest.raises(tnv.Refused) as e:
        node.params["x.limits.following_floor_mm"] = info["min"] + (info["max"] - info["min"]) / 2
    assert isinstance(e.value, tnv.Error)
    assert "x.limits.following_floor_mm is a safety parameter: enter commissioning mode first" in str(e.value)
    assert e.value.code == "commissioning_required"
    assert node.params["x.limits.following_floor_mm"] == before
    assert node.params.staged == []


def test_whole_set_refusal_names_the_parameter_and_its_limit(node):
    # In the table's range, but over the sliding-mode bound gamma < min(1 - g, q): the node refuses the commit.
    before = node.params[GAMMA]
    bound = min(1.0 - node.params["x.sliding.g"], node.params["x.sliding.q"])
    assert bound + 0.01 <= node.params.info(GAMMA)["max"]
    with pytest.raises(tnv.Refused) as e:
        node.params[GAMMA] = bound + 0.01
    assert e.value.code == "invalid"
    assert "x.sliding.gamma: axis x: sliding-mode" in str(e.value)
    assert "gamma < min(1 - g, q)" in str(e.value)
    assert node.params[GAMMA] == before
    assert node.params.staged == []


def test_unknown_name_is_a_key_error(node):
    with pytest.raises(KeyError, match="x.sliding.gama.*did you mean x.sliding.gamma"):
        node.params["x.sliding.gama"]
    with pytest.raises(KeyError):
        node.params["x.sliding.gama"] = 0.3
    with pytest.raises(KeyError):
        node.params.info("nope")


def test_nan_and_out_of_range_are_value_errors_before_anything_is_sent(node):
    before = node.params[GAMMA]
    with pytest.raises(ValueError, match="NaN"):
        node.params[GAMMA] = math.nan
    with pytest.raises(ValueError, match=GAMMA):
        node.params[GAMMA] = 1e9
    with pytest.raises(ValueError):
        node.params.stage(GAMMA, float("inf"))
    with pytest.raises(ValueError):
        node.params["x.controller"] = "fastest"
    assert node.params.staged == []
    assert node.params[GAMMA] == before
    with pytest.raises(ValueError):
        node.move("x", math.nan, 10.0)
    with pytest.raises(ValueError):
        node.move("w", 1.0, 10.0)


def test_move_then_capture_to_numpy_and_a_data_frame(node):
    status = node.move("x", 0.5, 10.0)
    assert status["state"] not in ("moving", "dwell", "faulted")
    assert node.status()["fault"] == "none"
    assert node.status()["tool_in_spindle"] is None  # no tool change since the node started: unknown

    data = node.capture(lambda n: n.move("x", -0.5, 10.0), channels="pos_x,pos_y,contour", trigger="motion",
                        decimation=2)
    assert list(data) == ["t_s", "pos_x_mm", "pos_y_mm", "contour_um"]
    n = len(data["t_s"])
    assert n > 10
    assert all(isinstance(a, np.ndarray) and a.shape == (n,) for a in data.values())
    assert data["t_s"][1] - data["t_s"][0] == pytest.approx(0.002)
    assert data["pos_x_mm"].min() < data["pos_x_mm"][0] - 0.4  # it moved back by 0.5 mm
    # The node's sample count, and what was uploaded: samples x 3 channels x 4 bytes.
    assert node.last_capture["samples"] == n and node.last_capture["bytes"] == n * 3 * 4
    assert node.last_capture["decimation"] == 2

    frame = node.capture_frame(lambda n: n.move("x", 0.5, 10.0), channels="pos_x,speed_x", trigger="motion")
    assert list(frame.columns) == ["t_s", "pos_x_mm", "speed_x_mm_s"]
    assert len(frame) == frame.attrs["samples"] > 10 and frame.attrs["bytes"] == len(frame) * 2 * 4
    assert frame["speed_x_mm_s"].max() > 5.0


def test_capture_setup_is_checked_before_anything_is_sent(node):
    with pytest.raises(ValueError, match="pos_q"):
        node.capture(channels="pos_q")


def test_telemetry_yields_samples(node):
    samples = list(node.telemetry(period_s=0.05, count=20))
    assert len(samples) == 20
    assert samples[-1]["t_s"] == pytest.approx(1.0, abs=0.06)
    assert samples[-1]["frames"] > samples[0]["frames"] > 0
    assert "position_mm" in samples[-1] and len(samples[-1]["position_mm"]) == len(tnv.axes)
    assert samples[-1]["status"]["state"]
    # The node is usable again afterwards.
    assert node.params[GAMMA] > 0


def test_closed_node_refuses_calls(tmp_path):
    node = tnv.Node.emulated(storage=tmp_path / "p.bin")
    with node:
        assert node.is_emulated
    with pytest.raises(tnv.Error, match="closed"):
        node.params[GAMMA]
    with pytest.raises(ValueError):
        tnv.Node()


def test_unix_iface_against_tnv_fw(daemon):
    with tnv.Node(iface=daemon, timeout_ms=2000) as node:
        assert not node.is_emulated
        node.params[GAMMA] = 0.375
        assert node.params[GAMMA] == 0.375
        with pytest.raises(ValueError):
            node.params[GAMMA] = 1e9
        assert node.params[GAMMA] == 0.375
        assert node.status()["protocol_version"] == tnv.protocol_version
        # A node just started does not know the tool in its spindle: None, not 0 (no tool).
        assert node.status()["tool_in_spindle"] is None


def test_waiting_on_the_bus_releases_the_gil(node):
    # Paced to the wall clock, 0.3 s of telemetry waits about 0.3 s: another
    # thread runs meanwhile. Its count is compared with its own count over a
    # plain 0.3 s sleep on the same machine at the same moment, not with a
    # constant: holding the GIL, the wait would leave it a few ticks between
    # samples at most.
    import threading
    import time

    done = threading.Event()
    ticks = 0

    def count():
        nonlocal ticks
        while not done.is_set():
            ticks += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    try:
        start = ticks
        time.sleep(0.3)
        free = ticks - start
        start = ticks
        samples = list(node.telemetry(period_s=0.1, count=3, realtime=True))
        during = ticks - start
    finally:
        done.set()
        t.join()
    assert len(samples) == 3
    assert free > 0, "the counting thread never ran"
    assert during >= free / 4, f"{during} ticks while waiting on the bus, {free} in a plain sleep of as long"


def test_spindle_starts_reaches_speed_in_telemetry_and_stops(node):
    before = list(node.telemetry(period_s=0.05, count=2))
    assert "spindle" not in before[-1], "tlm.spindle_ms is 0 by default: no TLM_SPINDLE"
    node.params["tlm.spindle_ms"] = 10
    assert node.spindle_start("reverse", 1500)["state"]
    # 1500 rpm at spindle.accel_rpm_s (5000 rpm/s) is a 0.3 s ramp: at speed well within 1.5 s.
    turning = list(node.telemetry(period_s=0.1, count=15))[-1]["spindle"]
    assert turning["state"] == "at_speed", turning
    assert turning["direction"] == "reverse"
    assert turning["commanded_on"] is True
    assert turning["measured_rpm"] == pytest.approx(-1500.0, abs=75.0)
    node.spindle_stop()
    stopped = list(node.telemetry(period_s=0.1, count=20))[-1]["spindle"]
    assert stopped["state"] == "off", stopped
    assert stopped["stop_cause"] == "command"
    assert abs(stopped["measured_rpm"]) < 20.0


def test_spindle_start_is_checked_before_anything_is_sent(node):
    node.params["tlm.spindle_ms"] = 10
    with pytest.raises(ValueError, match="forward or reverse"):
        node.spindle_start("sideways", 1000)
    with pytest.raises(ValueError, match="12000"):
        node.spindle_start("forward", 20000)
    with pytest.raises(ValueError, match="finite"):
        node.spindle_start("forward", float("nan"))
    with pytest.raises(ValueError, match="> 0"):
        node.spindle_start("forward", 0)
    spindle = list(node.telemetry(period_s=0.1, count=3))[-1]["spindle"]
    assert spindle["commanded_on"] is False and spindle["state"] == "off", spindle


def test_the_axes_are_the_firmwares_list():
    assert tnv.axes == ("x", "y", "z")
    with pytest.raises(ValueError, match="axis must be x, y, z or all"):
        tnv._axis("w", allow_all=True)
