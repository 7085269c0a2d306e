#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# The factory test's JSON report against its schema (daemon/report.schema.json)
# with Debian's python3-jsonschema: the reports of passing runs (every
# option), of every fault of datasheet section 8 (stopping and with
# --keep-going), and of every tampered judgment of test_judgments all
# validate, have unique IDs and values consistent with their results; a
# passing run has every judgment of the application note under its own ID.
# Output is TAP.
# Usage: report.sh PATH-TO-as9888-calibd PATH-TO-test_judgments
set -u

calibd=${1:?usage: report.sh PATH-TO-as9888-calibd PATH-TO-test_judgments}
judgments=${2:?usage: report.sh PATH-TO-as9888-calibd PATH-TO-test_judgments}
top=$(cd "$(dirname "$0")/../.." && pwd)
schema=$top/daemon/report.schema.json
checker=$top/tests/daemon/report_check.py
python3 -c 'import jsonschema' 2>/dev/null ||
	{ echo "1..0 # SKIP python3-jsonschema is not installed (scripts/setup.sh installs it)"; exit 77; }
work=$(mktemp -d /tmp/as9888-report-XXXXXX)
trap 'rm -rf "$work"' EXIT
export ASAN_OPTIONS=detect_leaks=1
# shellcheck source=../lib/tap.sh
. "$(dirname "$0")/../lib/tap.sh"
tap_plan 22
TAP_SHOW="$work/check"

vt="--backend sim --sim-clock virtual"
# report NAME UNIT-TEXT [OPTIONS...]: run factory-test --json into $work/NAME.json
report() {
	local name=$1 unit=$2
	shift 2
	printf '%s\n' "$unit" >"$work/$name.unit"
	# shellcheck disable=SC2086
	"$calibd" factory-test $vt --record "$work/rec-$name" --unit "$work/$name.unit" \
		--json "$@" >"$work/$name.json" 2>"$work/$name.err"
}
valid() { python3 "$checker" "$schema" "$@" >"$work/check" 2>&1; }

report pass "seed = 3"
check "a passing report validates, with every judgment of the application note under its own ID" \
	valid --complete "$work/pass.json"
report lpf "noise = 1.5" --lpf --gravity z- --samples 16
report pe "noise = 2" --permissible-error 0.25
report side "up = -1 0 0" --fluctuation 20
report pc "noise = 2" --permissible-error 0.25 --confidence 0.95 --sequence note
check "passing reports with --lpf --gravity --samples, --permissible-error (--confidence), --fluctuation validate" \
	valid --complete "$work/lpf.json" "$work/pe.json" "$work/side.json" "$work/pc.json"
check "the error bound: one sigma by default, the stated probability with --confidence" python3 -c "
import json, sys
e = json.load(open('$work/pe.json')); c = json.load(open('$work/pc.json'))
a, b = e['error_bound'], c['error_bound']
ok = (a['mode'] == 'one_sigma' and abs(a['probability'] - 0.6827) < 1e-4 and a['z'] == 1 and
      b['mode'] == 'probability' and b['probability'] == 0.95 and abs(b['z'] - 1.96) < 1e-3 and
      c['options']['confidence'] == 0.95 and c['options']['sequence'] == 'note' and
      c['calibration']['samples'] > 3 * e['calibration']['samples'])
for r in (e, c):
    m, se, z = r['calibration']['level_mean'], r['error_bound']['standard_error'], r['error_bound']['z']
    ok = ok and all(abs(lo - (m[i] - z * se[i])) < 1e-4 and abs(hi - (m[i] + z * se[i])) < 1e-4 and 0 < se[i] < 0.25
                    for i, (lo, hi) in enumerate(r['error_bound']['interval']))
sys.exit(not ok)"
check "the operator's options are in the report" python3 -c "
import json, sys
d = json.load(open('$work/lpf.json')); o = d['options']
e = json.load(open('$work/pe.json'))['options']
sys.exit(not (o['lpf'] and o['gravity'] == 'z-' and o['samples'] == 16 and
              o['permissible_error'] is None and e['permissible_error'] == 0.25 and
              d['chip']['fingerprint'] == '676f64b435a720ba' and d['backend'] == 'sim'))"

