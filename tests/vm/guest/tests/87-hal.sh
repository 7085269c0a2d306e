# SPDX-License-Identifier: GPL-2.0
# The sensors HAL's core (hal/, issue 36) against the real driver, through
# its own API: as9888-hal-cat makes the calls the Android adapter makes
# (list, batch, activate, flush, deactivate) and prints the events with
# the CLOCK_BOOTTIME at which each reached it.
#  - the sensor list: three sensors, the accelerometer's minDelay from
#    sampling_frequency_available (400 Hz: 2500 us);
#  - accelerometer and magnetometer together at unequal rates (100 + 10,
#    50 + 20 Hz, rates the device offers, and 33.3 + 20 Hz: the
#    accelerometer asked every 30 ms, which the device does not offer):
#    while they run, each device's sampling_frequency is the asked rate,
#    or the next faster one offered (50 Hz for 33.3, the HAL thinning it:
#    a HAL that passes every sample delivers 50 Hz, 50 % over); each
#    sensor delivers, counted from the events' own timestamps,
#    never more than 10 % over its rate, and at least 60 % of it. A TCG
#    guest on a busy host delivers less than asked, never more (as
#    69-trigger-rates), so a rate 10 to 40 % under is logged as a
#    diagnostic, not failed; under 60 % fails, for what a broken HAL
#    delivers: half or less (every other sample dropped, or the device set
#    to its next lower rate: 50 of 100, 10 of 20, 20 of 50 Hz). Event
#    times strictly increase per sensor and are CLOCK_BOOTTIME's
#    (current_timestamp_clock): none later than its arrival at the HAL (an
#    event stamped on another clock is hours, or years, off). The
#    issue's "within 20 ms of CLOCK_BOOTTIME", the time from an event's
#    timestamp to its arrival at the HAL: the median within 20 ms (beyond
#    it, the HAL holds events back: a watermark above 1, a queue drained
#    late) and the 99th percentile within 150 ms (beyond it, the HAL holds
#    the running device's samples through the other device's set-up,
#    which the median cannot see); a 95th or 99th percentile beyond 20 ms
#    is logged with the late events (when, how late). Not every event
#    within 20 ms: the guest's one vCPU runs a debug kernel under TCG,
#    and while the second device starts or stops (its buffer enable, the
#    chip's mode change under the chip's lock) the running device's
#    samples wait in the kernel. Figures, judgment: docs/DECISIONS.md,
#    "Session 17: the set-up off the reader thread; the arrival judged";
#  - after deactivation both buffers are off and the chip powers down
#    (runtime suspended, 2 s autosuspend; 30 s is a stall);
#  - a flush's flush-complete comes after the events before it, within
#    100 ms (logged beyond that) and never later than 1 s (fails: a flush
#    kept until some later event or timeout);
#  - a max report latency of 500 ms: events held back (the longest wait
#    at least 300 ms; beyond 700 ms logged, beyond 2 s it fails: a queue
#    kept until it fills or the sensor stops) and delivered in order;
#  - at rest, with noise 0, in the six device-frame postures (+-x, +-y,
#    +-z up) at -20, 25 and 70 degC: the mean event is 9.80665 m/s^2
#    within 0.5 % and points up in Android's frame, through the adapter's
#    mount matrix (0 1 0; -1 0 0; 0 0 1, not the identity).
#  - the compass on lib.sh's magnetic board (hard iron MAGN_HARD, soft
#    iron, the Earth's field MAGN_TRUE in the sensor frame when level),
#    its factory test first (as 89): magn-calibrate through the driver
#    with the board tumbling a degree a measurement stores a
#    calibration (the driver's calibbias and calibscale, the record's
#    residual); at rest and level again, the HAL with that record gives,
#    for every sample, uncalibrated - bias = calibrated (0.001 uT, the
#    printed precision) with accuracy high; the bias is the hard iron as
#    the calibrated field sees it, in Android's frame (M W MAGN_HARD, W =
#    S^-1 the soft iron's inverse, M the magnetometer's mount matrix;
#    within 3 uT: the fit's); the calibrated field's heading is the true
#    field's (M MAGN_TRUE) within 3 degrees and its magnitude 48 uT within
#    5 %, and the uncalibrated field's is not (the check can fail).
plan 50
HAL=/bin/as9888-hal-cat
W=/tmp/hal
G=9.80665
mkdir -p $W
load_sim
load_driver
dev_stale
printf '%s\n' "temperature = 25" "noise = 0" "field = 20 -5 -40" > $SIM/unit
check "unit: healthy, level, noise 0" wait_dev 5

