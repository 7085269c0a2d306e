#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# mutate.sh [NAME...]: a mutation check of the Meson suite.
#
# Each mutant of tests/mutate/mutants.txt (default: all; or the ones named)
# changes one expression of the shared arithmetic (the driver's
# as9888_calib.c, lib/calib/), of the factory-test engine (daemon/src/ftest/)
# or of the magnetometer's fit (lib/magcal/). The suite includes
# calib-kunit, the driver's KUnit cases built as a program, so a mutant of
# the shared arithmetic also meets KUnit's hand-computed values. For each
# mutant, the suite is built and run in a scratch
# copy of this checkout (working-tree files, tracked and untracked but not
# ignored); the checkout itself is never written, and the scratch copy is
# removed on exit, ^C included. A mutant is "killed" when the suite fails,
# "SURVIVED" when it passes: a change of behaviour no test notices.
# Prints one line per mutant and "mutate: N killed, N survived, N invalid"
# (invalid: the text is gone or ambiguous, or the mutant does not build:
# fix the list). Exit status 0 only when every mutant was killed.
#
# The build is a plain debug build (no sanitizers: faster; a mutant must
# change a result, not only trip a sanitizer); the suite stops at its first
# failure (meson test --maxfail 1). An unmutated run first must pass.
# Environment: AS9888_JOBS (meson test's processes, default 2), TMPDIR.
set -uo pipefail

top=$(cd "$(dirname "$0")/.." && pwd)
list=$top/tests/mutate/mutants.txt
jobs=${AS9888_JOBS:-2}

scratch=$(mktemp -d "${TMPDIR:-/tmp}/as9888-mutate.XXXXXX") || exit 1
cleanup() { rm -rf "$scratch"; }
trap cleanup EXIT
trap 'echo "mutate: interrupted" >&2; exit 130' INT TERM

src=$scratch/src
build=$scratch/build
mkdir -p "$src"
(cd "$top" && git ls-files -z -co --exclude-standard | xargs -0 cp --parents -t "$src" 2>/dev/null)
[ -f "$src/meson.build" ] || { echo "mutate: cannot copy the checkout" >&2; exit 1; }

mapfile -t mutants < <(grep -v '^#' "$list" | grep -v '^$')
if [ $# -gt 0 ]; then
	want=" $* "
	sel=()
	for m in "${mutants[@]}"; do
		case $want in *" ${m%%$'\t'*} "*) sel+=("$m") ;; esac
	done
	[ ${#sel[@]} -eq $# ] || { echo "mutate: unknown mutant among: $*" >&2; exit 2; }
	mutants=("${sel[@]}")
fi

# suite LOG: build and run the suite in the scratch copy; 0 = passed, 200 =
# the build failed
# The tests that judge a mutant: the whole suite but the attack and
# storage tests (the record's files, locks and journal, the service's
# sockets, the package install: they exercise neither the arithmetic nor
# the engine, and take minutes; flood.sh also runs as another user, who
# cannot enter this scratch directory)
skip_tests=" save_inject daemon_hostile storage_trust uevent_storm activation flood install "
suite() {
	local tests=() t
	ninja -C "$build" >"$1" 2>&1 || return 200
	while read -r t; do
		case $skip_tests in *" ${t##* / } "*) continue ;; esac
		tests+=("${t##* / }")
	done < <(meson test -C "$build" --no-rebuild --list 2>/dev/null)
	[ ${#tests[@]} -gt 0 ] || return 200
	meson test -C "$build" --no-rebuild --maxfail 1 --num-processes "$jobs" \
		"${tests[@]}" >>"$1" 2>&1
}

t0=$(date +%s)
meson setup "$build" "$src" -Db_sanitize=none -Dwerror=false >"$scratch/setup.log" 2>&1 ||
	{ cat "$scratch/setup.log" >&2; echo "mutate: meson setup failed" >&2; exit 1; }
if ! suite "$scratch/base.log"; then
	tail -n 30 "$scratch/base.log" >&2
	echo "mutate: the unmutated suite fails: no mutant can be judged" >&2
	exit 1
fi
echo "mutate: unmutated suite passes ($(($(date +%s) - t0)) s)"

killed=0 survived=0 invalid=0
for m in "${mutants[@]}"; do
	IFS=$'\t' read -r name file from to <<<"$m"
	t=$(date +%s)
	cp -p "$src/$file" "$scratch/orig"
	if ! python3 - "$src/$file" "$from" "$to" <<'EOF'
import re, sys
path, old, new = sys.argv[1:]
# \t, \n and \\ in the list stand for a TAB, a newline and a backslash
unescape = lambda s: re.sub(r"\\([tn\\])",
                            lambda m: {"t": "\t", "n": "\n", "\\": "\\"}[m.group(1)], s)
old, new = unescape(old), unescape(new)
text = open(path).read()
if text.count(old) != 1:
    sys.exit("text found %d times" % text.count(old))
open(path, "w").write(text.replace(old, new))
EOF
	then
		echo "mutate: $name: INVALID: its text is not in $file exactly once"
		invalid=$((invalid + 1))
		continue
	fi
	suite "$scratch/$name.log"
	rc=$?
	# the file back, newer than its objects: the next build recompiles it
	cp "$scratch/orig" "$src/$file"
	touch "$src/$file"
	if [ $rc -eq 200 ]; then
		echo "mutate: $name: INVALID: does not build:"
		grep -m 3 'error:' "$scratch/$name.log" | sed 's/^/    /'
		invalid=$((invalid + 1))
	elif [ $rc -ne 0 ]; then
		by=$(sed -n 's/^ *[0-9]*\/[0-9]* \(.*\) \(FAIL\|TIMEOUT\|ERROR\) .*/\1/p' \
			"$scratch/$name.log" | head -n 1 | sed 's/ *$//')
		echo "mutate: $name: killed by ${by:-the suite} ($(($(date +%s) - t)) s)"
		killed=$((killed + 1))
	else
		echo "mutate: $name: SURVIVED ($file: '$from' -> '$to')"
		survived=$((survived + 1))
	fi
done
echo "mutate: ${#mutants[@]} mutants in $(($(date +%s) - t0)) s"
echo "mutate: $killed killed, $survived survived, $invalid invalid"
[ $survived -eq 0 ] && [ $invalid -eq 0 ]
