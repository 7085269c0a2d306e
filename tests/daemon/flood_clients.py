#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""A flood of hostile clients on as9888-calibd's socket, for flood.sh.

flood_clients.py SOCKET IDLE BUSY TRICKLE SECONDS

keeps IDLE + BUSY + TRICKLE connections going for SECONDS, then closes
them all and prints one line of counts:
- IDLE connections send nothing and are reopened every 4.5 s (before the
  daemon's 5 s request deadline: the attack that kept all 16 slots of the
  old daemon taken), also when the daemon hung up on them before;
- BUSY connections ask "status" and reconnect as soon as they are answered;
- TRICKLE connections send one byte a second and never a newline.
Prints "ready" once every connection was tried. Non-blocking throughout: a
connection the daemon does not accept yet is tried again 50 ms later.
"""
import errno
import selectors
import socket
import sys
import time

IDLE_REOPEN_S = 4.5
RETRY_S = 0.05
BUSY_PAUSE_S = 0.01     # between a BUSY connection's answer and the next


class Conn:
    def __init__(self, kind):
        self.kind = kind
        self.sock = None
        self.due = 0.0          # when to act next
        self.reply = b""


def main(path, idle, busy, trickle, seconds):
    sel = selectors.DefaultSelector()
    conns = ([Conn("idle") for _ in range(idle)] + [Conn("busy") for _ in range(busy)] +
             [Conn("trickle") for _ in range(trickle)])
    counts = {"connects": 0, "refused": 0, "answered": 0, "dropped": 0, "retries": 0}

    def close(c):
        if c.sock:
            try:
                sel.unregister(c.sock)
            except (KeyError, ValueError):
                pass
            c.sock.close()
            c.sock = None

    def open_(c, now):
        close(c)
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.setblocking(False)
        try:
            s.connect(path)
        except BlockingIOError:
            s.close()
            counts["retries"] += 1
            c.due = now + RETRY_S
            return
        except OSError as e:
            s.close()
            counts["retries"] += 1
            if e.errno not in (errno.EAGAIN, errno.ECONNREFUSED, errno.ENOENT):
                raise
            c.due = now + RETRY_S
            return
        counts["connects"] += 1
        c.sock = s
        c.reply = b""
        sel.register(s, selectors.EVENT_READ, c)
        if c.kind == "busy":
            try:
                s.send(b"status\n")
            except OSError:
                pass
            c.due = now + 60
        elif c.kind == "idle":
            c.due = now + IDLE_REOPEN_S
        else:
            c.due = now + 1.0

    start = time.monotonic()
    for c in conns:
        open_(c, start)
    print("ready", flush=True)
    while time.monotonic() - start < seconds:
        now = time.monotonic()
        nxt = min(c.due for c in conns)
        for key, _ in sel.select(timeout=max(0.0, min(nxt - now, 0.2))):
            c = key.data
            try:
                b = c.sock.recv(65536)
            except OSError:
                b = b""
            if b:
                c.reply += b
                continue
            # the daemon hung up: answered, refused or dropped
            if b"error: busy" in c.reply:
                counts["refused"] += 1
            elif b"exit status 0" in c.reply:
                counts["answered"] += 1
            else:
                counts["dropped"] += 1
            close(c)
            # IDLE: reopened at its next period, as the attack of the issue does
            if c.kind == "busy":
                c.due = time.monotonic() + BUSY_PAUSE_S
            elif c.kind == "trickle":
                c.due = time.monotonic() + 1.0
        now = time.monotonic()
        for c in conns:
            if c.due > now:
                continue
            if c.sock is None or c.kind != "trickle":
                open_(c, now)
                continue
            try:
                c.sock.send(b"s")
            except OSError:
                pass
            c.due = now + 1.0
    for c in conns:
        close(c)
    print("connects %(connects)d refused %(refused)d answered %(answered)d "
          "dropped %(dropped)d retries %(retries)d" % counts, flush=True)


main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), float(sys.argv[5]))
