#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Storage trust as root (F6/F7 of issue 15): a record, lock or state
# directory another user could have written is refused before anything is
# measured, restored or written, as is a symlinked state directory, a lock
# that is not a regular file and a record path that names a device; each
# refusal names the path and the fix. A group-writable state directory is
# accepted when --state-group names its group. A second user (nobody,
# through setpriv) cannot hold the record's lock, and a journal that is not
# believed is never acted on (points 1 and 6 of issue 25). Output is TAP.
set -u

calibd=${1:?usage: storage_trust.sh PATH-TO-as9888-calibd}
if [ "$(id -u)" -ne 0 ] || ! id nobody >/dev/null 2>&1 || ! command -v setpriv >/dev/null; then
	echo "1..0 # SKIP needs root, the user nobody and setpriv"
	exit 77
fi
work=$(mktemp -d /tmp/as9888-trust-XXXXXX)
trap 'rm -rf "$work"' EXIT
chmod 755 "$work"
export ASAN_OPTIONS=detect_leaks=1
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
# shellcheck source=../lib/record.sh
. "$(dirname "$0")/../lib/record.sh"
tap_plan 25
TAP_SHOW="$work/err"

state=$work/state
rec=$state/calibration
sim="--backend sim --sim-clock virtual"
group=$(id -gn nobody)
# shellcheck disable=SC2086
"$calibd" factory-test $sim --record "$rec" >/dev/null || { echo "Bail out! no record"; exit 1; }
cp "$rec" "$work/good"
fresh() {
	rm -rf "$state"
	mkdir -m 755 "$state"
	cp "$work/good" "$rec"
	chmod 644 "$rec"
}
untouched() { cmp -s "$rec" "$work/good"; }
# refused CMD TEXT...: exit 1, nothing measured (no report), every TEXT said
refused() {
	local t
	[ "$rc" -eq 1 ] && [ ! -s "$work/out" ] || return 1
	for t in "$@"; do says "$t" err || return 1; done
}

fresh
chmod 777 "$state"
# shellcheck disable=SC2086
run factory-test $sim --samples 12 --record "$rec"
check "factory-test in a world-writable state directory: refused before the test, naming the fix" \
	eval 'refused "directory $state is writable by everyone (mode 0777)" "chmod 0755 $state" && untouched'
# shellcheck disable=SC2086
run restore $sim --record "$rec"
check "restore from a world-writable state directory: refused" \
	eval 'refused "directory $state is writable by everyone"'
chmod 1777 "$state"
# shellcheck disable=SC2086
run recalibrate $sim --record "$rec"
check "recalibrate in a sticky world-writable directory: refused" \
	eval 'refused "directory $state is writable by everyone (mode 1777)" && untouched'

fresh
chgrp "$group" "$state"
chmod 775 "$state"
# shellcheck disable=SC2086
run restore $sim --record "$rec"
check "a group-writable state directory: refused, suggesting --state-group" \
	eval 'refused "writable by its group (mode 0775)" "state-group"'
# shellcheck disable=SC2086
run restore $sim --record "$rec" --state-group "$group"
check "the same with --state-group naming its group: accepted" test "$rc" -eq 0

fresh
# another user's record, valid checksum, DAC changed: never applied
sed -i 's/^dac = .*/dac = 10 10 10/' "$rec"
record_reseal "$rec"
# shellcheck disable=SC2086
"$calibd" show --record "$rec" >/dev/null 2>&1 && forged_ok=1 || forged_ok=0
chown nobody "$rec"
# shellcheck disable=SC2086
run restore $sim --record "$rec"
check "a record owned by another user (valid checksum, DAC changed): refused, naming owner and fix" \
	eval 'refused "file $rec belongs to uid $(id -u nobody)" "chown 0 $rec"'
check "(the forged record is otherwise valid: the refusal is the owner's)" test $forged_ok -eq 1

