#!/usr/bin/python3
"""The DBC against an independent parser (Debian's python3-canmatrix).

tnvctl --emu --trace records a session: a parameter set, enable, a little
telemetry. canmatrix loads docs/tnv.dbc and decodes the recorded frames;
the physical values must be what the session did: x.sliding.gamma = 0.25
(a float parameter multiplexed on its id), the heartbeat's bits as 1-bit
signals, the position telemetry in mm, and the cycle-time attribute.

Usage: dbc_decode_check.py TNVCTL DBC
"""
import os
import re
import subprocess
import sys
import tempfile

import canmatrix.formats

LINE = re.compile(r"^\((\d+\.\d+)\) (\S+) ([0-9A-F]{3}|[0-9A-F]{8})#([0-9A-F]*)$")


def fail(message):
    print("dbc_decode_check: " + message, file=sys.stderr)
    sys.exit(1)


def record_session(tnvctl, workdir):
    trace = os.path.join(workdir, "session.log")
    script = os.path.join(workdir, "session.tnvctl")
    with open(script, "w") as f:
        f.write("params set x.sliding.gamma=0.25 x.controller=dvsc\nenable\nmonitor --duration-s 0.3\n")
    env = dict(os.environ, XDG_STATE_HOME=workdir)
    run = subprocess.run([tnvctl, "--emu", "--trace", trace, "script", script], env=env,
                         capture_output=True, text=True, timeout=300)
    if run.returncode != 0:
        fail("tnvctl failed (%d): %s" % (run.returncode, run.stderr))
    frames = []
    with open(trace) as f:
        for number, line in enumerate(f, 1):
            m = LINE.match(line.rstrip("\n"))
            if not m:
                fail("%s:%d: not a candump -l line: %r" % (trace, number, line))
            frames.append((int(m.group(3), 16), bytes.fromhex(m.group(4))))
    return frames


def main():
    if len(sys.argv) != 3:
        fail(__doc__)
    tnvctl, dbc = sys.argv[1], sys.argv[2]
    db = canmatrix.formats.loadp_flat(dbc)
    with tempfile.TemporaryDirectory() as workdir:
        frames = record_session(tnvctl, workdir)
    if len(frames) < 20:
        fail("only %d frames recorded" % len(frames))

    gamma_replies, controller_replies, heartbeats, positions = [], [], [], []
    pending_x = None  # a tick's TLM_POSITION_X waiting for its _Y
    for can_id, data in frames:
        frame = db.frame_by_id(canmatrix.ArbitrationId(can_id))
        if frame is None:
            fail("identifier 0x%03X is not in the DBC" % can_id)
        decoded = frame.decode(data)
        values = {name: signal.phys_value for name, signal in decoded.items()}
        if frame.name == "PARAM_REPLY" and "x_sliding_gamma" in values:
            gamma_replies.append(float(values["x_sliding_gamma"]))
        if frame.name == "PARAM_REPLY" and "x_controller" in values:
            controller_replies.append(decoded["x_controller"].named_value)
        if frame.name == "HEARTBEAT":
            heartbeats.append(values)
        # One TLM_POSITION_<AXIS> per axis (protocol 5): a sample is x then y of a tick.
        if frame.name == "TLM_POSITION_X":
            pending_x = float(values["position"])
        if frame.name == "TLM_POSITION_Y" and pending_x is not None:
            positions.append((pending_x, float(values["position"])))
            pending_x = None

    if 0.25 not in gamma_replies:
        fail("no PARAM_REPLY decoded x_sliding_gamma as 0.25 (decoded: %s)" % gamma_replies[:8])
    if "dvsc" not in controller_replies:
        fail("no PARAM_REPLY decoded x_controller as dvsc (decoded: %s)" % controller_replies[:8])
    if not heartbeats:
        fail("no HEARTBEAT recorded")
    for bit in ("params_unsaved", "storage_fault", "commissioning", "homed_x", "shaper_y"):
        if bit not in heartbeats[-1]:
            fail("HEARTBEAT has no 1-bit signal %s" % bit)
    if int(heartbeats[-1]["params_unsaved"]) != 1:
        fail("params_unsaved should be set after an unsaved change: %s" % heartbeats[-1])
    if int(heartbeats[-1]["storage_fault"]) != 0:
        fail("storage_fault set on a fresh node: %s" % heartbeats[-1])
    if not positions or abs(positions[-1][0] - 6.0) > 0.01 or abs(positions[-1][1]) > 0.01:
        fail("TLM_POSITION_X and _Y should read x 6 mm, y 0 mm at rest: %s" % positions[-3:])
    cycle = db.frame_by_name("HEARTBEAT").attribute("GenMsgCycleTime", db)
    if int(cycle) != 100:
        fail("HEARTBEAT GenMsgCycleTime %s, expected 100 ms" % cycle)
    print("dbc_decode_check: %d frames decoded; x_sliding_gamma 0.25, x_controller dvsc, heartbeat bits, "
          "position (%.4f, %.4f) mm, heartbeat cycle %s ms" % (len(frames), positions[-1][0], positions[-1][1], cycle))


if __name__ == "__main__":
    main()
