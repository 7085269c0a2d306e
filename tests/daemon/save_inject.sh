#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Crash safety of the record save: inject a failure (an error return, or
# SIGKILL as a stand-in for a power cut) into every system call of the save
# path in turn, with strace, and check what is on disk afterwards: the
# record path holds either the complete old record or a complete new one,
# never a torn one, and a failed save reports failure and leaves no
# temporary file. Output is TAP.
set -u

calibd=${1:?usage: save_inject.sh PATH-TO-as9888-calibd}
command -v strace >/dev/null || { echo "1..0 # SKIP strace is not installed"; exit 77; }

work=$(mktemp -d /tmp/as9888-inject-XXXXXX)
trap 'rm -rf "$work"' EXIT
rec=$work/cal
export ASAN_OPTIONS=detect_leaks=0

run() {
	"$calibd" factory-test --sim-clock virtual --record "$rec" "$@"
}

run >/dev/null || { echo "Bail out! factory test does not pass"; exit 1; }
cp "$rec" "$work/old"

n=0
fail=0
hits=0
ok() { n=$((n + 1)); echo "ok $n - $*"; }
not_ok() { n=$((n + 1)); fail=$((fail + 1)); echo "not ok $n - $*"; }

# The plan comes first, so that a run that stops early fails: every
# injection point of both parts is listed before the first check.
#
# Part 2's record pair lives in its own directory (part 1 saves a record
# with no previous one, as before); its points are the calls each command
# makes on the pair's files, from one run without injection.
rec1=$rec
rec=$work/pair/cal
mkdir -p "$work/pair"
# The record and its previous one as a pair (daemon/src/store/record_pair.h):
# rollback, recalibrate, factory-test and magn-calibrate are each
# interrupted at every
# system call that touches the record's files (a SIGKILL, standing in for
# a power cut), or see EIO at every one of them (rollback, recalibrate,
# magn-calibrate),
# ENOSPC at every write, fsync and close and EROFS at every open, rename,
# unlink and fchmod. Then one rollback follows (it finishes or undoes what
# was interrupted, then swaps), and the pair must be what the old pair or
# the new pair gives after that swap: no record is ever lost or
# duplicated, and no temporary or journal file stays. And the exit status
# of rollback, recalibrate and magn-calibrate tells the truth (issue 25, point 3): 0 when
# the new pair stands, not 0 when the old one does.
run_sim() { "$calibd" "$@" --backend sim --sim-clock virtual --record "$rec"; }
run_sim factory-test >/dev/null && run_sim recalibrate --samples 11 >/dev/null ||
	{ echo "Bail out! no record pair"; exit 1; }
