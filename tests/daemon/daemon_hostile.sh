#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# as9888-calibd daemon against hostile clients and a second instance: a
# client that hangs up before its answer (F1 of issue 15), silent and
# trickling clients, a record lock held by someone else, SIGTERM while
# clients stall (F3), a second daemon on the same socket (F4), request's
# exit status and --json on failure (F5), the requester of state changes in
# the log. Every wait is bounded by a generous timeout, so a stall fails a
# test instead of hanging it; no test depends on a tight time budget.
# Output is TAP.
set -u

calibd=${1:?usage: daemon_hostile.sh PATH-TO-as9888-calibd}
calibd=$(realpath "$calibd")
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/as9888-hostile-XXXXXX)
export ASAN_OPTIONS=detect_leaks=1
# no AS9888 device here: the daemon serves requests only
mkdir -p "$work/sys"
export AS9888_SYSFS=$work/sys
# shellcheck source=background.sh
. "$here/background.sh"
# shellcheck source=../lib/tap.sh
. "$here/../lib/tap.sh"
tap_plan 25
TAP_SHOW="$work/log"
# clients WHAT ARGS...: hostile_clients.py on the socket (in the background
# too: exec, so that killing $! kills the clients)
clients() { exec python3 "$here/hostile_clients.py" "$sock" "$@"; }

rec=$work/state/calibration
sock=$work/sock
"$calibd" factory-test --sim-clock virtual --record "$rec" >/dev/null ||
	{ echo "Bail out! no factory record"; exit 1; }

# start_daemon LOG [OPTIONS]: $pid, once its socket answers. A busy
# machine only makes it slower: the wait ends when the daemon exits, or
# after 120 s without an answer (a stall)
start_daemon() {
	local log=$1 t0
	shift
	"$calibd" daemon --sim-clock virtual --record "$rec" --socket "$sock" "$@" 2>"$log" &
	pid=$!
	pids+=("$pid")
	t0=$(date +%s)
	while kill -0 "$pid" 2>/dev/null && [ $(($(date +%s) - t0)) -lt 120 ]; do
		timeout 10 "$calibd" request status --socket "$sock" >/dev/null 2>&1 && return 0
		sleep 0.05
	done
	echo "Bail out! the daemon did not come up ($(kill -0 "$pid" 2>/dev/null && echo "no answer in 120 s" || echo exited): $(head -c 300 "$log"))"
	exit 1
}
alive() { kill -0 "$pid" 2>/dev/null; }
status_ok() { timeout "${1:-30}" "$calibd" request status --socket "$sock" >"$work/status" 2>&1; }
# stopped [SECONDS]: the daemon exits (SIGTERM sent) within SECONDS, status 0
stopped() {
	local t
	kill -TERM "$pid"
	for t in $(seq $((${1:-30} * 10))); do
		alive || { wait "$pid"; return; }
		sleep 0.1
	done
	kill -KILL "$pid"
	return 1
}

start_daemon "$work/log"

# F1: hang up before the answer, many times, during status and recalibrate
(clients hangup 20 status)
(clients hangup 3 recalibrate)
sleep 1
check "clients hanging up before their answer: the daemon lives on" alive
for _ in $(seq 600); do
	[ "$(grep -c 'recalibrate done' "$work/log")" -ge 3 ] && break
	sleep 0.1
done
check "and serves the next client" status_ok
check "the recalibrations whose clients left completed, record intact" \
	eval '[ "$(grep -c "recalibrate done: exit status 0" "$work/log")" -eq 3 ] &&
	      "$calibd" show --record "$rec" >/dev/null'
check "the requester of each state change is logged (SO_PEERCRED)" \
	eval '[ "$(grep -c "recalibrate requested by uid $(id -u) gid $(id -g) pid [0-9]" "$work/log")" -eq 3 ]'

# F5: request's exit status; --json prints JSON only on success
mv "$rec.previous" "$work/previous"
run request rollback --socket "$sock"
check "request rollback without a previous record: exit 1, says why" \
	eval '[ $rc -eq 1 ] && says "nothing to roll back" out && says "request rollback failed" err'
run request rollback --json --socket "$sock"
check "the same with --json: exit 1, error on stderr, nothing on stdout" \
	eval '[ $rc -eq 1 ] && [ ! -s "$work/out" ] && says "nothing to roll back" err'
mv "$work/previous" "$rec.previous"
run request check --json --socket "$sock"
check "request check --json: exit 0, stdout is JSON alone" \
	eval '[ $rc -eq 0 ] && python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$work/out"'
run request reboot --socket "$sock"
check "an unknown request: exit 2, named" eval '[ $rc -eq 2 ] && says "unknown request \"reboot\"" out'
out=$(clients raw $'recalibrate --force\n')
check "words after the request are refused, exit status 2" \
	eval 'grep -q "^error: unexpected \"--force\"" <<<"$out" && grep -q "^exit status 2$" <<<"$out"'

# F3: silent clients delay nobody
(clients silent 10 60) >"$work/silent" &
silent=$!
pids+=("$silent")
for _ in $(seq 300); do grep -q ready "$work/silent" && break; sleep 0.1; done
check "10 silent clients connected: status is still answered" status_ok 40
# each told so (the log names them too, at most a few lines a second)
check "each silent client is dropped at its request deadline" \
	eval 'for _ in $(seq 300); do grep -q "^dropped" "$work/silent" && break; sleep 0.1; done;
	      grep -qx "dropped 10" "$work/silent" && grep -q "dropped: no request line" "$work/log"'
kill "$silent" 2>/dev/null
wait "$silent" 2>/dev/null

