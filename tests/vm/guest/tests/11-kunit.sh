# SPDX-License-Identifier: GPL-2.0
# The driver's KUnit suite (as9888_calib_kunit.c: the calibration
# arithmetic) in this kernel, the same build as the driver under test:
# the module runs the suite when it loads and prints its results in KTAP
# to the kernel log, which this file reads (not KUnit's debugfs results:
# 6.1 keeps 512 bytes a test case there, and a parameterised case's
# results are cut off). One check a test case, so the plan is the number
# of KUNIT_CASE entries of the source (the host writes it to
# /tests/kunit-cases when it packs the initramfs); a parameterised case
# passes when every parameter passed (the count of each is a diagnostic).
# A case that did not run, or a suite that reports fewer cases, fails.
KU_CASES=$(cat /tests/kunit-cases 2>/dev/null)
is_int "$KU_CASES" || KU_CASES=1
plan $((KU_CASES + 3))
KU_KO=$MODDIR/as9888_calib_kunit.ko

# the kernel log from here on: the suite's KTAP, without the timestamps
_ku_from=$(dmesg | wc -l)
if insmod $KU_KO; then
	ok "kunit: as9888_calib_kunit.ko loads (its suite runs at load)"
else
	bail_rest "as9888_calib_kunit.ko did not load"
	return 0
fi
dmesg | tail -n +$((_ku_from + 1)) | sed 's/^\[[^]]*\] //' >/tmp/kunit.ktap
rmmod as9888_calib_kunit

# ku_cases: "RESULT NAME PARAMS_PASSED PARAMS_FAILED" for every case (the
# result lines one level below the suite's own), in order; RESULT is ok,
# fail or skip
ku_cases() {
	awk '
	function indent(s) { match(s, /^ */); return RLENGTH }
	/^ *(not )?ok [0-9]+ / {
		d = indent($0); line = $0; sub(/^ */, "", line)
		res = (line ~ /^not ok/) ? "fail" : "ok"
		if (line ~ /# SKIP/) res = "skip"
		sub(/^(not )?ok [0-9]+ /, "", line); sub(/ *#.*$/, "", line)
		n++; D[n] = d; R[n] = res; N[n] = line
	}
	END {
		# the suite: the shallowest result; its cases: the next level
		s = -1
		for (i = 1; i <= n; i++) if (s < 0 || D[i] < s) s = D[i]
		c = -1
		for (i = 1; i <= n; i++) if (D[i] > s && (c < 0 || D[i] < c)) c = D[i]
		pp = 0; pf = 0
		for (i = 1; i <= n; i++) {
			if (D[i] > c) { if (R[i] == "fail") pf++; else pp++; continue }
			if (D[i] == c) { print R[i], N[i], pp, pf; pp = 0; pf = 0 }
		}
	}' /tmp/kunit.ktap
}
ku_cases >/tmp/kunit.cases
KU_SUITE=$(grep -E '^(not )?ok [0-9]+ as9888-calib$' /tmp/kunit.ktap | head -n 1)
eq "kunit: the suite's own verdict" "${KU_SUITE%% [0-9]*}" ok
eq "kunit: every case of the source ran" "$(wc -l </tmp/kunit.cases)" "$KU_CASES"
KU_PARAMS=0
_ku_i=0
while read -r _r _n _pp _pf; do
	_ku_i=$((_ku_i + 1))
	[ $_ku_i -le "$KU_CASES" ] || break
	KU_PARAMS=$((KU_PARAMS + _pp + _pf))
	_ku_p=""
	[ $((_pp + _pf)) -eq 0 ] || _ku_p=" ($_pp of $((_pp + _pf)) parameters passed)"
	case $_r in
	ok) ok "kunit: $_n$_ku_p" ;;
	skip) skip "kunit: $_n" "skipped by the suite" ;;
	*) nok "kunit: $_n$_ku_p" "$(grep -E "# $_n: |EXPECTATION FAILED|ASSERTION FAILED" /tmp/kunit.ktap | head -n 5)" ;;
	esac
done </tmp/kunit.cases
# cases the suite did not report: failed, so the plan holds
while [ $_ku_i -lt "$KU_CASES" ]; do
	_ku_i=$((_ku_i + 1))
	nok "kunit: case $_ku_i of $KU_CASES not reported by the suite"
done
diag "kunit: $(wc -l </tmp/kunit.cases) cases, $KU_PARAMS parameter runs in them"
