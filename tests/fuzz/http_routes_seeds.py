#!/usr/bin/env python3
"""Writes the http_routes fuzz target's seed corpus (tests/fuzz/corpus/http_routes):
each route with a well-formed request (own Host, the page's Origin, the
bearer secret, a JSON body), and the refusals around it (no credentials,
the session cookie, a foreign Host or Origin, no Origin, a text body).
The input format is http_routes_entry.hpp's. Usage: http_routes_seeds.py DIR"""

import os
import sys

BODIES = {
    11: b'{"name":"motion.move_ramp_s","value":0.3}', 12: b'{"name":"motion.move_dwell_s","value":"0.2"}',
    16: b'{"kind":"move","axis":"x","distance_mm":20,"speed_mm_s":10}', 17: b'{"channels":"pos_x","duration_s":0.5}',
    18: b'{"axis":"x","loop":"open"}',
    25: b'{"gcode":"G21 G91\\nG1 X1 F600\\nM0\\nG1 X-1\\nM2\\n"}',
    26: b'{"gcode":"G21 G91\\nG1 X1 F600\\nM1\\nT1 M6\\nG1 X-1\\nM2\\n"}', 27: b"{}",
    28: b'{"hold":true}',
}
TEXT = {19: b"0" * 64, 20: b"/api/motion?x=1", 21: b"/api/params?filter=x.", 22: b"PUT", 23: b"DELETE /api/control"}
WAYS = {"ok": 0x00, "cookie": 0x40, "none": 0xC0, "host": 0x03, "origin": 0x08}


def main(out):
    os.makedirs(out, exist_ok=True)
    n = 0
    for route in range(29):
        body = BODIES.get(route, b'{"kind":"enable"}' if route == 16 else b"")
        text = TEXT.get(route, b"")
        for way, b0 in WAYS.items():
            for b1 in (route, route | 0x40):  # JSON, text/plain
                data = bytes([b0, b1]) + text + b"\n" + body
                with open(os.path.join(out, f"r{route:02d}-{way}-{b1 >> 5}"), "wb") as f:
                    f.write(data)
                n += 1
    print(f"{n} seeds in {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "corpus", "http_routes"))
