#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""A magnetometer consumer feeding the daemon (its field mode).

magn_feed.py SOCKET N SEED HX HY HZ [STEP]: N samples of a board with
hard iron (HX, HY, HZ) uT and the soft iron below, turned through random
orientations (with STEP: turned STEP degrees a sample about an axis that
wanders, as a slow hand turns it) in a 48 uT field dipping 60 deg, 0.4 uT
noise, sent as the
driver's output with its calibration at the defaults (calibbias 0,
calibscale 1: no driver here), one "magn-feed" request each. Prints the
replies' last fit line; exits 1 when a request is refused, or when the
daemon stalls (no reply for STALL_S: a stall, not a time budget).
"""
import math
import random
import socket
import sys

S = [[1.05, 0.03, -0.02], [0.03, 0.95, 0.04], [-0.02, 0.04, 1.02]]
# No byte from the daemon for this long: it stalled (a busy machine only
# slows a reply down)
STALL_S = 120


def rot(q, v):
    w, x, y, z = q
    # v' = q v q*
    ix = w * v[0] + y * v[2] - z * v[1]
    iy = w * v[1] + z * v[0] - x * v[2]
    iz = w * v[2] + x * v[1] - y * v[0]
    iw = -x * v[0] - y * v[1] - z * v[2]
    return [ix * w + iw * -x + iy * -z - iz * -y,
            iy * w + iw * -y + iz * -x - ix * -z,
            iz * w + iw * -z + ix * -y - iy * -x]


def unit(v):
    norm = math.sqrt(sum(c * c for c in v))
    return [c / norm for c in v]


def qmul(a, b):
    return [a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]]


def main():
    path, n, seed = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    h = [float(v) for v in sys.argv[4:7]]
    step = math.radians(float(sys.argv[7])) if len(sys.argv) > 7 else 0
    rng = random.Random(seed)
    dip = math.radians(60)
    earth = [0, 48 * math.cos(dip), -48 * math.sin(dip)]   # world ENU
    last = ""
    if step:
        q = unit([rng.gauss(0, 1) for _ in range(4)])
        axis = unit([rng.gauss(0, 1) for _ in range(3)])
    for _ in range(n):
        if step:
            axis = unit([a + rng.gauss(0, 0.2) for a in axis])
            c, s_ = math.cos(step / 2), math.sin(step / 2)
            q = unit(qmul([c, s_ * axis[0], s_ * axis[1], s_ * axis[2]], q))
        else:
            q = unit([rng.gauss(0, 1) for _ in range(4)])
        # world to sensor: the inverse rotation
        qi = [q[0], -q[1], -q[2], -q[3]]
        b = rot(qi, earth)
        g = rot(qi, [0, 0, 256])
        m = [sum(S[i][j] * b[j] for j in range(3)) + h[i] + rng.gauss(0, 0.4)
             for i in range(3)]
        line = "magn-feed %.3f %.3f %.3f %.0f %.0f %.0f\n" % (*m, *g)
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.settimeout(STALL_S)
        reply = b""
        try:
            s.connect(path)
            s.sendall(line.encode())
            while True:
                chunk = s.recv(4096)
                if not chunk:
                    break
                reply += chunk
        except socket.timeout:
            print("stalled: nothing from %s for %d s" % (path, STALL_S),
                  file=sys.stderr)
            sys.exit(1)
        finally:
            s.close()
        text = reply.decode()
        if not text.rstrip().endswith("exit status 0"):
            print("refused: " + text, file=sys.stderr)
            sys.exit(1)
        for row in text.splitlines():
            if row.startswith("fit:"):
                last = row
    print(last)


main()
