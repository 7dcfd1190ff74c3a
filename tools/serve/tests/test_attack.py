"""The attack of issue 30 repeated against `tnvctl --emu serve`: what a
web page the operator merely visits sends after DNS rebinding, or what any
other local user can send — take control, servo on, move 20 mm, set a
parameter — with a foreign Host, a foreign Origin, a guessed X-Tnv-Token,
a guessed bearer token and no token at all. Every step is refused, and
nothing changed on the node. No browser needed."""

import json
import os
import signal
import subprocess
import time

import pytest
from page_http import owner, param_value, request

TAB = "0123456789abcdef0123456789abcdef"  # a well-formed tab token, as a page would make
PARAM = "x.sliding.gamma"
STEPS = [
    ("take control", "/api/control/take", None),
    ("servo on", "/api/motion", {"kind": "enable"}),
    ("move 20 mm", "/api/motion", {"kind": "move", "axis": "x", "distance_mm": 20, "speed_mm_s": 10}),
    ("set a parameter", "/api/params/set", {"name": PARAM, "value": 0.3}),
]


def attacks(server):
    """(name, request headers, the refusal expected) for each way in."""
    port = server.host.rsplit(":", 1)[1]
    foreign = f"attacker.example:{port}"
    return [
        ("rebound host and origin, no secret", dict(host=foreign, origin=f"http://{foreign}", tab=TAB), 403),
        ("rebound host and origin, with the secret", dict(host=foreign, origin=f"http://{foreign}", tab=TAB,
                                                          bearer=server.secret), 403),
        ("foreign origin, no secret", dict(origin=f"http://{foreign}", tab=TAB), 401),
        ("foreign origin, with the secret", dict(origin=f"http://{foreign}", tab=TAB, bearer=server.secret), 403),
        ("no origin, with the secret", dict(tab=TAB, bearer=server.secret), 403),
        ("guessed X-Tnv-Token only", dict(origin=server.base, tab=TAB), 401),
        ("guessed bearer token", dict(origin=server.base, tab=TAB, bearer="0" * 64), 401),
        ("no token at all", dict(origin=server.base), 401),
    ]


def node_state(server):
    status = owner(server, "/api/status")
    control = owner(server, "/api/control")
    hb = status["heartbeat"]
    return {"state": hb and hb["state"], "owner": hb and hb["owner"], "taken": control["taken"],
            PARAM: param_value(server, PARAM)}


def test_every_step_of_the_attack_is_refused_and_nothing_changes(server):
    deadline = time.monotonic() + 10
    while owner(server, "/api/status")["heartbeat"] is None:  # the node's first heartbeat
        assert time.monotonic() < deadline, "no heartbeat from the node"
        time.sleep(0.05)
    before = node_state(server)
    refused = 0
    for name, headers, expected in attacks(server):
        for step, path, body in STEPS:
            status, answer = request(server, "POST", path, body, **headers)
            assert status == expected, f"{name}: {step} answered {status} {answer}"
            assert answer and answer.get("error"), f"{name}: {step}: no reason given"
            refused += 1
    time.sleep(0.3)  # a move, had one started, would show by now
    assert node_state(server) == before, "a refused request changed the node"
    print(f"attack: {refused} of {refused} requests refused, node unchanged: {before}")
    # Each refusal is in the audit trail.
    lines = [json.loads(l) for l in server.audit.read_text().splitlines()]
    refusals = [l for l in lines if l.get("status") in (401, 403)]
    assert len(refusals) >= refused, f"{len(refusals)} refusals in the audit trail, {refused} sent"


def test_the_operator_with_the_secret_and_the_pages_origin_is_let_in(server):
    """The control case: the same request with the secret and the page's own origin is served."""
    status, answer = request(server, "POST", "/api/control/take", origin=server.base, tab=TAB, bearer=server.secret)
    assert status == 200 and answer["you"], (status, answer)
    status, answer = request(server, "POST", "/api/control/release", origin=server.base, tab=TAB, bearer=server.secret)
    assert status == 200 and not answer["you"], (status, answer)


@pytest.mark.parametrize("body,content_type,expected", [
    (b'{"kind":"enable"}', "text/plain", 415),
    (b"kind=enable", "application/x-www-form-urlencoded", 415),
    (b'{"kind":"enable","pad":"' + b"x" * 70000 + b'"}', "application/json", 413),
])
def test_a_body_that_is_not_small_json_is_refused(server, body, content_type, expected):
    status, answer = request(server, "POST", "/api/motion", body, origin=server.base, tab=TAB, bearer=server.secret,
                             content_type=content_type)
    assert status == expected, (status, answer)


def _serve(*args, timeout=30):
    exe = os.environ["TNVCTL_EXE"]
    return subprocess.run([exe, "--emu", "serve", "--port", "0", *args], capture_output=True, text=True,
                          timeout=timeout)


def test_a_bind_off_the_loopback_needs_tls():
    for bind in ("0.0.0.0", "::", "192.0.2.1"):
        r = _serve("--bind", bind)
        assert r.returncode == 2, (bind, r.returncode, r.stdout, r.stderr)
        assert "--tls-cert" in r.stderr and "http://" not in r.stdout, (bind, r.stderr)
    r = _serve("--tls-cert", "/nonexistent.pem")
    assert r.returncode == 2 and "both --tls-cert and --tls-key" in r.stderr, r.stderr


def test_a_token_file_others_may_read_is_refused(tmp_path):
    secret = "0123456789abcdef" * 4
    path = tmp_path / "token"
    path.write_text(secret + "\n")
    os.chmod(path, 0o644)
    r = _serve("--token-file", str(path))
    assert r.returncode == 2 and "chmod 600" in r.stderr, (r.returncode, r.stderr)
    os.chmod(path, 0o600)
    short = tmp_path / "short"
    short.write_text("abc\n")
    os.chmod(short, 0o600)
    r = _serve("--token-file", str(short))
    assert r.returncode == 2 and "at least 32" in r.stderr, (r.returncode, r.stderr)
    # Owner-only: served, with that secret in the URL.
    proc = subprocess.Popen([os.environ["TNVCTL_EXE"], "--emu", "serve", "--port", "0", "--token-file", str(path)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = proc.stdout.readline()
        assert f"/?token={secret} " in line, line
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(timeout=10)
