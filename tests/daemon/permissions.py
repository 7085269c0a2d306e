#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""Who may ask as9888-calibd for what (issue 40: N1, N4, N5). Output is TAP.

permissions.py PATH-TO-as9888-calibd

As root, with other uids taken by forked clients (setgroups/setgid/setuid):
- a consumer (any uid that may connect) gets status and magn, and is
  refused check, recalibrate and rollback, the record untouched; a member
  of the operator group (primary or supplementary) may roll back;
- 1,000 rollbacks asked as fast as they are answered change the record at
  most RECORD_BUDGET_BURST times, the others told when the next is allowed;
- a flood of status requests leaves the log at a few lines a second, and
  says how many it left out;
- six users holding four idle connections each do not keep a seventh out:
  the biggest holder gives one up.
Every wait is bounded (a stall fails a check); no check depends on a tight
time budget.
"""
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

PLAN = 13
BUDGET = 8              # RECORD_BUDGET_BURST (daemon/src/store/record_budget.h)
LOG_LINES_PER_S = 5     # LOG_LIMIT_LINES a LOG_LIMIT_WINDOW_MS of 1 s
OPERATOR_GID = 100      # "users" on Debian; any gid works, none is created
CONSUMER = 4241
OPERATOR = 4242

n = 0
failed = 0


def check(what, ok, diag=""):
    global n, failed
    n += 1
    if ok:
        print("ok %d - %s" % (n, what))
    else:
        failed += 1
        print("not ok %d - %s" % (n, what))
        for line in str(diag).splitlines()[-15:]:
            print("# " + line)
    sys.stdout.flush()


def recv_all(s):
    """What the peer sends on S until it hangs up (or S times out)"""
    out = b""
    try:
        while True:
            b = s.recv(4096)
            if not b:
                break
            out += b
    except OSError:
        pass
    return out


def reap(pid, r):
    """All a forked child writes to R until it ends; then the child reaped"""
    out = b""
    while True:
        b = os.read(r, 4096)
        if not b:
            break
        out += b
    os.close(r)
    os.waitpid(pid, 0)
    return out


def child_ask(w, r, sock, line, uid, gid, groups, timeout):
    os.close(r)
    try:
        os.setgroups(list(groups))
        os.setgid(gid)
        os.setuid(uid)
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.settimeout(timeout)
        s.connect(sock)
        s.sendall(line.encode() + b"\n")
        os.write(w, recv_all(s))
    except OSError as e:
        os.write(w, ("client error: %s" % e).encode())


def hold_idle(r, w, sock, uid, n):
    """As UID, N connections that send nothing; what the daemon told them"""
    os.close(r)
    os.setgroups([])
    os.setgid(uid)
    os.setuid(uid)
    conns = []
    for _ in range(n):
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.connect(sock)
        conns.append(s)
    os.write(w, b"r")
    got = b""
    deadline = time.monotonic() + 30
    for s in conns:
        s.settimeout(max(0.01, deadline - time.monotonic()))
        got += recv_all(s)
    os.write(w, got)


def ask(sock, line, uid=0, gid=0, groups=(), timeout=120):
    """Send LINE as UID; the reply text (or "" when the connection failed)"""
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:
        # a child never returns into the caller (its finally would clean up)
        try:
            child_ask(w, r, sock, line, uid, gid, groups, timeout)
        finally:
            os._exit(0)
    os.close(w)
    return reap(pid, r).decode(errors="replace")


def status_of(reply):
    last = reply.rstrip("\n").split("\n")[-1]
    return int(last[len("exit status "):]) if last.startswith("exit status ") else None


def main():
    calibd = os.path.realpath(sys.argv[1])
    if os.getuid() != 0:
        print("1..0 # SKIP needs root (other uids are taken by forked clients)")
        return 77
    print("1..%d" % PLAN, flush=True)
    work = tempfile.mkdtemp(prefix="as9888-perm-")
    os.chmod(work, 0o755)
    rec = work + "/state/calibration"
    sock = work + "/sock"
    log = work + "/log"
    env = dict(os.environ, AS9888_SYSFS=work + "/sys", ASAN_OPTIONS="detect_leaks=1")
    os.makedirs(work + "/sys")
    sim = ["--sim-clock", "virtual"]
    daemon = None
    try:
        for cmd in (["factory-test"], ["recalibrate", "--samples", "12"]):
            subprocess.run([calibd] + cmd + sim + ["--record", rec], env=env,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                           check=True, timeout=300)
        daemon = subprocess.Popen([calibd, "daemon"] + sim +
                                  ["--record", rec, "--socket", sock,
                                   "--socket-mode", "0666",
                                   "--operator-group", str(OPERATOR_GID)],
                                  env=env, stderr=open(log, "w"))
        for _ in range(1200):
            if daemon.poll() is not None or status_of(ask(sock, "status", timeout=10)) == 0:
                break
            time.sleep(0.1)
        if daemon.poll() is not None:
            print("Bail out! the daemon did not start: " + open(log).read()[-300:])
            return 1

        # N1: a consumer's requests, and the record's
        with open(rec, "rb") as f:
            before = f.read()
        ok = [status_of(ask(sock, "status", CONSUMER, CONSUMER)) for _ in range(1)]
        magn = ask(sock, "magn", CONSUMER, CONSUMER)
        check("a consumer (uid %d) is answered status and magn" % CONSUMER,
              ok == [0] and status_of(magn) is not None and
              "operator group only" not in magn, magn)
        refused = {}
        for req in ("check", "recalibrate", "rollback"):
            refused[req] = ask(sock, req, CONSUMER, CONSUMER)
        check("a consumer is refused check, recalibrate and rollback, saying who may ask",
              all(status_of(r) == 1 and "is for root and the operator group only" in r
                  for r in refused.values()), refused)
        with open(rec, "rb") as f:
            check("and the record is untouched", f.read() == before)
        text = open(log).read()
        check("the log names the refused consumer's uid",
              "rollback refused for uid %d" % CONSUMER in text, text)
        r = ask(sock, "rollback", OPERATOR, 65534, groups=[OPERATOR_GID])
        check("a member of the operator group (supplementary) may roll back",
              status_of(r) == 0, r)
        text = open(log).read()
        check("the change and its completion name the requester",
              "rollback requested by uid %d" % OPERATOR in text and
              "rollback done: exit status 0 (requested by uid %d" % OPERATOR in text, text)

        # the budget: 1,000 rollbacks from root, one after the other
        done = 0
        budget_told = 0
        for _ in range(1000):
            r = ask(sock, "rollback")
            done += status_of(r) == 0
            budget_told += "too many changes of the record: the next is allowed in" in r
        check("1,000 rollbacks: %d changed the record (the budget: %d, one used above)"
              % (done, BUDGET), done == BUDGET - 1)
        check("the other %d were told when the next change is allowed" % (1000 - done),
              budget_told == 1000 - done)

        # N4: a flood of status requests, a few log lines a second
        lines0 = len(open(log).read().splitlines())
        t0 = time.monotonic()
        for _ in range(300):
            ask(sock, "status")
        elapsed = time.monotonic() - t0
        lines = open(log).read().splitlines()[lines0:]
        # each second's share, its note of what was left out, and the
        # second the flood started in
        bound = (LOG_LINES_PER_S + 1) * (int(elapsed) + 2) + 5
        check("300 status requests in %.1f s: %d log lines (at most %d)"
              % (elapsed, len(lines), bound), len(lines) <= bound, "\n".join(lines[-15:]))
        ask(sock, "status")    # after the flood, the count of what was left out
        time.sleep(1.1)
        ask(sock, "status")
        check("the log says how many routine lines it left out",
              "log line(s) like the next left out" in open(log).read())

        # N5: root with six idle connections, six users with four each,
        # then a seventh user
        holders = []
        for uid, conns in [(0, 6)] + [(uid, 4) for uid in range(5001, 5007)]:
            r, w = os.pipe()
            pid = os.fork()
            if pid == 0:
                try:
                    hold_idle(r, w, sock, uid, conns)
                finally:
                    os._exit(0)
            os.close(w)
            assert os.read(r, 1) == b"r"
            holders.append((pid, r))
        seventh = ask(sock, "status", 5007, 5007, timeout=60)
        told = []
        for pid, r in holders:
            told.append(reap(pid, r))
        check("six users holding 4 idle connections each: a seventh user is served",
              status_of(seventh) == 0, seventh)
        check("the user holding the most gave one up, told why",
              any(b"another user needed a connection" in t for t in told[1:]), told)
        check("root's 6 idle connections (its reserve) were not given up",
              b"another user needed a connection" not in told[0], told[0][-300:])
        return 0 if failed == 0 and n == PLAN else 1
    finally:
        if daemon and daemon.poll() is None:
            daemon.send_signal(signal.SIGTERM)
            try:
                daemon.wait(60)
            except subprocess.TimeoutExpired:
                daemon.kill()
        if n != PLAN:
            print("# planned %d checks, made %d" % (PLAN, n))
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
