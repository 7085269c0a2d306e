#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The record and <record>.magn are one generation (daemon/src/store/record_store.h):
# both carry the record's "created", and a .magn of another change of the
# record is never used with it. A crash between the two pairs' changes
# (magn-calibrate's save: the magnetometer's pair first; rollback: the
# record's first) leaves them a change apart; the next command that takes
# the lock puts the magnetometer's pair back in step, keeping both files.
# The crash states are made by hand from the files of two real changes,
# as a power cut between the two pairs leaves them. Output is TAP.
set -u

calibd=${1:?usage: record_store.sh PATH-TO-as9888-calibd}
calibd=$(realpath "$calibd")
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/as9888-store-XXXXXX)
trap 'rm -rf "$work"' EXIT
export ASAN_OPTIONS=detect_leaks=1
# shellcheck source=../lib/tap.sh
. "$here/../lib/tap.sh"
tap_plan 12
TAP_SHOW="$work/err $work/out"

rec=$work/state/calibration
sim="--sim-clock virtual --unit /dev/null"
# a board with a hard iron alone, tumbled
printf 'earth = 50 55 0\nhard_iron = -60 30 90\nmagn_noise = 0.3\ntumble = 3\n' >"$work/board.unit"
# shellcheck disable=SC2086
"$calibd" factory-test $sim --record "$rec" >/dev/null ||
	{ echo "Bail out! no factory record"; exit 1; }
# "created" has a resolution of a second: each change its own
sleep 1.1
# shellcheck disable=SC2086
"$calibd" magn-calibrate --sim-clock virtual --unit "$work/board.unit" --record "$rec" >/dev/null ||
	{ echo "Bail out! no magnetometer calibration"; exit 1; }
# generation 1: the record R1 and M1, previous R0 and none (N0)
for f in "" .previous .magn .magn.previous; do cp "$rec$f" "$work/g1$f"; done
sleep 1.1
# shellcheck disable=SC2086
"$calibd" magn-calibrate --sim-clock virtual --unit "$work/board.unit" --record "$rec" >/dev/null ||
	{ echo "Bail out! no second magnetometer calibration"; exit 1; }
# generation 2: R2 and M2, previous R1 and M1
for f in "" .previous .magn .magn.previous; do cp "$rec$f" "$work/g2$f"; done
same() { cmp -s "$rec$1" "$work/$2"; }
created() { sed -n 's/^created = //p' "$1"; }

check "the two files of each change carry the record's created" eval '
	[ "$(created "$work/g1")" = "$(created "$work/g1.magn")" ] &&
	[ "$(created "$work/g2")" = "$(created "$work/g2.magn")" ] &&
	[ "$(created "$work/g1.previous")" = "$(created "$work/g1.magn.previous")" ] &&
	[ "$(created "$work/g1")" != "$(created "$work/g2")" ]'

# a save cut short between the pairs: M2 stored beside R1 (the
# magnetometer's pair changed, the record's not yet)
cp "$work/g1" "$rec"
cp "$work/g1.previous" "$rec.previous"
cp "$work/g2.magn" "$rec.magn"
cp "$work/g2.magn.previous" "$rec.magn.previous"
run show --record "$rec"
check "show (no lock): the .magn a change away is not used, its previous (the record's) is, read-only, said" eval '
	[ $rc -eq 0 ] && says "a change away from .* (an interrupted change of both)" err &&
	says "calibration.magn.previous, the record.s, is used" err && says "driver calibbias" out &&
	same .magn g2.magn && same .magn.previous g2.magn.previous'
# shellcheck disable=SC2086
run restore $sim --record "$rec"
check "restore (no lock, as at boot): the same, exit 0, the files as they were" eval '
	[ $rc -eq 0 ] && says "the record.s, is used" err && same .magn g2.magn &&
	same .magn.previous g2.magn.previous'
# shellcheck disable=SC2086
run rollback $sim --record "$rec"
check "the next command with the lock puts the magnetometer's pair in step (swapped, both kept), said" eval '
	says "was a change away from" err && says "both kept" err &&
	[ $rc -eq 0 ] && same .previous g1 && same "" g1.previous'
check "then rollback: the record back, the magnetometer's pair left (its previous is of no record here), said" eval '
	same .magn g2.magn.previous && same .magn.previous g2.magn &&
	says "the magnetometer.s pair is left as it is" err'