# hal ARGS...: the core without a record or a daemon to feed
hal() { $HAL --record "" --socket "" "$@"; }

hal --list > $W/list 2> $W/list.err
eq "list: three sensors" "$(grep -c '^sensor ' $W/list)" 3
eq "list: the accelerometer's minDelay is 2500 us (400 Hz)" \
	"$(awk '$1 == "sensor" && $2 == 1 { print $4 }' $W/list)" 2500

# rate_mhz FILE HANDLE: the sensor's rate from its events' timestamps, mHz
rate_mhz() {
	awk -v h="$2" '$1 == "ev" && $2 == h { if (!n++) f = $4; l = $4 }
		END { if (n > 1 && l > f) printf "%.0f", (n - 1) * 1e12 / (l - f) }' "$1"
}
# increasing FILE: every sensor's timestamps strictly increase
increasing() {
	awk '$1 == "ev" { if (($2 in last) && $4 <= last[$2]) bad++; last[$2] = $4; n++ }
		END { exit (n < 2 || bad) }' "$1"
}
# lags FILE: the times from the events' timestamps to the HAL, ms:
# "FEWEST MEDIAN P95 P99 MOST" ("none" without events)
lags() {
	awk '$1 == "ev" { print ($5 - $4) / 1e6 }' "$1" | sort -n | awk '{ v[n++] = $1 }
		END { if (!n) { print "none"; exit }
		      printf "%.0f %.0f %.0f %.0f %.0f\n", v[0], v[int(n / 2)], v[int(n * 0.95)],
			     v[int(n * 0.99)], v[n - 1] }'
}
# late FILE: the events that reached the HAL more than 20 ms after their
# timestamps: "N of M", then up to 12 of them as HANDLE@AT:LAG (AT: ms
# after the first event's timestamp, LAG: ms)
late() {
	awk '$1 == "ev" { if (!n++) f = $4; l = ($5 - $4) / 1e6
		if (l > 20) { if (k++ < 12) s = s sprintf(" %d@%.0f:%.0f", $2, ($4 - f) / 1e6, l) } }
		END { printf "%d of %d%s\n", k, n, s }' "$1"
}
# clock_ok "FEWEST MEDIAN P95 P99 MOST": the timestamps are
# CLOCK_BOOTTIME's (none after its arrival), the median arrival within
# 20 ms and the 99th percentile within 150 ms; a 95th or 99th percentile
# beyond 20 ms is said
clock_ok() {
	[ "$1" != none ] && [ "$1" -ge 0 ] && [ "$2" -le 20 ] && [ "$4" -le 150 ] || return 1
	if [ "$3" -gt 20 ] || [ "$4" -gt 20 ]; then
		diag "arrival p95 $3 ms, p99 $4 ms: beyond 20 ms (the other device's start, a busy host)"
	fi
}

# rate_ok FILE HANDLE HZ NAME TAG: the sensor's rate at most 10 % over HZ
# and at least 60 % of it; 10 % under or more is said
rate_ok() {
	_r=$(rate_mhz $1 $2)
	diag "AS9888-METRIC hal_rate_$5_$4_mhz=${_r:-none} (asked $3 Hz)"
	check "$5 Hz: the $4 delivers ${_r:-no} mHz, asked $3 Hz (60 % .. +10 %)" \
		in_range "$_r" $(($3 * 600)) $(($3 * 1100))
	in_range "$_r" 1 $(($3 * 900 - 1)) &&
		diag "$5 Hz: the $4 more than 10 % slow: the guest did not keep up"
}
# in_range VALUE LOW HIGH: an integer within LOW..HIGH
in_range() { is_int "$1" && [ "$1" -ge "$2" ] && [ "$1" -le "$3" ]; }

