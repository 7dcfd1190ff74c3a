"""The TNV-40 node from Python, over the C++ host library (tnv_can_host).

    import tnv
    with tnv.Node.emulated() as node:          # tnvctl --emu
        node.params["x.sliding.gamma"] = 0.3   # staged and committed, read back
        node.move("x", 5.0, 10.0)              # waits until the move is done
        data = node.capture(lambda n: n.move("x", -5.0, 10.0))

tnv.Node(iface="can0") opens a SocketCAN interface, tnv.Node(iface="unix:PATH")
tnv-fw's Unix-socket CAN link. A refusal by the node raises tnv.Refused
(a tnv.Error) with the reason tnvctl prints; an unknown parameter name
raises KeyError and a value the table refuses ValueError, before anything
is sent. docs/python.md walks through it.
"""

from collections.abc import Mapping
import math

from . import _tnv

__all__ = ["Node", "Params", "Error", "Refused", "Timeout", "BusError", "MotionFailed", "protocol_version"]

Error = _tnv.Error
Refused = _tnv.Refused
Timeout = _tnv.Timeout
BusError = _tnv.BusError
MotionFailed = _tnv.MotionFailed
protocol_version = _tnv.protocol_version

# The machine's axes, from the firmware's list (hal/axis.hpp).
axes = tuple(_tnv.axes)
_AXES = {name: i for i, name in enumerate(axes)}


def _choice(names):
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]


def _axis(axis, allow_all=False):
    if allow_all and axis == "all":
        return 255
    if axis not in _AXES:
        names = list(axes) + (["all"] if allow_all else [])
        raise ValueError(f"axis must be {_choice(names)}, not {axis!r}")
    return _AXES[axis]


