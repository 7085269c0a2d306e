#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# as9888-calibd magn-calibrate on the simulator (virtual clock): a board
# with hard and soft iron turned by the model's tumble is calibrated and
# the stored hard iron and soft iron are compared with the unit's truth;
# --earth-field makes the stored field the site's; a device lying still
# and an implausible field fail with a clear message and leave the record
# as it was; a passing magnet's samples are rejected and the result stays
# right; a slow weak magnet leaves the result right or is refused with
# the record as it was; the options are checked. Output is TAP.
set -u

calibd=${1:?usage: magn_calibrate.sh PATH-TO-as9888-calibd}
calibd=$(realpath "$calibd")
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/as9888-magncal-XXXXXX)
export ASAN_OPTIONS=detect_leaks=1
trap 'rm -rf "$work"' EXIT
# shellcheck source=../lib/tap.sh
. "$here/../lib/tap.sh"
# shellcheck source=../lib/record.sh
. "$here/../lib/record.sh"
tap_plan 30
TAP_SHOW="$work/err $work/out"
mkdir -p "$work/sys"
export AS9888_SYSFS=$work/sys

rec=$work/state/calibration
# the factory test's record: the built-in unit lying still (its EEPROM is
# the same chip's as every unit below, which give none)
"$calibd" factory-test --sim-clock virtual --unit /dev/null --record "$rec" >/dev/null ||
	{ echo "Bail out! no factory record"; exit 1; }
cp "$rec" "$work/factory"

# a board: Earth 48 uT dipping 60 deg, hard iron, soft iron with cross terms
cat >"$work/board.unit" <<'UNIT'
earth = 48 60 3
hard_iron = 120 -80 45
soft_iron = 1.05 0.03 -0.02 0.03 0.95 0.04 -0.02 0.04 1.02
magn_noise = 0.4
tumble = 4
UNIT

run magn-calibrate --sim-clock virtual --unit "$work/board.unit" --record "$rec"
check "a tumbling board: exit 0, progress shown, stored" eval '[ $rc -eq 0 ] &&
	says "^coverage .*%, [0-9]* samples kept" out && says "^Stored in" out'
check "the progress lines say which way to turn to cover more (the chip's axis, its sense, how far)" \
	says "^coverage .*%, [0-9]* samples kept; to cover more: turn it about the chip's [XYZ] axis, +[XYZ] toward [+-][XYZ], about [0-9]* deg$" out
cp "$work/out" "$work/first.out"
check "the record stays format 1, key for key the factory record (what an older build reads), the calibration in its .magn file, the factory record kept as previous" eval '
	grep -q "^format = as9888-calibration 1$" "$rec" && cmp -s "$rec.previous" "$work/factory" &&
	grep -q "^format = as9888-magnetometer 1$" "$rec.magn" && ! grep -q magn_ "$rec" &&
	diff <(grep -v "^created\|^crc32" "$rec") <(grep -v "^created\|^crc32" "$work/factory") >/dev/null'
check "hard iron within 1 uT and soft iron within 1% of the unit's truth" \
	python3 - "$rec.magn" <<'PY'
import sys
keys = dict(l.split(" = ", 1) for l in open(sys.argv[1]).read().splitlines()
            if " = " in l)