# both_on: both devices' buffers run (30 s without: a stall)
both_on() {
	_bo=0
	until [ "$(cat $DEV/buffer/enable) $(cat $MDEV/buffer/enable)" = "1 1" ]; do
		[ $_bo -ge 300 ] && return 1
		sleep 0.1; _bo=$((_bo + 1))
	done
}

# pair ACC_HZ MAG_HZ [DEVICE_RATES]: both sensors for 4 s, each asked
# every 1000 / HZ ms (integer); DEVICE_RATES "ACC MAG": the devices'
# sampling_frequency then, when not the rates asked
pair() {
	_f=$W/pair-$1-$2
	hal --seconds 4 1:$((1000 / $1)) 2:$((1000 / $2)) > $_f 2> $_f.err &
	_pp=$!
	if both_on; then
		_hz="$(cat $DEV/sampling_frequency) $(cat $MDEV/sampling_frequency)"
	else
		_hz="buffers not both on in 30 s"
	fi
	wait $_pp
	eq "$1+$2 Hz: the devices' sampling_frequency while they run" "$_hz" "${3:-$1 $2}"
	[ -s $_f.err ] && diag "as9888-hal-cat: $(cat $_f.err)"
	rate_ok $_f 1 $1 accelerometer "$1+$2"
	rate_ok $_f 2 $2 magnetometer "$1+$2"
	check "$1+$2 Hz: event times strictly increase per sensor" increasing $_f
	_l=$(lags $_f)
	diag "AS9888-METRIC hal_lag_ms_$1_$2=$_l (fewest median p95 p99 most)"
	diag "beyond 20 ms at $1+$2 Hz: $(late "$_f")"
	check "$1+$2 Hz: event times on CLOCK_BOOTTIME: none after its arrival, median within 20 ms, p99 within 150 ms (ms: $_l)" \
		clock_ok $_l
}
pair 100 10
pair 50 20
# the accelerometer every 30 ms: the device at 50 Hz, the HAL thinning
pair 33 20 "50 20"
eq "deactivated: both buffers off" "$(cat $DEV/buffer/enable) $(cat $MDEV/buffer/enable)" "0 0"
check "deactivated: the chip powers down (runtime suspended)" wait_runtime suspended

# batch_ok COUNT FILE: enough events, in order
batch_ok() { [ "$1" -ge 200 ] && increasing "$2"; }

# flush at 1 s into a 2 s run at 100 Hz
hal --seconds 2 --flush-at 1 1:10 > $W/flush 2> $W/flush.err
_fl=$(awk '$1 == "flush-asked" { a = $3 } $1 == "flush" && a { printf "%.0f", ($3 - a) / 1e6; exit }' $W/flush)
diag "AS9888-METRIC hal_flush_ms=${_fl:-none}"
# (10 s: a flush-complete that never comes is a stall; a slow one on a
# busy host is said, not failed)
check "flush: flush-complete ${_fl:-never} ms after the call (a stall beyond 10 s)" in_range "$_fl" 0 10000
in_range "$_fl" 101 10000 && diag "flush: more than 100 ms (a busy host?)"
check "flush: the flush-complete comes after events" \
	awk '$1 == "ev" { e++ } $1 == "flush" { f = 1; exit !(e > 0) } END { if (!f) exit 1 }' $W/flush

# a max report latency of 500 ms at 100 Hz for 3 s
hal --seconds 3 1:10:500 > $W/batch 2> $W/batch.err
_bl=$(awk '$1 == "ev" { d = $5 - $4; if (d > m) m = d } END { printf "%.0f", m / 1e6 }' $W/batch)
_bn=$(grep -c '^ev ' $W/batch)
diag "AS9888-METRIC hal_batch_longest_wait_ms=$_bl events=$_bn"
# (held back: at least 300 ms; beyond 10 s a queue that stalls)
check "batch 500 ms: events held back (longest wait $_bl ms, 300..10000)" in_range "$_bl" 300 10000
in_range "$_bl" 701 10000 && diag "batch 500 ms: longest wait beyond 700 ms (a busy host?)"
check "batch 500 ms: $_bn events (>= 200 of about 300: the last batch goes with the deactivation), in order" \
	batch_ok $_bn $W/batch