# every slot (32) taken by silent connections of the same user: the next
# request of that user takes the place of the oldest silent one, which is
# told busy (flood.sh floods from another user)
(clients silent 32 60) >"$work/silent" &
silent=$!
pids+=("$silent")
for _ in $(seq 300); do grep -q ready "$work/silent" && break; sleep 0.1; done
for _ in $(seq 100); do
	grep -q "refused as busy" "$work/log" && break
	run request status --socket "$sock"
	sleep 0.1
done
check "32 silent connections: the next request is served, the oldest silent one let go as busy" \
	eval 'status_ok && grep -q "client(s) refused as busy in 10 s" "$work/log"'
kill "$silent" 2>/dev/null
wait "$silent" 2>/dev/null
for _ in $(seq 100); do status_ok && break; sleep 0.1; done

# a client trickling one byte every 2 s: a per-read timeout would hold it for
# minutes; the whole-request deadline (5 s) lets it go
drops=$(grep -c "dropped: no request line" "$work/log")
held=$(clients trickle 2 90)
check "a trickling client is let go within 60 s (took ${held} s)" \
	eval '[ "$held" != held ] && [ "${held%.*}" -lt 60 ] &&
	      [ "$(grep -c "dropped: no request line" "$work/log")" -gt "$drops" ]'

# a lock held by another process: the request says so and gives up after
# --lock-timeout; status is answered meanwhile
stopped || true
start_daemon "$work/log2" --lock-timeout 3
TAP_SHOW="$work/log2"
exec python3 "$here/hostile_clients.py" "$rec.lock" lock 120 >"$work/holder" &
holder=$!
pids+=("$holder")
for _ in $(seq 300); do grep -q held "$work/holder" && break; sleep 0.1; done
timeout 100 "$calibd" request recalibrate --socket "$sock" >"$work/recal" 2>&1 &
recal=$!
for _ in $(seq 300); do grep -q "recalibrate requested" "$work/log2" && break; sleep 0.1; done
check "status answered while a recalibration waits for the lock" status_ok 30
wait "$recal"; rc=$?
check "the recalibration gives up after --lock-timeout, naming the lock and who to ask" \
	eval '[ $rc -eq 1 ] && grep -q "calibration.lock is still held after 3 s" "$work/recal" &&
	      grep -q "fuser -v" "$work/recal"'
kill "$holder"
wait "$holder" 2>/dev/null
check "with the lock free, the recalibration runs" \
	eval 'timeout 100 "$calibd" request recalibrate --socket "$sock" >/dev/null'

# Issue 25, point 1: a daemon starting beside a journal (an interrupted
# change) while a command holds the lock answers status at once; it leaves
# the recovery to the holder instead of waiting up to --lock-timeout
stopped || true
cp "$rec" "$rec.previous.swap"
exec python3 "$here/hostile_clients.py" "$rec.lock" lock 120 >"$work/holder" &
holder=$!
pids+=("$holder")
for _ in $(seq 300); do grep -q held "$work/holder" && break; sleep 0.1; done
"$calibd" daemon --sim-clock virtual --record "$rec" --socket "$sock" --lock-timeout 60 2>"$work/log4" &
pid=$!
pids+=("$pid")
t0=$(date +%s)
for _ in $(seq 300); do
	timeout 10 "$calibd" request status --socket "$sock" >/dev/null 2>&1 && break
	sleep 0.1
done
waited=$(($(date +%s) - t0))
check "a daemon starting beside a journal with the lock held answers status within 30 s, not after the 60 s lock timeout (${waited} s)" \
	eval '[ $waited -lt 30 ] && status_ok'
kill "$holder"
wait "$holder" 2>/dev/null
run rollback --sim-clock virtual --record "$rec"
check "the next command takes the lock and recovers (the journal undone)" \
	eval '[ $rc -eq 0 ] && [ ! -e "$rec.previous.swap" ]'
stopped || true
start_daemon "$work/log2" --lock-timeout 3

# F4: a second daemon on the same socket refuses; the first keeps it
run daemon --sim-clock virtual --record "$rec" --socket "$sock"
check "a second daemon on a live socket refuses to start, naming the first" \
	eval '[ $rc -eq 1 ] && says "another as9888-calibd (pid $pid) is serving $sock" err'
check "the first still owns the socket" status_ok

# SIGTERM while a client trickles: the daemon stops at once
(clients trickle 2 60) >/dev/null &
trickler=$!
pids+=("$trickler")
sleep 1
check "SIGTERM with a stalling client: stopped within 30 s, exit 0" stopped 30
check "and removed its socket" test ! -e "$sock"
kill "$trickler" 2>/dev/null
wait "$trickler" 2>/dev/null

# a stale socket (nobody listening) is replaced
python3 -c "import socket,sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])" "$sock"
start_daemon "$work/log3" --lock-timeout 5
TAP_SHOW="$work/log3"
check "a stale socket file is replaced" status_ok

# SIGTERM while a request runs (it waits for a held lock): the request
# completes and its client gets its status, then the daemon stops
exec python3 "$here/hostile_clients.py" "$rec.lock" lock 120 >"$work/holder" &
holder=$!
pids+=("$holder")
for _ in $(seq 300); do grep -q held "$work/holder" && break; sleep 0.1; done
timeout 100 "$calibd" request recalibrate --socket "$sock" >"$work/recal" 2>&1 &
recal=$!
for _ in $(seq 300); do grep -q "recalibrate requested" "$work/log3" && break; sleep 0.1; done
check "SIGTERM during a request: the daemon stops within 60 s, exit 0" stopped 60
wait "$recal"
check "and the running request completed first, its client told its status" \
	eval 'grep -q "^exit status 1$" "$work/recal" && grep -q "still held after 5 s" "$work/recal" &&
	      grep -q "recalibrate done: exit status 1" "$work/log3"'
kill "$holder" 2>/dev/null
wait "$holder" 2>/dev/null

tap_end