faults="no_drdy int1_open int2_open rstn_open wia eeprom_blank stuck_x saturate_z nak selftest_weak hofl"
files=()
for f in $faults; do
	report "$f" "fault = $f"
	report "$f-kg" "fault = $f" --keep-going
	files+=("$work/$f.json" "$work/$f-kg.json")
done
check "the reports of every fault, stopping and with --keep-going, validate" valid "${files[@]}"
check "every fault's report says fail" python3 -c "
import json, sys
sys.exit(any(json.load(open(f))['result'] != 'fail' for f in sys.argv[1:]))" "${files[@]}"

# JUnit XML (--junit FILE): the same judgments, for dashboards and CI
report junit-pass "seed = 3" --junit "$work/pass.xml"
report junit-fail "fault = saturate_z" --keep-going --junit "$work/fail.xml"
junit_matches() {
	python3 - "$1" "$2" <<'PY'
import json, sys
import xml.etree.ElementTree as ET
x, j = ET.parse(sys.argv[1]).getroot(), json.load(open(sys.argv[2]))
suite = x.find("testsuite")
cases = suite.findall("testcase")
failed = [c for c in cases if c.find("failure") is not None]
skipped = [c for c in cases if c.find("skipped") is not None]
want_failed = [s["id"] for s in j["steps"] if s["result"] == "fail"]
props = {p.get("name"): p.get("value") for p in suite.find("properties")}
ok = (len(cases) == len(j["steps"]) == int(suite.get("tests")) == int(x.get("tests")) and
      len(failed) == int(suite.get("failures")) and len(skipped) == int(suite.get("skipped")) and
      [c.get("name").split()[0] for c in failed] == want_failed and
      [c.get("name").split()[0] for c in cases] == [s["id"] for s in j["steps"]] and
      props["backend"] == j["backend"] and props["chip"] == j["chip"]["fingerprint"])
sys.exit(0 if ok else 1)
PY
}
check "--junit: well-formed JUnit XML, one testcase per judgment, none failed on a pass" \
	eval 'junit_matches "$work/pass.xml" "$work/junit-pass.json" && grep -q "failures=\"0\"" "$work/pass.xml"'
check "--junit: a failing run's failures are the JSON report's, in order (3-12 first)" \
	eval 'junit_matches "$work/fail.xml" "$work/junit-fail.json" && grep -q "<testcase classname=\"step 3-12\" name=\"3-12 Z below 2047 on every sample\" time=\"0\">" "$work/fail.xml"'
"$calibd" factory-test $vt --record "$work/rec-x" --junit "$work/no/such/dir/x.xml" >"$work/junit.out" 2>"$work/junit.err"
rc=$?
check "--junit to a path that cannot be written: exit 1 before the test, said, no record" \
	eval '[ $rc -eq 1 ] && grep -q "cannot write the JUnit report: cannot open directory $work/no/such/dir" "$work/junit.err" &&
	      [ ! -s "$work/junit.out" ] && [ ! -e "$work/rec-x" ]'

# Jenkins' rules for JUnit XML (tests/daemon/junit.xsd restates junit-10.xsd):
# both reports validate, and a report with "skipped" on <testsuites> would not
junit_schema=$top/tests/daemon/junit.xsd
xsd_valid() { xmllint --noout --schema "$junit_schema" "$@" >"$work/check" 2>&1; }
if command -v xmllint >/dev/null; then
	check "--junit: the passing and the failing run's XML validate against Jenkins' junit-10 rules (xmllint)" \
		xsd_valid "$work/pass.xml" "$work/fail.xml"
	sed 's/<testsuites \(.*\) errors=/<testsuites \1 skipped="0" errors=/' "$work/fail.xml" >"$work/skipped.xml"
	check "the schema refuses \"skipped\" on <testsuites> (the check can fail)" \
		eval '! xsd_valid "$work/skipped.xml" && grep -q "attribute .skipped.: The attribute .skipped. is not allowed" "$work/check"'
	check "--junit: a failure has a type and the suite a hostname (the Ant schema wants both)" \
		eval 'grep -q "<failure type=\"as9888.judgment\" message=" "$work/fail.xml" &&
		      grep -q "<testsuite [^>]* hostname=\"[^\"]" "$work/fail.xml"'
