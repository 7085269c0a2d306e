#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The descriptor systemd passes (issue 25, point 4): as9888-calibd daemon
# started as a socket unit would start it (LISTEN_PID = its pid,
# LISTEN_FDS = 1, fd 3) with fd 3 anything but a listening Unix stream
# socket refuses to start, naming what fd 3 is, instead of saying "ready"
# and spinning, serving nothing, or serving a TCP port that bypasses the
# socket file's permissions. Eight wrong descriptors or variables, then the
# right one (served), and variables meant for another process (ignored).
# Every run is bounded (a daemon that does not exit in time is killed and
# the check fails). Output is TAP.
set -u

calibd=${1:?usage: activation.sh PATH-TO-as9888-calibd}
work=$(mktemp -d /tmp/as9888-activation-XXXXXX)
# shellcheck source=background.sh
. "$(dirname "$0")/background.sh"
export ASAN_OPTIONS=detect_leaks=1
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
tap_plan 10
TAP_SHOW="$work/err"
mkdir -p "$work/sys"
export AS9888_SYSFS=$work/sys
rec=$work/state/calibration
"$calibd" factory-test --sim-clock virtual --record "$rec" >/dev/null ||
	{ echo "Bail out! no factory record"; exit 1; }

# launch.py KIND FDS PID-MODE -- COMMAND...: fd 3 made of KIND, LISTEN_FDS=FDS,
# LISTEN_PID this process's pid ("self", kept by exec) or another ("other")
cat >"$work/launch.py" <<'PY'
import os, socket, sys
kind, fds, pid_mode = sys.argv[1:4]
argv = sys.argv[5:]
keep = []
if kind == "file":
    fd = os.open(sys.argv[0], os.O_RDONLY)
elif kind == "pipe":
    fd, w = os.pipe()
    keep.append(w)
elif kind == "unbound":
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM); keep.append(s); fd = s.fileno()
elif kind == "dgram":
    s = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    s.bind(os.environ["SOCK"]); keep.append(s); fd = s.fileno()
elif kind == "tcp":
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    s.bind(("127.0.0.1", 0)); s.listen(); keep.append(s); fd = s.fileno()
elif kind == "unix":
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.bind(os.environ["SOCK"]); s.listen(); keep.append(s); fd = s.fileno()
else:
    fd = None
if fd is None:
    try:
        os.close(3)
    except OSError:
        pass
elif fd != 3:
    os.dup2(fd, 3)
else:
    os.set_inheritable(3, True)
os.environ["LISTEN_FDS"] = fds
os.environ["LISTEN_PID"] = str(os.getpid() if pid_mode == "self" else 1)
os.execv(argv[0], argv)
PY

# daemon_with KIND FDS [PID-MODE]: the daemon under launch.py, at most 30 s; $rc
daemon_with() {
	SOCK=$work/act.sock timeout -s KILL 30 python3 "$work/launch.py" "$1" "$2" "${3:-self}" -- \
		"$calibd" daemon --sim-clock virtual --record "$rec" --socket "$work/own.sock" \
		>"$work/out" 2>"$work/err"
	rc=$?
	rm -f "$work/act.sock" "$work/own.sock"
}
# refused TEXT: exit 1 at once, TEXT said, never "ready"
refused() { [ "$rc" -eq 1 ] && says "$1" err && ! says "ready" err; }

daemon_with file 1
check "fd 3 a regular file: refused, not a socket" refused "descriptor 3 is not a socket"
daemon_with pipe 1
check "fd 3 a pipe: refused, not a socket" refused "descriptor 3 is not a socket"
daemon_with unbound 1
check "fd 3 an unbound Unix stream socket: refused, not listening" \
	refused "descriptor 3 is not listening"
daemon_with dgram 1
check "fd 3 a Unix datagram socket: refused, not a stream socket" \
	refused "descriptor 3 is not a stream socket"
daemon_with tcp 1
check "fd 3 a TCP socket on 127.0.0.1: refused (the socket file's permissions would not apply)" \
	refused "descriptor 3 is not a Unix socket"
daemon_with closed 1
check "fd 3 closed: refused (its own descriptors are never taken for it)" \
	refused "descriptor 3 is not open"
daemon_with unix 1x
check "LISTEN_FDS=1x: refused, not counted as 1" refused 'LISTEN_FDS="1x": exactly one socket'
daemon_with unix 2
check "LISTEN_FDS=2: refused, one socket expected" refused 'LISTEN_FDS="2": exactly one socket'

# the right descriptor is served; LISTEN_* of another process are ignored
serve_with() {
	SOCK=$work/act.sock python3 "$work/launch.py" "$1" 1 "$2" -- \
		"$calibd" daemon --sim-clock virtual --record "$rec" --socket "$work/own.sock" \
		2>"$work/err" &
	pid=$!
	pids+=("$pid")
	for _ in $(seq 300); do
		timeout 10 "$calibd" request status --socket "$3" >"$work/out" 2>&1 && break
		sleep 0.1
	done
	timeout 10 "$calibd" request status --socket "$3" >"$work/out" 2>&1
	rc=$?
	kill "$pid"
	wait "$pid" 2>/dev/null
}
serve_with unix self "$work/act.sock"
check "fd 3 a listening Unix stream socket: served" \
	eval '[ $rc -eq 0 ] && says "Chip 676f64b435a720ba" out && [ ! -e "$work/own.sock" ]'
rm -f "$work/act.sock"
serve_with unix other "$work/own.sock"
check "LISTEN_PID of another process: ignored, the daemon makes its own socket" \
	eval '[ $rc -eq 0 ] && says "Chip 676f64b435a720ba" out'

tap_end