cp "$rec" "$work/R"
cp "$rec.previous" "$work/P"
files="$rec $rec.new $rec.previous $rec.previous.swap $rec.previous.swap.new $rec.lock ${rec%/*}"
# the magnetometer's file and its pair (magn-calibrate writes them)
files="$files $rec.magn $rec.magn.new $rec.magn.previous $rec.magn.previous.swap $rec.magn.previous.swap.new"
trace_paths=()
for f in $files; do trace_paths+=(-P "$f"); done
reset_pair() {
	cp "$work/R" "$rec"
	cp "$work/P" "$rec.previous"
	rm -f "$rec.new" "$rec.previous.swap" "$rec.previous.swap.new" "$rec.magn"*
}
# is_new FILE: a valid record from the interrupted command (12 samples)
is_new() {
	grep -q '^samples = 12$' "$1" && "$calibd" show --record "$1" >/dev/null 2>&1
}
# magn_is FILE yes|no: <record>.magn FILE holds a calibration (yes), or
# none or is missing (no)
magn_is() {
	if [ "$2" = yes ]; then grep -q '^magn_hard_iron = ' "$1"
	else [ ! -e "$1" ] || ! grep -q '^magn_hard_iron = ' "$1"; fi
}
# magn-calibrate's board: turned through every direction by the model
printf 'earth = 48 60 3\nhard_iron = 120 -80 45\ntumble = 4\n' >"$work/board.unit"
same() { cmp -s "$1" "$2"; }
# pair_state CMD: which pair CMD left ("old" or "new"), seen after one
# rollback; nothing (status 1) when it is neither
pair_state() {
	local old=no new=no
	case $1 in
	rollback)	# old (R,P) -> (P,R); new (P,R) -> (R,P)
		same "$rec" "$work/P" && same "$rec.previous" "$work/R" && old=yes
		same "$rec" "$work/R" && same "$rec.previous" "$work/P" && new=yes ;;
	recalibrate)	# old (R,P) -> (P,R); new (N,R) -> (R,N)
		same "$rec" "$work/P" && same "$rec.previous" "$work/R" && old=yes
		same "$rec" "$work/R" && is_new "$rec.previous" && new=yes ;;
	magn-calibrate)	# the record's pair as recalibrate's, N the same
		# accelerometer's record (format 1); the magnetometer's:
		# old: none in effect; new (M, none) -> (none, M)
		same "$rec" "$work/P" && same "$rec.previous" "$work/R" &&
			magn_is "$rec.magn" no && old=yes
		same "$rec" "$work/R" && "$calibd" show --record "$rec.previous" >/dev/null 2>&1 &&
			grep -q '^samples = 11$' "$rec.previous" &&
			magn_is "$rec.magn" no && magn_is "$rec.magn.previous" yes && new=yes ;;
	factory-test)	# old (R,P) -> (P,R); new (N,P) -> (P,N)
		same "$rec" "$work/P" && same "$rec.previous" "$work/R" && old=yes
		same "$rec" "$work/P" && is_new "$rec.previous" && new=yes ;;
	esac
	[ $old = yes ] && echo old && return 0
	[ $new = yes ] && echo new && return 0
	return 1
}
# the command's calls on the record's files, each "NAME K" (its K-th NAME)
calls_of() {
	reset_pair
	strace -f -qq -o "$work/trace" "${trace_paths[@]}" "$calibd" "$@" \
		--backend sim --sim-clock virtual --record "$rec" >/dev/null 2>&1
	awk '{ sub(/\(.*/, "", $2); if ($2 !~ /^[a-z_0-9]+$/) next; print $2, ++k[$2] }' "$work/trace"
}
# cmd_args CMD: $args, the command line part 2 runs for CMD
cmd_args() {
	args=("$1")
	case $1 in
	rollback) ;;
	magn-calibrate) args+=(--unit "$work/board.unit") ;;
	*) args+=(--samples 12) ;;
	esac
}
# pair_points: "CMD ACTION CALL K INJECT" for each injection of part 2
pair_points() {
	local cmd call k action inject
	for cmd in rollback recalibrate factory-test magn-calibrate; do
		cmd_args "$cmd"
		while read -r call k; do
			for action in kill EIO ENOSPC EROFS; do
				case $action:$call in
				kill:*) inject="$call:signal=KILL:when=$k" ;;
				EIO:*) [ "$cmd" = factory-test ] && continue
					inject="$call:error=EIO:when=$k" ;;
				ENOSPC:write|ENOSPC:fsync|ENOSPC:close) inject="$call:error=ENOSPC:when=$k" ;;
				EROFS:openat|EROFS:rename|EROFS:renameat|EROFS:renameat2|EROFS:unlinkat|EROFS:fchmod|EROFS:mkdir)
					inject="$call:error=EROFS:when=$k" ;;
				*) continue ;;
				esac
				echo "$cmd $action $call $k $inject"
			done
		done < <(calls_of "${args[@]}")
	done
}
pair_points >"$work/points"
rec=$rec1

# Part 1's points: an error and a kill at each of the first three calls
# of each kind the save makes, as one run without injection makes them
cp "$work/old" "$rec"
strace -f -qq -o "$work/trace" -P "$rec" -P "$rec.new" -P "$work" \
	-e trace=openat,fchmod,write,fsync,close,rename,renameat,renameat2 \
	"$calibd" factory-test --sim-clock virtual --samples 12 --record "$rec" >/dev/null 2>&1
awk '{ sub(/\(.*/, "", $2); if ($2 ~ /^[a-z_0-9]+$/) k[$2]++ }
	END { split("error kill", acts, " ")
	      split("openat fchmod write fsync close renameat rename renameat2", calls, " ")
	      for (a = 1; a <= 2; a++) for (c = 1; c <= 8; c++) for (w = 1; w <= 3; w++)
		if (k[calls[c]] >= w) print acts[a], calls[c], w }' "$work/trace" >"$work/points1"
# part 1's points, its save after an interrupted one and its floor of 10
# points; part 2's points, its floor of 250 and the two directory checks
plan=$(($(wc -l <"$work/points1") + 2 + $(wc -l <"$work/points") + 3))
echo "1..$plan"

# (the list on descriptor 3: what the loop runs keeps its own stdin)
while read -r action call when <&3; do
	case $action in
	error) inject="$call:error=EIO:when=$when" ;;
	kill) inject="$call:signal=KILL:when=$when" ;;
	esac
	cp "$work/old" "$rec"
	rm -f "$rec.new"
	# a different sample count makes the new record differ
	strace -f -qq -o "$work/trace" -P "$rec" -P "$rec.new" -P "$work" \
		-e trace=openat,fchmod,write,fsync,close,rename,renameat,renameat2 \
		-e inject="$inject" \
		"$calibd" factory-test --sim-clock virtual --samples 12 \
		--record "$rec" >"$work/out" 2>"$work/stderr" &
	wait $! 2>/dev/null
	rc=$?
	if ! grep -qE 'INJECTED|killed by SIGKILL' "$work/trace"; then
		not_ok "$action at $call #$when: the injection point was not reached"
		continue
	fi
	hits=$((hits + 1))
	what="$action at $call #$when"
	if cmp -s "$rec" "$work/old"; then
		state=old
	elif "$calibd" show --record "$rec" >/dev/null 2>&1 &&
	     grep -q '^samples = 12$' "$rec"; then
		state=new
	else
		not_ok "$what: record torn or missing"
		continue
	fi
	if [ "$action" = error ] && [ $rc -eq 0 ] && [ $state = old ]; then
		not_ok "$what: save failed but the command reported success"
	elif [ "$action" = error ] && [ -e "$rec.new" ]; then
		not_ok "$what: temporary file left behind"
	elif [ "$action" = error ] && [ $rc -ne 0 ] &&
	     ! grep -qE '^4-1 +fail store calibration record: cannot' "$work/out"; then
		not_ok "$what: no reason given"
	else
		ok "$what: $state record intact (exit $rc)"
	fi