def _finite(name, value, positive=False, maximum=None):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, not {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite (got {v})")
    if positive and not v > 0.0:
        raise ValueError(f"{name} must be > 0 (got {v:g})")
    if maximum is not None and v > maximum:
        raise ValueError(f"{name} must be <= {maximum:g} (got {v:g})")
    return v


class Params(Mapping):
    """The node's parameters by name: params["x.sliding.gamma"] reads,
    params["x.sliding.gamma"] = 0.3 stages and commits one change (read back
    and checked), set({...}) several as one set; stage() / commit() /
    discard() build a set step by step. Values: float for float parameters,
    int for integers, bool for booleans, the name (str) for enumerations;
    enumerations and booleans also take their names."""

    def __init__(self, node):
        self._node = node
        self._names = _tnv.param_names()

    def _value(self, name, v):
        t = _tnv.param_info(name)["type"]
        if t == "f32":
            return v
        if t == "bool":
            return bool(v)
        if t == "enum":
            return _tnv.format_value(name, v)
        return int(v)

    def __getitem__(self, name):
        return self._value(name, self._node._conn().get(name))

    def __setitem__(self, name, value):
        self.set({name: value})

    def __iter__(self):
        return iter(self._names)

    def __len__(self):
        return len(self._names)

    def __contains__(self, name):
        try:
            _tnv.param_info(name)
        except KeyError:
            return False
        return True

    def set(self, values):
        """Stages every change, then commits them as one set (all or nothing).
        Returns {name: value read back}."""
        items = list(dict(values).items())
        conn = self._node._conn()
        if conn.staged_names():
            raise Error("a staged set is pending (params.staged): commit() or discard() it first")
        after = conn.set(items)
        return {n: self._value(n, v) for (n, _), v in zip(items, after)}

    def stage(self, name, value):
        """Stages one change (this host's set); returns the staged value."""
        return self._value(name, self._node._conn().stage(name, value))

    def commit(self):
        """Commits this host's staged set; returns {name: value read back}."""
        conn = self._node._conn()
        names = conn.staged_names()
        after = conn.commit()
        return {n: self._value(n, v) for n, v in zip(names, after)}

    def discard(self):
        """Drops this host's staged set."""
        self._node._conn().discard()

    @property
    def staged(self):
        """The names staged since the last commit or discard."""
        return self._node._conn().staged_names()

    @staticmethod
    def info(name):
        """The table's entry: id, name, type, unit, min, max, range, values,
        access, apply, safety, description (KeyError for an unknown name)."""
        return _tnv.param_info(name)

    def __repr__(self):
        return f"<tnv.Params: {len(self)} parameters>"


class Node:
    """One node over one bus. Node(iface="can0") or Node(iface="unix:PATH");
    Node.emulated() for the in-process emulated node. A context manager:
    leaving it gives back command ownership and closes the bus."""

    def __init__(self, iface=None, *, node=1, host_id=1, timeout_ms=250, trace="", _emu=None):
        if _emu is None and not iface:
            raise ValueError("give iface (a SocketCAN interface or unix:PATH), or use Node.emulated()")
        emu = _emu or {}
        self._c = _tnv.Connection(iface=iface or "", emu=_emu is not None, node=node, host_id=host_id,
                                  timeout_ms=timeout_ms, scenario=emu.get("scenario", "no-cut"),
                                  seed=emu.get("seed", 0), storage=emu.get("storage", ""), trace=trace)
        self.params = Params(self)
        self.notes = list(self._c.notes)
        self.last_capture = None

    @classmethod
    def emulated(cls, scenario="no-cut", *, seed=0, storage=None, node=1, host_id=1, timeout_ms=250, trace=""):
        """The emulated node tnvctl --emu runs: the firmware on the emulated
        board, simulated time. storage: its parameter file (default: tnvctl's)."""
        return cls(node=node, host_id=host_id, timeout_ms=timeout_ms, trace=trace,
                   _emu={"scenario": scenario, "seed": seed, "storage": str(storage or "")})

    def _conn(self):
        if self._c is None or self._c.closed:
            raise Error("the node is closed")
        return self._c

    @property
    def is_emulated(self):
        return self._conn().emulated

    def describe(self):
        return self._conn().describe()

    # --- commands: each waits for the node's acknowledgement; motions also
    # until they are done (wait=False: only the acknowledgement). A motion
    # that ends in a fault raises MotionFailed naming it.
    def move(self, axis, distance_mm, speed_mm_s, wait=True):
        a = _axis(axis)
        d = _finite("distance_mm", distance_mm)
        if d == 0.0:
            raise ValueError("distance_mm must not be 0")
        s = _finite("speed_mm_s (the MOVE frame carries 0.01 mm/s steps)", speed_mm_s, positive=True, maximum=655.35)
        return self._conn().move(a, d, s, wait)

    def circle(self, radius_mm=None, feed_mm_s=None, wait=True):
        r = None if radius_mm is None else _finite("radius_mm", radius_mm, positive=True)
        f = None if feed_mm_s is None else _finite("feed_mm_s", feed_mm_s, positive=True)
        return self._conn().circle(r, f, wait)

    def home(self, axis="all"):
        return self._conn().home(_axis(axis, allow_all=True))

    def stop(self, wait=True):
        return self._conn().stop(wait)

    def spindle_start(self, direction, rpm):
        """SPINDLE start as `tnvctl spindle start`: direction "forward" (M3) or
        "reverse" (M4), rpm in (0, 12000] (the node refuses more than
        spindle.max_rpm). Returns once the node acknowledged; the spindle then
        ramps on its own and feed moves wait until it is at speed. Its state
        and speeds are in telemetry()'s "spindle" (with tlm.spindle_ms > 0)."""
        if not isinstance(direction, str):
            raise ValueError(f"direction must be 'forward' or 'reverse', not {direction!r}")
        return self._conn().spindle_start(direction, _finite("rpm", rpm))

    def spindle_stop(self):
        """SPINDLE stop (M5): the spindle ramps down, the enable drops at standstill."""
        return self._conn().spindle_stop()

    def clear_fault(self):
        return self._conn().clear_faults()

    clear_faults = clear_fault

    def enable(self):
        return self._conn().command("enable")

    def disable(self):
        return self._conn().command("disable")

    def command(self, name, axis=0, arg=0, value=0.0):
        """Any COMMAND by its protocol name (docs/can-protocol.md), e.g. "zero"."""
        return self._conn().command(name, axis, arg, _finite("value", value))

    def status(self):
        """One heartbeat (state, fault, flags, ...), the capture state, the firmware and
        tool_in_spindle (the node's PROGRAM_TOOL; None when it does not know)."""
        return self._conn().status()

    # --- capture
    def capture(self, run=None, *, channels=None, trigger=None, decimation=None, tail_s=0.0, wait_s=60.0):
        """Arms the on-target capture (channels: "pos_x,pos_y,...", "default"
        or "all"; trigger: immediate | motion | fault; None keeps the node's),
        calls run(node) if given (a motion), records tail_s more seconds and
        stops, waits up to wait_s for the recording, uploads it. Returns
        {"t_s": array, "<column>": array, ...} of numpy arrays; last_capture
        then holds samples, decimation, period_s, bytes, upload_s, rerequests."""
        import numpy as np

        tail = _finite("tail_s", tail_s)
        wait = _finite("wait_s", wait_s)
        if tail < 0.0 or wait < 0.0:
            raise ValueError("tail_s and wait_s must be >= 0")
        conn = self._conn()
        conn.arm_capture(channels or "", trigger or "", int(decimation or 0))
        if run is not None:
            run(self)
        if tail > 0.0:
            conn.stop_capture_after(tail)
        d = conn.download_capture(wait)
        self.last_capture = {k: v for k, v in d.items() if k != "columns"}
        out = {"t_s": np.arange(d["samples"], dtype=float) * d["period_s"]}
        out.update(d["columns"])
        return out

    def capture_frame(self, run=None, **options):
        """capture() as a pandas DataFrame: a t_s column, then one per channel;
        attrs holds last_capture."""
        import pandas as pd

        frame = pd.DataFrame(self.capture(run, **options))
        frame.attrs.update(self.last_capture)
        return frame

    # --- telemetry
    def telemetry(self, period_s=0.1, count=None, duration_s=None, realtime=False):
        """Yields a dict every period_s (bus clock) with the latest heartbeat
        and telemetry, as `tnvctl monitor --json` prints them; count or
        duration_s bound it (else it runs until the loop breaks). On the
        emulated node time is simulated; realtime=True paces it to the wall clock."""
        p = _finite("period_s", period_s, positive=True, maximum=3600.0)
        conn = self._conn()
        conn.telemetry_start(bool(realtime))
        try:
            n = 0
            while count is None or n < count:
                sample = conn.telemetry_sample(p)
                yield sample
                n += 1
                if duration_s is not None and sample["t_s"] >= duration_s:
                    break
        finally:
            if not conn.closed:
                conn.telemetry_stop()

    # --- life
    def close(self):
        """Gives back command ownership (if taken) and closes the bus."""
        if self._c is not None and not self._c.closed:
            error = self._c.close()
            if error:
                raise Error(f"could not release command ownership: {error}")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __repr__(self):
        if self._c is None or self._c.closed:
            return "<tnv.Node: closed>"
        return f"<tnv.Node on {self._c.describe()}>"