fresh
chmod 666 "$rec"
# shellcheck disable=SC2086
run restore $sim --record "$rec"
check "a world-writable record: refused, naming the chmod" \
	eval 'refused "file $rec is writable by everyone (mode 0666)" "chmod 0644 $rec"'

fresh
: >"$rec.lock"
chown nobody "$rec.lock"
# shellcheck disable=SC2086
run factory-test $sim --samples 12 --record "$rec"
check "a lock created by another user: refused at once, before the test" \
	eval 'refused "file $rec.lock belongs to uid" && untouched'

fresh
mkfifo "$rec.lock"
# shellcheck disable=SC2086
timeout 60 "$calibd" factory-test $sim --samples 12 --record "$rec" >"$work/out" 2>"$work/err"
rc=$?
check "a FIFO as the lock: refused at once, not waited on" \
	eval 'refused "lock $rec.lock is not a regular file: remove it" && untouched'

fresh
ln -s state "$work/link"
# shellcheck disable=SC2086
run factory-test $sim --samples 12 --record "$work/link/calibration"
check "a symlinked state directory: not followed, refused before the test" \
	eval 'refused "directory $work/link is a symbolic link" && untouched'
# shellcheck disable=SC2086
run restore $sim --record "$work/link/calibration"
check "restore through a symlinked state directory: refused" \
	eval 'refused "directory $work/link is a symbolic link"'

fresh
mknod "$state/null" c 1 3
# shellcheck disable=SC2086
run factory-test $sim --record "$state/null"
check "--record naming a device: refused before the test, no lock created next to it" \
	eval 'refused "$state/null is a device, FIFO or socket, not a record" && [ ! -e "$state/null.lock" ]'

fresh
# shellcheck disable=SC2086
run recalibrate $sim --samples 12 --record "$rec"
check "a sound state directory: recalibrate works" test "$rc" -eq 0

# Issue 25, point 1: flock(2) works on a descriptor opened read-only, so a
# lock another user may read is one that user may hold for ever. The lock
# is root's alone (0600); one left readable (0644, by an older version) is
# made private by the next command. "nobody" then tries to hold it.
as_nobody() { setpriv --reuid="$(id -u nobody)" --regid="$(id -g nobody)" --clear-groups "$@"; }
# holder_says WORD: wait (30 s at most) until $holder wrote WORD or ended
holder_says() {
	for _ in $(seq 300); do
		grep -q "$1" "$work/holder" 2>/dev/null && return
		kill -0 "$holder" 2>/dev/null || return
		sleep 0.1
	done
}
# hold_lock: nobody tries flock on the lock; "held" in $work/holder if it got it
hold_lock() {
	rm -f "$work/holder"
	as_nobody flock -x -n "$rec.lock" sh -c 'echo held; exec sleep 120' >"$work/holder" 2>&1 &
	holder=$!
	holder_says held
}
let_go() { kill "$holder" 2>/dev/null; wait "$holder" 2>/dev/null; }
check "the record's lock is private to root (mode 0600)" \
	test "$(stat -c %a "$rec.lock")" = 600
hold_lock
# shellcheck disable=SC2086
run rollback $sim --record "$rec" --lock-timeout 5
check "another user cannot take the lock: rollback runs at once" \
	eval '[ $rc -eq 0 ] && ! grep -q held "$work/holder"'
let_go
chmod 644 "$rec.lock"
# shellcheck disable=SC2086
run recalibrate $sim --samples 12 --record "$rec" --lock-timeout 5
check "a lock left readable by others (0644): made private by the next command" \
	eval '[ $rc -eq 0 ] && [ "$(stat -c %a "$rec.lock")" = 600 ]'
hold_lock
# shellcheck disable=SC2086
run factory-test $sim --samples 12 --record "$rec" --lock-timeout 5
check "and then another user cannot hold it: factory-test runs" \
	eval '[ $rc -eq 0 ] && ! grep -q held "$work/holder"'