done 3<"$work/points1"

# a stale temporary left by a killed save does not block the next save
run --samples 13 >/dev/null && grep -q '^samples = 13$' "$rec" && [ ! -e "$rec.new" ] &&
	ok "save after an interrupted one" || not_ok "save after an interrupted one"

[ $hits -ge 10 ] && ok "$hits injection points reached (at least 10)" ||
	not_ok "only $hits injection points were reached"

rec=$work/pair/cal
pair_runs=0
status_lies=0
while read -r cmd action call k inject <&3; do
	cmd_args "$cmd"
	reset_pair
	strace -f -qq -o "$work/trace" "${trace_paths[@]}" -e inject="$inject" \
		"$calibd" "${args[@]}" --backend sim --sim-clock virtual \
		--record "$rec" >"$work/out" 2>"$work/stderr" &
	wait $! 2>/dev/null
	rc=$?
	pair_runs=$((pair_runs + 1))
	what="$cmd, $action at $call #$k"
	if [ "$action" != kill ] && [ $rc -ne 0 ] && [ ! -s "$work/stderr" ] &&
	   ! grep -q 'fail store calibration record' "$work/out"; then
		not_ok "$what: failed without saying why"
		continue
	fi
	if [ "$action" != kill ] && [ -e "$rec.new" -o -e "$rec.previous.swap.new" -o \
	     -e "$rec.magn.new" -o -e "$rec.magn.previous.swap.new" ]; then
		not_ok "$what: temporary file left behind"
		continue
	fi
	run_sim rollback >"$work/out2" 2>"$work/stderr2"
	rc2=$?
	if [ $rc2 -ne 0 ]; then
		not_ok "$what: the next rollback fails: $(head -c 300 "$work/stderr2")"
	elif [ -e "$rec.previous.swap" ] || [ -e "$rec.magn.previous.swap" ]; then
		not_ok "$what: journal left after the next rollback"
	elif ! state=$(pair_state "$cmd"); then
		not_ok "$what: record pair neither the old nor the new one"
	elif [ "$action" != kill ] && [ "$cmd" != factory-test ] &&
	     { [ $rc -eq 0 ] && [ $state = old ] || [ $rc -ne 0 ] && [ $state = new ]; }; then
		status_lies=$((status_lies + 1))
		not_ok "$what: exit $rc but the $state pair stands: $(head -c 300 "$work/stderr")"
	else
		ok "$what: $state pair intact (exit $rc)"
	fi
done 3<"$work/points"
[ $pair_runs -ge 250 ] && ok "$pair_runs pair injections ran (at least 250)" ||
	not_ok "only $pair_runs pair injections ran"

# A directory where the previous record goes: recalibrate refuses before it
# changes anything (it used to store the new record, say FAIL and leave a
# journal that stopped every later command)
reset_pair
mv "$rec.previous" "$work/P.aside"
mkdir "$rec.previous"
run_sim recalibrate --samples 12 >"$work/out" 2>"$work/stderr"
rc=$?
if [ $rc -ne 0 ] && same "$rec" "$work/R" && [ ! -e "$rec.previous.swap" ] &&
   grep -q "previous is a directory, not a record: nothing changed; remove it" "$work/out"; then
	ok "recalibrate with a directory as the previous record: exit $rc, nothing changed, the reason given"
else
	not_ok "recalibrate with a directory as the previous record: exit $rc, journal $([ -e "$rec.previous.swap" ] && echo left || echo none): $(head -c 300 "$work/out")"
fi
rmdir "$rec.previous"
mv "$work/P.aside" "$rec.previous"
if run_sim rollback >/dev/null 2>&1 && same "$rec" "$work/P" && same "$rec.previous" "$work/R"; then
	ok "and once it is removed, rollback works"
else
	not_ok "and once it is removed, rollback works"
fi

[ "$n" -eq "$plan" ] || { echo "# planned $plan checks, made $n"; fail=$((fail + 1)); }
echo "# $hits save injection points, $pair_runs record-pair injections, $status_lies exit statuses not matching the disk, $fail failures"
[ $fail -eq 0 ]
