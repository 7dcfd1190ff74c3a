"""Plain HTTP to `tnvctl serve` as a script or an attacker sends it, with
every header chosen by the caller (http.client: no browser, no cookies)."""

import http.client
import json
import time


def request(server, method, path, body=None, host=None, origin=None, bearer=None, tab=None,
            content_type="application/json"):
    """(status, JSON answer or None). `host` replaces the Host header
    (default: the server's own); `bearer` is sent as Authorization: Bearer."""
    ip, port = server.host.rsplit(":", 1)
    conn = http.client.HTTPConnection(ip, int(port), timeout=30)
    try:
        conn.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
        conn.putheader("Host", host or server.host)
        if origin is not None:
            conn.putheader("Origin", origin)
        if bearer is not None:
            conn.putheader("Authorization", "Bearer " + bearer)
        if tab is not None:
            conn.putheader("X-Tnv-Token", tab)
        data = b"" if body is None else (body if isinstance(body, bytes) else json.dumps(body).encode())
        if data:
            conn.putheader("Content-Type", content_type)
        conn.putheader("Content-Length", str(len(data)))
        conn.endheaders(data)
        res = conn.getresponse()
        raw = res.read()
        try:
            answer = json.loads(raw)
        except ValueError:
            answer = None
        return res.status, answer
    finally:
        conn.close()


def owner(server, path, **kw):
    """An authorised GET of `path` (the operator's own view), its JSON."""
    status, answer = request(server, "GET", path, bearer=server.secret, **kw)
    assert status == 200, (path, status, answer)
    return answer


def param_value(server, name):
    for p in owner(server, "/api/params?filter=" + name)["params"]:
        if p["name"] == name:
            return p["value"]
    raise AssertionError(f"no parameter {name}")


def position_samples(server, stop, wall_timeout_s=20.0):
    """Reads the telemetry stream (as the operator) and yields (t_s, pos_x_mm)
    in machine time until stop(t_s) is true or the wall timeout (a stuck
    server must not hang the test)."""
    ip, port = server.host.rsplit(":", 1)
    conn = http.client.HTTPConnection(ip, int(port), timeout=10)
    conn.request("GET", "/api/telemetry", headers={"Authorization": "Bearer " + server.secret})
    res = conn.getresponse()
    assert res.status == 200, res.status
    deadline = time.monotonic() + wall_timeout_s
    try:
        while time.monotonic() < deadline:
            line = res.readline()
            if not line:
                return
            if not line.startswith(b"data: "):
                continue
            event = json.loads(line[6:])
            for t, v in zip(event["t"], event["v"]):
                if v[0] is not None:
                    yield t, v[0]
                    if stop(t):
                        return
    finally:
        conn.close()