let_go
# Issue 40, N2: a descriptor nobody opened while the lock was 0644 must not
# hold the lock once it is private: chmod on the same inode would leave that
# descriptor working, a new file renamed over the old one does not
chmod 644 "$rec.lock"
ino_before=$(stat -c %i "$rec.lock")
rm -f "$work/holder" "$work/go"
# shellcheck disable=SC2016
as_nobody sh -c 'exec 3<"$1"; echo opened; while [ ! -e "$2" ]; do sleep 0.1; done
	flock -x -n 3 && echo held; exec sleep 120' sh "$rec.lock" "$work/go" >"$work/holder" 2>&1 &
holder=$!
holder_says opened
# shellcheck disable=SC2086
run recalibrate $sim --samples 12 --record "$rec" --lock-timeout 5
touch "$work/go"
holder_says held
check "a lock opened by another user while it was 0644: replaced by a new private file" \
	eval '[ $rc -eq 0 ] && grep -q opened "$work/holder" && [ "$(stat -c %i "$rec.lock")" != "$ino_before" ] && [ "$(stat -c %a "$rec.lock")" = 600 ]'
# shellcheck disable=SC2086
run rollback $sim --record "$rec" --lock-timeout 5
check "and that old descriptor's flock does not stop rollback (it locks an inode nobody uses)" \
	eval '[ $rc -eq 0 ] && grep -q held "$work/holder"'
let_go

# Issue 25, point 6: a journal (<record>.previous.swap) is acted on only when
# it is believed (root's, not writable by others) and a valid record; the
# good previous record is never replaced by one that is not
fresh
# shellcheck disable=SC2086
"$calibd" recalibrate $sim --samples 12 --record "$rec" >/dev/null 2>&1
cp "$rec.previous" "$work/prev.good"
journal=$rec.previous.swap
# journal_refused CMD TEXT: CMD refused naming TEXT; the pair and the journal as they were
journal_refused() {
	local cmd=$1 text=$2
	cp "$rec" "$work/cur.before"
	# shellcheck disable=SC2086
	run $cmd $sim --record "$rec" --lock-timeout 5
	[ "$rc" -eq 1 ] && says "$text" err && says "nothing changed: move $journal aside by hand" err &&
		cmp -s "$rec.previous" "$work/prev.good" && cmp -s "$rec" "$work/cur.before" && [ -e "$journal" ]
}
sed 's/^samples = .*/samples = 99/' "$work/good" >"$journal"	# its checksum no longer matches
chown nobody "$journal"
check "another user's journal with a broken checksum: rollback refuses it, the previous record kept" \
	journal_refused rollback "$journal belongs to uid $(id -u nobody), not to root: not trusted"
cp "$work/good" "$journal"
chown nobody "$journal"
check "another user's journal with a valid checksum: refused all the same (recalibrate)" \
	journal_refused recalibrate "$journal belongs to uid $(id -u nobody), not to root: not trusted"
sed 's/^samples = .*/samples = 99/' "$work/good" >"$journal"
chown root "$journal"
check "root's journal that is not a valid record: refused (rollback)" \
	journal_refused rollback "$journal is not a valid record"
# a journal holds the only copy of the record it replaced: with the record
# gone beside it, nothing is removed on its word
cp "$work/good" "$journal"
mv "$rec" "$work/rec.aside"
# shellcheck disable=SC2086
run rollback $sim --record "$rec" --lock-timeout 5
check "root's valid journal beside a missing record: refused, the journal and the previous record kept" \
	eval '[ $rc -eq 1 ] && says "nothing changed: move $journal aside by hand" err && cmp -s "$journal" "$work/good" && cmp -s "$rec.previous" "$work/prev.good"'
mv "$work/rec.aside" "$rec"
rm -f "$journal"
# shellcheck disable=SC2086
run rollback $sim --record "$rec"
check "with the journal removed, rollback works" \
	eval '[ $rc -eq 0 ] && cmp -s "$rec" "$work/prev.good"'

tap_end