else
	check "xmllint is installed (libxml2-utils; scripts/setup.sh installs it)" false
fi

# --junit never writes through a symbolic link or into anything but its own
# report (issue 25, point 5): a planted link, a device, a FIFO, another
# file, a hard link are refused before the test, and nothing is changed
junit_refused() {
	local target=$1
	shift
	rm -f "$work/rec-j"
	timeout 60 "$calibd" factory-test $vt --record "$work/rec-j" --junit "$target" \
		>"$work/junit.out" 2>"$work/junit.err"
	rc=$?
	[ $rc -eq 1 ] && [ ! -s "$work/junit.out" ] && [ ! -e "$work/rec-j" ] &&
		grep -q "cannot write the JUnit report: .*$1" "$work/junit.err"
}
printf 'root:secret:1:0:99999:7:::\n' >"$work/victim"
cp "$work/victim" "$work/victim.orig"
ln -s "$work/victim" "$work/link.xml"
check "--junit through a planted symbolic link: refused before the test, its target untouched" \
	eval 'junit_refused "$work/link.xml" "is a symbolic link" && cmp -s "$work/victim" "$work/victim.orig" &&
	      [ -L "$work/link.xml" ]'
check "--junit naming another file (not a report): refused, the file untouched" \
	eval 'junit_refused "$work/victim" "not a JUnit report" && cmp -s "$work/victim" "$work/victim.orig"'
check "--junit naming a device: refused" junit_refused /dev/null "not a regular file"
mkfifo "$work/fifo.xml"
check "--junit naming a FIFO: refused without waiting for a reader" \
	junit_refused "$work/fifo.xml" "not a regular file"
cp "$work/pass.xml" "$work/old.xml"
ln "$work/old.xml" "$work/hardlink.xml"
check "--junit naming a report with another hard link: refused, unchanged" \
	eval 'junit_refused "$work/hardlink.xml" "other hard links" && cmp -s "$work/old.xml" "$work/pass.xml"'
rm -f "$work/hardlink.xml"
# a temporary file of another user in the way (a shared, sticky
# directory): not removed, the run refused
echo theirs >"$work/theirs.xml.new"
chown 65534:65534 "$work/theirs.xml.new"
check "--junit with another user's <report>.new in the way: refused, their file kept" \
	eval 'junit_refused "$work/theirs.xml" "not a file of ours" && [ "$(cat "$work/theirs.xml.new")" = theirs ]'
report again "fault = saturate_z" --junit "$work/old.xml"
check "--junit naming an older report: replaced by the new one, no temporary file left" \
	eval 'grep -q "failures=\"[1-9]" "$work/old.xml" && [ ! -e "$work/old.xml.new" ] &&
	      [ "$(stat -c %a "$work/old.xml")" = 644 ]'

mkdir -p "$work/tampered"
AS9888_REPORT_DIR=$work/tampered "$judgments" >"$work/judgments.log" 2>&1
check "test_judgments ran and left a report per tampered judgment" \
	test "$(find "$work/tampered" -name '*.json' | wc -l)" -gt 40
check "the report of every tampered judgment validates" valid "$work"/tampered/*.json

# the checker itself sees a bad report
python3 - "$work/pass.json" "$work/broken.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["steps"][1]["id"] = d["steps"][0]["id"]
j = [s for s in d["steps"] if s["low"] is not None and s["result"] == "pass"][3]
j["value"] = j["low"] - 1
json.dump(d, open(sys.argv[2], "w"))
PY
check "a report with a repeated ID and a value outside its passing limits is refused" \
	eval '! valid "$work/broken.json" && grep -q "not unique" "$work/check" && grep -q "but result pass" "$work/check"'

tap_end