# postures: the device-frame direction V up, at three temperatures, on a
# calibrated chip (the daemon's factory test through the driver, Z up at
# 25 degC: the probe's zero calibration leaves the unit's offset drift)
/bin/as9888-calibd factory-test --backend iio --record $W/rec > $W/ft.out 2>&1
RC=$?
[ $RC -eq 0 ] || sed 's/^/# /' $W/ft.out | tail -n 20
eq "factory test through the driver at 25 degC, Z up: exit status 0" $RC 0
diag "mount matrix: $(cat $DEV/in_accel_mount_matrix)"
for t in -20 25 70; do
	sim_temp $t
	for v in "1 0 0" "-1 0 0" "0 1 0" "0 -1 0" "0 0 1" "0 0 -1"; do
		sim_up $(sp_up_for $v)
		_p=$W/posture
		hal --seconds 1 1:20 > $_p 2> $_p.err
		# the mean event: its length (busybox awk has no sqrt: Newton's
		# method), and its component along V
		set -- $(awk -v v="$v" 'BEGIN { split(v, u, " ") }
			$1 == "ev" { x += $6; y += $7; z += $8; n++ }
			END { if (!n) { print "none none"; exit }
			      x /= n; y /= n; z /= n; q = x * x + y * y + z * z; r = q
			      for (i = 0; i < 50 && r > 0; i++) r = (r + q / r) / 2
			      printf "%.4f %.4f\n", r, x * u[1] + y * u[2] + z * u[3] }' $_p)
		diag "AS9888-METRIC hal_g_${t}C_$(echo $v | tr ' -' '_m')=$1"
		check "at rest, $t degC, device ($v) up: |a| = $1 m/s^2 (9.80665 +- 0.5 %), along up $2" \
			awk -v m="$1" -v a="$2" -v g=$G 'BEGIN { exit !(m != "none" && m - g <= g * 0.005 && g - m <= g * 0.005 && a >= g * 0.995) }'
	done
done
sim_temp 25
sim_up 0 0 1

# --- the compass: magn-calibrate, then the HAL's calibrated field -----------------
# (as 89: the factory test's accelerometer needs its noise, its
# magnetometer self-test a low field)
magn_board "offset = 40 -25 60" "noise = 0.5" "seed = 7"
check "magnetic board (hard and soft iron): as9888-accel and as9888-magn" wait_dev 5
magn_iron off
check "factory test through the driver on the magnetic board" \
	sh -c "/bin/as9888-calibd factory-test --backend iio --record $W/rec-m > $W/ft-m.log 2>&1"
magn_iron on
echo 0.3 > $SIM/magn_noise && echo 1 > $SIM/tumble
# (restore: what applies the record at boot; --timeout 600 stops a
# session that stalls, a slow guest is not timed: learning takes 84 s idle)
check "magn-calibrate --backend iio, the board tumbling: stored, and restored to the driver" \
	sh -c "/bin/as9888-calibd magn-calibrate --backend iio --timeout 600 --record $W/rec-m > $W/mc.log 2>&1 &&
	       /bin/as9888-calibd restore --backend iio --record $W/rec-m >> $W/mc.log 2>&1"
echo 0 > $SIM/tumble && echo 0 > $SIM/magn_noise && echo "1 0 0 0" > $SIM/orientation
tail -n 3 $W/mc.log | sed "s/^/# /"
grep -E "^(samples: |Magnetometer calibrated|  field)" $W/mc.log | sed 's/^/# /'
# (the magnetometer's next measurements are of the level board)
sleep 1
$HAL --record $W/rec-m --socket "" --seconds 3 2:100 3:100 > $W/compass 2> $W/compass.err
[ -s $W/compass.err ] && diag "as9888-hal-cat: $(cat $W/compass.err)"
MM=$(cat $MDEV/in_magn_mount_matrix)
diag "magnetometer mount matrix: $MM"
# android_of "X Y Z": M X, in Android's frame
android_of() {
	echo "$MM; $1" | tr ',;' '  ' | awk '{ for (i = 1; i <= 3; i++)
		printf "%.3f%s", $(3 * i - 2) * $10 + $(3 * i - 1) * $11 + $(3 * i) * $12, i < 3 ? " " : "\n" }'
}
# uncal_minus_bias FILE: N samples with both events, each uncalibrated -
# bias = calibrated within 0.001 uT and of accuracy high; "N bad"
uncal_minus_bias() {
	awk '$1 == "ev" && $2 == 2 { c[$4] = $6 " " $7 " " $8 " " $12 }
		$1 == "ev" && $2 == 3 { u[$4] = ($6 - $9) " " ($7 - $10) " " ($8 - $11) }
		END { for (t in c) if (t in u) { n++; split(c[t], a, " "); split(u[t], b, " ")
			for (i = 1; i <= 3; i++) { d = a[i] - b[i]; if (d > 0.001 || d < -0.001) { bad++; break } }
			if (a[4] != 3) bad++ }
		      printf "%d %d\n", n, bad }' "$1"
}
# mean FILE HANDLE FROM: the mean of an event's values FROM..FROM+2 ($6: the field)
mean() {
	awk -v h=$2 -v f=$3 '$1 == "ev" && $2 == h { x += $f; y += $(f + 1); z += $(f + 2); n++ }
		END { if (n) printf "%.3f %.3f %.3f\n", x / n, y / n, z / n; else print "none" }' "$1"
}
# near3 "A" "B" TOL: every axis of A within TOL of B's
near3() {
	echo "$1 $2" | awk -v t=$3 'NF != 6 { exit 1 } { for (i = 1; i <= 3; i++) { d = $i - $(i + 3)
		if (d > t || d < -t) exit 1 } }'
}
# heading_ok "FIELD" "TRUE": FIELD's horizontal direction (x, y of
# Android's frame, the device flat) within 3 degrees of TRUE's
# (|cross| <= tan 3 deg x dot), and |FIELD| 48 uT within 5 %
heading_ok() {
	echo "$1 $2" | awk 'NF != 6 { exit 1 } { c = $1 * $5 - $2 * $4; d = $1 * $4 + $2 * $5
		q = $1 * $1 + $2 * $2 + $3 * $3
		exit !(d > 0 && c <= 0.0524 * d && -c <= 0.0524 * d && q >= 45.6 * 45.6 && q <= 50.4 * 50.4) }'
}
set -- $(uncal_minus_bias $W/compass)
check "calibrated and uncalibrated field: $1 samples, uncalibrated - bias = calibrated (0.001 uT), accuracy high (${2:-?} not)" \
	eval "[ ${1:-0} -ge 10 ] && [ ${2:-1} -eq 0 ]"
BIAS=$(mean $W/compass 3 9)
# the hard iron as the calibrated field sees it: W h, W = 1 / diag(S)
HARD=$(android_of "$(echo "$MAGN_HARD $MAGN_CALIBSCALE" | awk '{ printf "%.3f %.3f %.3f", $1 * $4, $2 * $5, $3 * $6 }')")
diag "AS9888-METRIC hal_magn_bias_ut=$BIAS (W h in Android's frame: $HARD)"
check "the reported bias $BIAS uT is the hard iron W h in Android's frame, $HARD uT (3 uT)" \
	near3 "$BIAS" "$HARD" 3
CAL=$(mean $W/compass 2 6)
UNCAL=$(mean $W/compass 3 6)
TRUE=$(android_of "$MAGN_TRUE")
diag "AS9888-METRIC hal_magn_calibrated_ut=$CAL (true: $TRUE; uncalibrated: $UNCAL)"
check "heading: the calibrated field $CAL uT points as the true field $TRUE uT (3 deg), |B| 48 uT (5 %)" \
	heading_ok "$CAL" "$TRUE"
check_not "heading: the uncalibrated field $UNCAL uT does not (the check can fail)" \
	heading_ok "$UNCAL" "$TRUE"
