#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""Hostile clients of as9888-calibd's socket, for daemon_hostile.sh.

hostile_clients.py SOCKET hangup N REQUEST  send REQUEST and hang up at once, N times
hostile_clients.py SOCKET silent N SECONDS   N connections that send nothing, held
                                            SECONDS at most (prints "ready" once
                                            connected, then "dropped K": how many
                                            the daemon let go at their deadline)
hostile_clients.py SOCKET trickle PERIOD LIMIT  one byte every PERIOD s, no newline;
                                            prints how long the daemon took to hang
                                            up, or "held" after LIMIT s
hostile_clients.py SOCKET raw LINE          send LINE as it is, print the reply
hostile_clients.py FILE lock SECONDS        hold flock(FILE) SECONDS (prints "held")
"""
import fcntl
import socket
import sys
import time


def connect(path):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.connect(path)
    return s


def hangup(path, n, request):
    for _ in range(int(n)):
        s = connect(path)
        s.sendall(request.encode() + b"\n")
        # RST-free hang-up before the answer: the daemon's writes get EPIPE
        s.close()


def silent(path, n, seconds):
    """Hold the connections; print how many the daemon let go for want of
    a request line ("dropped K") once each was answered or SECONDS passed"""
    held = [connect(path) for _ in range(int(n))]
    print("ready", flush=True)
    deadline = time.monotonic() + float(seconds)
    dropped = 0
    for s in held:
        reply = b""
        try:
            while True:
                s.settimeout(max(0.01, deadline - time.monotonic()))
                b = s.recv(4096)
                if not b:
                    break
                reply += b
        except (socket.timeout, OSError):
            pass
        dropped += b"no request line in time" in reply
        s.close()
    print("dropped %d" % dropped, flush=True)


def trickle(path, period, limit):
    s = connect(path)
    start = time.monotonic()
    s.settimeout(float(period))
    while time.monotonic() - start < float(limit):
        try:
            s.send(b"s")
        except OSError:
            break       # the daemon hung up
        try:
            if s.recv(4096) == b"":
                break
            # an answer ("error: ..."): it gave up on us; wait for the close
            s.settimeout(float(limit))
            while s.recv(4096):
                pass
            break
        except socket.timeout:
            continue
        except OSError:
            break
    else:
        print("held")
        return
    print("%.1f" % (time.monotonic() - start))


def raw(path, line):
    s = connect(path)
    s.sendall(line.encode())
    s.shutdown(socket.SHUT_WR)
    out = b""
    s.settimeout(60)
    while True:
        b = s.recv(4096)
        if not b:
            break
        out += b
    sys.stdout.write(out.decode(errors="replace"))


def lock(path, seconds):
    with open(path, "a") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        print("held", flush=True)
        time.sleep(float(seconds))


{"hangup": hangup, "lock": lock, "silent": silent, "trickle": trickle, "raw": raw}[sys.argv[2]](
    sys.argv[1], *sys.argv[3:])
