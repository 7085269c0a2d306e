#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Storage trust as root (F6/F7 of issue 15): a record, lock or state
# directory another user could have written is refused before anything is
# measured, restored or written, as is a symlinked state directory, a lock
# that is not a regular file and a record path that names a device; each
# refusal names the path and the fix. A group-writable state directory is
# accepted when --state-group names its group. Output is TAP.
set -u

calibd=${1:?usage: storage_trust.sh PATH-TO-as9888-calibd}
if [ "$(id -u)" -ne 0 ] || ! id nobody >/dev/null 2>&1; then
	echo "1..0 # SKIP needs root and the user nobody"
	exit 77
fi
work=$(mktemp -d /tmp/as9888-trust-XXXXXX)
trap 'rm -rf "$work"' EXIT
chmod 755 "$work"
export ASAN_OPTIONS=detect_leaks=1
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
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
python3 - "$rec" <<'PY'
import re, sys, zlib
p = sys.argv[1]
text = open(p).read()
text = re.sub(r"(?m)^dac = .*$", "dac = 10 10 10", text)
body = re.sub(r"(?m)^crc32 = .*\n", "", text)
open(p, "w").write(body + "crc32 = %08x\n" % zlib.crc32(body.encode()))
PY
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

tap_end