run show --record "$rec"
check "and its .magn (of the record rolled back from) is not used with the record rolled back to" eval '
	[ $rc -eq 1 ] && says "of another change of the record" err'

# a rollback cut short between the pairs: the record's pair swapped (R0
# current), the magnetometer's not (M1 beside R0)
cp "$work/g1.previous" "$rec"
cp "$work/g1" "$rec.previous"
cp "$work/g1.magn" "$rec.magn"
cp "$work/g1.magn.previous" "$rec.magn.previous"
# shellcheck disable=SC2086
run rollback $sim --record "$rec"
check "rollback after a rollback cut short: the pairs put in step first, then both rolled back" eval '
	[ $rc -eq 0 ] && says "was a change away from" err &&
	says "^Rolled back: .*calibration.magn holds" out &&
	same "" g1 && same .previous g1.previous && same .magn g1.magn &&
	same .magn.previous g1.magn.previous'
run show --record "$rec"
check "and the magnetometer's calibration is used again" eval '[ $rc -eq 0 ] && says "driver calibbias" out'

# both files of a generation that is neither the record's nor its
# previous one's: left as they are, nothing deleted
cp "$work/g2" "$rec"
cp "$work/g2.previous" "$rec.previous"
cp "$work/g1.magn.previous" "$rec.magn"
cp "$work/g1.magn.previous" "$rec.magn.previous"
# shellcheck disable=SC2086
run rollback $sim --record "$rec"
check "a .magn pair of no generation here: nothing deleted, nothing swapped, the record rolled back" eval '
	[ $rc -eq 0 ] && ! says "was a change away" err && cmp -s "$rec.magn" "$work/g1.magn.previous" &&
	cmp -s "$rec.magn.previous" "$work/g1.magn.previous" && same "" g2.previous'

# a save the record's pair refuses (its previous one a directory) when
# only <record>.magn.previous is there (what "remove it, then run
# magn-calibrate" leaves): the magnetometer's pair put back as it was
cp "$work/g2" "$rec"
rm -f "$rec.previous" "$rec.magn"
mkdir "$rec.previous"
cp "$work/g2.magn.previous" "$rec.magn.previous"
run magn-calibrate --sim-clock virtual --unit "$work/board.unit" --record "$rec"
check "a save refused by the record's pair: exit 1, nothing changed (<record>.magn.previous kept, no .magn made)" eval '
	[ $rc -eq 1 ] && says "nothing changed" err && same .magn.previous g2.magn.previous &&
	[ ! -e "$rec.magn" ] && same "" g2'
rmdir "$rec.previous"

# a new factory record when the magnetometer's file of the one before
# cannot be removed (a directory there): the record stands, exit 0, said
rm -f "$rec.magn" "$rec.magn.previous"
mkdir -p "$rec.magn/x"
# shellcheck disable=SC2086
run factory-test $sim --record "$rec"
check "factory-test: a .magn that cannot be removed does not fail the stored record (exit 0, said, not used)" eval '
	[ $rc -eq 0 ] && says "the record is written; the magnetometer.s files" err &&
	says "^4-1 *pass store calibration record" out && [ -d "$rec.magn" ]'
rm -rf "$rec.magn"

# the daemon at start: the same cut save (no journal) put in step
cp "$work/g1" "$rec"
cp "$work/g1.previous" "$rec.previous"
cp "$work/g2.magn" "$rec.magn"
cp "$work/g2.magn.previous" "$rec.magn.previous"
sock=$work/sock
# shellcheck disable=SC2086
"$calibd" daemon $sim --record "$rec" --socket "$sock" 2>"$work/err" &
pid=$!
# ready when it says so, after its recovery of the record (its socket is
# made before: a kill then would find the recovery not run yet); a busy
# machine only makes it slower, a daemon that died is not waited for, one
# not ready in 120 s has stalled
t0=$(date +%s)
while ! grep -q "ready: record" "$work/err" && kill -0 "$pid" 2>/dev/null &&
	[ $(($(date +%s) - t0)) -lt 120 ]; do sleep 0.1; done
kill "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
check "the daemon at start puts a cut save's pairs in step (no journal left by it), said" eval '
	says "was a change away from" err && same .magn g2.magn.previous &&
	same .magn.previous g2.magn && same "" g1'

tap_end