b = [float(v) for v in keys["magn_hard_iron"].split()]
w = [float(v) for v in keys["magn_soft_iron"].split()]
W = [w[0:3], w[3:6], w[6:9]]
S = [[1.05, 0.03, -0.02], [0.03, 0.95, 0.04], [-0.02, 0.04, 1.02]]
h = [120, -80, 45]
err_b = max(abs(b[i] - h[i]) for i in range(3))
M = [[sum(W[i][k] * S[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
det = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
       - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
       + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
k = det ** (1 / 3)
err_w = max(abs(M[i][j] / k - (i == j)) for i in range(3) for j in range(3))
print(f"# hard iron off by {err_b:.3f} uT, W*S off the identity by {err_w:.4f}")
field = float(keys["magn_field"])
# W is normalised to det 1: the fitted field is 48 uT times S's mean gain
assert 40 < field < 56, field
assert err_b < 1.0 and err_w < 0.01, (b, W)
PY

# the site's field (--earth-field, the WMM's figure) as the calibrated
# magnitude: the same session, W scaled so the stored field is the
# reference; the fit's own field and the scale are shown
cp "$rec.magn" "$work/plain"
run magn-calibrate --sim-clock virtual --unit "$work/board.unit" --earth-field 48.5 --record "$rec"
check "--earth-field 48.5: exit 0, says the scale, stored" eval '[ $rc -eq 0 ] &&
	says "the site.s field: the fit saw [0-9.]* uT, W scaled by" out && says "^Stored in" out'
check "--earth-field 48.5: the stored field is 48.5 uT, W the fit's times the scale, the hard iron the same" \
	python3 - "$work/plain" "$rec.magn" <<'PY'
import sys
def keys(path):
    return dict(l.split(" = ", 1) for l in open(path).read().splitlines()
                if " = " in l)
plain, ref = keys(sys.argv[1]), keys(sys.argv[2])
f0, f1 = float(plain["magn_field"]), float(ref["magn_field"])
print(f"# field without the reference {f0} uT, with it {f1} uT")
assert abs(f1 - 48.5) < 0.0015 and abs(f0 - 48.5) > 0.05, (f0, f1)
w0 = [float(v) for v in plain["magn_soft_iron"].split()]
w1 = [float(v) for v in ref["magn_soft_iron"].split()]
assert all(abs(b - a * f1 / f0) < 1e-5 for a, b in zip(w0, w1)), (w0, w1)
assert plain["magn_hard_iron"] == ref["magn_hard_iron"]
PY
cp "$rec" "$work/before"
cp "$rec.magn" "$work/before.magn"
cp "$rec.previous" "$work/before.previous"
for bad in 19.9 70.001 abc -48 "" 48uT; do
	run magn-calibrate --sim-clock virtual --unit "$work/board.unit" --earth-field "$bad" --record "$rec"
	check "--earth-field \"$bad\": a usage error, says the range, nothing written" eval '
		[ $rc -eq 2 ] && says "earth-field takes the site.s field strength in uT, 20..70" err &&
		! says "Turn the device" out &&
		cmp -s "$rec" "$work/before" && cmp -s "$rec.magn" "$work/before.magn" && cmp -s "$rec.previous" "$work/before.previous"'
done

# failures leave the record as it was
cp "$rec" "$work/before"
cp "$rec.magn" "$work/before.magn"
run magn-calibrate --sim-clock virtual --unit /dev/null --timeout 20 --record "$rec"
check "a device lying still: exit 1 after the timeout, says to turn it, record unchanged" eval '
	[ $rc -eq 1 ] && says "not enough orientations covered" err &&
	says "record is unchanged" err && cmp -s "$rec" "$work/before" && cmp -s "$rec.magn" "$work/before.magn"'

# turned 0.3 degrees a measurement (1.5 a sample of five), the session's
# 60 s cover about 43 % of the sphere: magcal's own floor (40 %) passes,
# the session's 55 % does not, and the fit at the timeout is held to the
# session's rule (before: stored, exit 0; such fits were found degrees off)
sed 's/^tumble = 4$/tumble = 0.3/' "$work/board.unit" >"$work/crawl.unit"
run magn-calibrate --sim-clock virtual --unit "$work/crawl.unit" --timeout 60 --record "$rec"
check "too little covered at the timeout, though magcal would fit it: exit 1, the coverage said, record unchanged" eval '
	[ $rc -eq 1 ] && says "not enough orientations covered (4[0-9]% in 60 s" err &&
	says "record is unchanged" err && cmp -s "$rec" "$work/before" && cmp -s "$rec.magn" "$work/before.magn"'

sed 's/^earth = 48/earth = 110/' "$work/board.unit" >"$work/strong.unit"
run magn-calibrate --sim-clock virtual --unit "$work/strong.unit" --timeout 60 --record "$rec"
check "a 110 uT field: exit 1, not the Earth's, record unchanged" eval '
	[ $rc -eq 1 ] && says "is not the Earth" err && cmp -s "$rec" "$work/before" && cmp -s "$rec.magn" "$work/before.magn"'

# a magnet passing during the session: its samples rejected as outliers
# and the result still right (on the virtual clock the session is the same
# every run, so this is the one outcome). A faster tumble ends the session
# before the fit's 300 samples are full, so that the magnet's 20 stay in it
# (with the board's 4 degrees they would be pushed out: nothing to reject)
sed 's/^tumble = 4$/tumble = 12/' "$work/board.unit" >"$work/magnet.unit"
printf 'disturbance = 300 -200 150 20\n' >>"$work/magnet.unit"
run magn-calibrate --sim-clock virtual --unit "$work/magnet.unit" --timeout 60 --record "$rec"
check "a passing magnet: its samples rejected, exit 0" eval '
	[ $rc -eq 0 ] && grep -q "samples used, [1-9][0-9]* rejected" "$work/out"'
check "a passing magnet: the stored hard iron is still within 1 uT" \
	python3 -c '
import sys
keys = dict(l.split(" = ", 1) for l in open(sys.argv[1]).read().splitlines() if " = " in l)
b = [float(v) for v in keys["magn_hard_iron"].split()]
assert max(abs(x - y) for x, y in zip(b, [120, -80, 45])) < 1.0, b' "$rec.magn"

# a weak magnet moving slowly past (17.6 uT peak over 2950 measurements,
# 38 s at the session's 5 measurements every 64.5 ms on the simulator's
# clock, from the start: a phone's speaker, a laptop's hinge), which a
# fit absorbs into
# the hard iron (before the store and the gate of issue 39 it was stored
# 9.6 uT off): the gate refuses the fits while the magnet's samples are
# in the store, the store replaces them as the turning goes on, and the
# stored hard iron is the board's
cp "$work/board.unit" "$work/slow.unit"
printf 'disturbance = 10 -12 8 2950\n' >>"$work/slow.unit"
cp "$rec" "$work/before"
cp "$rec.magn" "$work/before.magn"
run magn-calibrate --sim-clock virtual --unit "$work/slow.unit" --record "$rec"
check "a slow weak magnet: said while it lasts, exit 0, the stored hard iron within 1 uT" eval '
	[ $rc -eq 0 ] && says "^the field is changing" out && python3 -c "
import sys
keys = dict(l.split(\" = \", 1) for l in open(sys.argv[1]).read().splitlines() if \" = \" in l)
b = [float(v) for v in keys[\"magn_hard_iron\"].split()]
assert max(abs(x - y) for x, y in zip(b, [120, -80, 45])) < 1.0, b" "$rec.magn"'
# the same magnet, slower (6000 measurements, 77 s) and a session of 15 s,
# which ends while it is there (before: stored 4 uT off), the board turned
# 10 degrees a sample (2 a measurement: at 4 the session covers 57 % in
# 5 s, before the gate can see the slow rise): refused, the record
# unchanged
sed 's/^disturbance = .*/disturbance = 10 -12 8 6000/; s/^tumble = 4$/tumble = 2/' \
	"$work/slow.unit" >"$work/slower.unit"
cp "$rec" "$work/before"
cp "$rec.magn" "$work/before.magn"
run magn-calibrate --sim-clock virtual --unit "$work/slower.unit" --timeout 15 --record "$rec"
check "a slow magnet through the whole session: exit 1, the field changed, record unchanged" eval '
	[ $rc -eq 1 ] && says "the field changed during the session" err &&
	cmp -s "$rec" "$work/before" && cmp -s "$rec.magn" "$work/before.magn"'
# a weaker one (6.4 uT peak over 6000 measurements) drifts the field's
# strength by 0.33 uT and its dip by 0.41 deg: under magcal's default
# limits (0.4 uT, 0.6 deg) it was stored after 10.6 s with the hard iron
# 1.1 uT off; the session's own limit on the strength (0.1 uT) refuses it
sed 's/^disturbance = .*/disturbance = 4 -4 3 6000/' "$work/slower.unit" >"$work/weaker.unit"
run magn-calibrate --sim-clock virtual --unit "$work/weaker.unit" --record "$rec"
check "a weak slow magnet: exit 1, its strength drifted beyond the session's 0.10 uT, record unchanged" eval '
	[ $rc -eq 1 ] && says "the field changed during the session (its strength drifted by 0\.[1-9][0-9] uT.*at most 0\.10 uT" err &&
	cmp -s "$rec" "$work/before" && cmp -s "$rec.magn" "$work/before.magn"'

# the board's soft iron turned by 2 deg about Z (S' = Rz S: asymmetric,
# which the record's symmetric W cannot hold): stored, and the turn seen
# against the accelerometer is said (the tumbling board above says none)
sed 's/^soft_iron = .*/soft_iron = 1.048313 -0.003173 -0.021384 0.066626 0.950468 0.039278 -0.020000 0.040000 1.020000/' \
	"$work/board.unit" >"$work/turned.unit"
grep -q "turned by" "$work/first.out" && first_turn=1 || first_turn=0
cp "$rec" "$work/before-turned"
cp "$rec.magn" "$work/before-turned.magn"
run magn-calibrate --sim-clock virtual --unit "$work/turned.unit" --record "$rec"
check "a soft iron turned by 2 deg: stored, the turn of 1.5..2.5 deg said, stored as magn_rotation (issue 39 point 5)" eval '
	[ $rc -eq 0 ] && [ $first_turn -eq 0 ] && says "turn against the accelerometer .* stored" out &&
	python3 -c "
import math, re, sys
m = re.search(r\"field turned by ([0-9.]+) deg against the accelerometer\", open(sys.argv[1]).read())
assert m and 1.5 <= float(m.group(1)) <= 2.5, m
keys = dict(l.split(\" = \", 1) for l in open(sys.argv[2]).read().splitlines() if \" = \" in l)
r = [float(v) for v in keys[\"magn_rotation\"].split()]
deg = math.degrees(math.acos((r[0] + r[4] + r[8] - 1) / 2))
print(\"# stored turn %.3f deg\" % deg)
assert 1.5 <= deg <= 2.5, r" "$work/out" "$rec.magn"'

run show --json --record "$rec"
check "show of the turned board: its turn, Rrot W and the HAL's bias Rrot W b" python3 - "$work/out" "$rec.magn" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["magnetometer"]
keys = dict(l.split(" = ", 1) for l in open(sys.argv[2]).read().splitlines() if " = " in l)
r = [float(v) for v in keys["magn_rotation"].split()]
R = [r[0:3], r[3:6], r[6:9]]
W, b = d["soft_iron"], d["hard_iron"]
assert all(abs(d["rotation"][i][j] - R[i][j]) < 1e-6 for i in range(3) for j in range(3)), d
assert abs(R[0][1]) > 0.01, R	# turned about Z: not the identity
RW = [[sum(R[i][k] * W[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
assert all(abs(d["correction"][i][j] - RW[i][j]) < 1e-6 for i in range(3) for j in range(3)), d
hal = [sum(RW[i][j] * b[j] for j in range(3)) for i in range(3)]
assert all(abs(hal[i] - d["hal_bias"][i]) < 1e-5 for i in range(3)), (hal, d)
PY

# rollback takes both files one change back and says so; a second one
# brings the turned board's calibration back
cp "$rec.magn" "$work/turned.magn"
run rollback --sim-clock virtual --record "$rec"
check "rollback: the record and its .magn file as before the last magn-calibrate, both said" eval '
	[ $rc -eq 0 ] && says "^Rolled back: .*calibration.magn holds the magnetometer" out &&
	cmp -s "$rec" "$work/before-turned" && cmp -s "$rec.magn" "$work/before-turned.magn" &&
	cmp -s "$rec.magn.previous" "$work/turned.magn"'
run rollback --sim-clock virtual --record "$rec"
check "a second rollback: the turned board's calibration again" eval '
	[ $rc -eq 0 ] && cmp -s "$rec.magn" "$work/turned.magn" &&
	cmp -s "$rec.magn.previous" "$work/before-turned.magn"'

# through the driver (a sysfs tree like its own, readings that never
# change: a device lying still), in real time
sys=$work/sys
bus=$sys/devices/i2c/1-000c
mkdir -p "$bus/iio:device0" "$bus/iio:device1" "$bus/as9888-eeprom0" "$sys/bus/iio/devices"
ln -s ../../../devices/i2c/1-000c/iio:device0 "$sys/bus/iio/devices/iio:device0"
ln -s ../../../devices/i2c/1-000c/iio:device1 "$sys/bus/iio/devices/iio:device1"
printf 'as9888-accel\n' >"$bus/iio:device0/name"
printf 'as9888-magn\n' >"$bus/iio:device1/name"
printf '\x9a\x71\x15\x5c\x80\x85\x7b\x1c\x63\xa2\x38\xe6\x9c\x0d\x8f\x8c\x04\x65\xc3\x88\x50' \
	>"$bus/as9888-eeprom0/nvmem"
for a in x y z; do
	echo 100 >"$bus/iio:device1/in_magn_${a}_raw"
	echo 5 >"$bus/iio:device0/in_accel_${a}_raw"
	echo 0 >"$bus/iio:device0/in_accel_${a}_calibbias"
done
echo 256 >"$bus/iio:device0/in_accel_z_raw"
run magn-calibrate --backend iio --timeout 2 --record "$rec"
check "through the driver, a simulator's record: refused before anything is measured" eval '
	[ $rc -eq 1 ] && says "written by a factory test on the simulator" err &&
	! says "orientations" err'
# the same record as a chip's (its source line taken out, re-sealed)
sed -i '/^source = simulator$/d' "$rec" && record_reseal "$rec"
cp "$rec" "$work/before"
cp "$rec.magn" "$work/before.magn"
run magn-calibrate --backend iio --timeout 2 --record "$rec"
check "through the driver, a device lying still: exit 1, not enough orientations, record unchanged" eval '
	[ $rc -eq 1 ] && says "not enough orientations covered" err && cmp -s "$rec" "$work/before" && cmp -s "$rec.magn" "$work/before.magn"'
printf '\x01' | dd of="$bus/as9888-eeprom0/nvmem" bs=1 seek=4 conv=notrunc status=none
run magn-calibrate --backend iio --timeout 2 --record "$rec"
check "through the driver, another chip: refused before sampling, says to run factory-test" eval '
	[ $rc -eq 1 ] && says "run factory-test on this unit first" err && ! says "orientations" err'
rm -rf "$bus/iio:device1" "$sys/bus/iio/devices/iio:device1"
run magn-calibrate --backend iio --timeout 2 --record "$rec"
check "through a driver without the magnetometer device: exit 1, says so" eval '
	[ $rc -eq 1 ] && says "no as9888-magn IIO device" err'

run magn-calibrate --sim-clock virtual --unit /dev/null --timeout 0 --record "$rec"
check "--timeout 0 is a usage error" eval '[ $rc -eq 2 ] && says "timeout takes seconds 1..3600" err'
run magn-calibrate --sim-clock virtual --unit /dev/null --record "$work/none"
check "no factory record: exit 1, says to run factory-test" eval '
	[ $rc -eq 1 ] && says "run factory-test first" err'
tap_end
