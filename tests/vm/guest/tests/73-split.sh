# SPDX-License-Identifier: GPL-2.0
# One IIO device per sensor (issue 10, item 3): as9888-accel and
# as9888-magn share the chip and its data-ready trigger.
#  - an accel-only client that enables every scan element of as9888-accel
#    (as iio-sensor-proxy 3.7+ does) makes the chip measure the
#    magnetometer zero times (adapter stats chip_magn_measurements);
#  - both devices buffering at once on the shared trigger get the same
#    measurements: the same rate, valid magnetometer and accelerometer
#    samples; a raw read on either is refused while its own buffer runs;
#  - a magn raw read and the magn selftest while the accel buffer runs
#    work (the driver waits for the gap between two samples), and the
#    accel capture goes on without losing samples;
#  - the data-ready trigger refuses an IIO device of another chip
#    (as9888_sim_other.ko, tests/vm/adapter), which takes a trigger free
#    for all; the magn device takes it;
#  - an unbind and a module removal with both buffers running: the readers
#    return, new devices probe and capture (a kernel splat fails the run on
#    the host, and is named here).
# Waits are for stalls only: 60 s without the samples waited for.
plan 56
set_unit "temperature = 25" "noise = 0"
check "fresh unit: as9888-accel and as9888-magn" wait_dev 5
set_cal 0 0 0 25000
T=$(dr_trig)
check "the data-ready trigger as9888-dev${DEV##*iio:device} exists" test -n "$T"
eq "as9888-accel's current_trigger defaults to the data-ready trigger" \
	"$(cat $DEV/trigger/current_trigger)" "$T"
eq "as9888-magn's current_trigger defaults to the data-ready trigger" \
	"$(cat $MDEV/trigger/current_trigger)" "$T"
echo 100 > $DEV/sampling_frequency
O=/tmp/split
mkdir -p $O
# sv FILE KEY: a counter of a saved copy of the adapter's stats
sv() { sed -n "s/^$2 //p" "$1"; }
# ts FILE: the timestamps of a capture of 16-byte scans, one a line
ts() { od -A n -t d8 -v "$1" | awk 'NF == 2 { print $2 }'; }
# magn_bad FILE: magn scans (x y z + timestamp, 16 bytes) that are not the
# ambient field of the unit (67 -16 -136, see 20-channels.sh) within 1 LSB;
# s13 in 16 bits, the sign from bit 12
magn_bad() {
	od -A n -t u2 -v "$1" | awk 'function s13(v) { v = v % 8192; return v >= 4096 ? v - 8192 : v }
		NF == 8 { x = s13($1); y = s13($2); z = s13($3)
			if (x < 66 || x > 68 || y < -17 || y > -15 || z < -137 || z > -135) bad++ }
		END { print bad + 0 }'
}
# accel_start FILE: the accel device's buffer, accel x y z + timestamp, on
# the data-ready trigger; PA is the reader; 10 samples must come (60 s)
accel_start() {
	buf_start $DEV "$T" "$1" accel_x accel_y accel_z timestamp &&
		PA=$BUF_PID && wait_grow "$1" $((10 * 16))
}

# --- 1. an accel-only client with every scan element ---------------------------
cat $SIM/stats > $O/s0
if buf_start $DEV "$T" $O/all.bin all; then
	sleep 2
	Z=$(scan_bytes $DEV)
	cat $SIM/stats > $O/s1
	buf_stop $DEV $BUF_PID $O/all.bin
	M=$(($(sv $O/s1 chip_measurements) - $(sv $O/s0 chip_measurements)))
	G=$(($(sv $O/s1 chip_magn_measurements) - $(sv $O/s0 chip_magn_measurements)))
	S=$(($(wc -c < $O/all.bin) / Z))
	diag "every scan element of as9888-accel ($(echo $(cd $(se_dir $DEV) && ls *_en))), $Z bytes a scan: $S samples, $M measurements, $G with the magnetometer in 2 s"
	diag "AS9888-METRIC accel_all_scan_elements_magn_measurements=$G measurements=$M samples=$S"
	eq "accel device, every scan element: a scan is accel x y z, temp, timestamp (16 bytes)" "$Z" 16
	eq "accel device, every scan element, data-ready trigger: no magnetometer measurement" "$G" 0
	check "accel device, every scan element: chip_measurements grows ($M in 2 s)" test "$M" -ge 20
	check "accel device, every scan element: samples arrive ($S in 2 s)" test "$S" -ge 20
	eq "accel device, every scan element: every z sample 1 g (1024 +- 4)" "$(zbad $O/all.bin)" 0
else
	nok_for 5 "accel device: buffer with every scan element on the data-ready trigger"
fi

# --- 2. both devices buffering on the shared trigger ------------------------------
if buf_start $MDEV "$T" $O/m.bin magn_x magn_y magn_z timestamp; then
	PM=$BUF_PID
	if accel_start $O/a.bin; then
		ok "both devices buffer on the same data-ready trigger"
	else
		nok "both devices buffer on the same data-ready trigger" "the accel buffer did not start or stalled"
	fi
	# each device's raw reads are refused while its own buffer runs
	check_not "both buffering: as9888-accel refuses a raw read" \
		sh -c "cat $DEV/in_accel_x_raw > /dev/null 2>&1"
	check_not "both buffering: as9888-magn refuses a raw read" \
		sh -c "cat $MDEV/in_magn_x_raw > /dev/null 2>&1"
	sleep 3
	echo 0 > $DEV/buffer/enable
	echo 0 > $MDEV/buffer/enable
	buf_drain $DEV $PA $O/a.bin
	buf_drain $MDEV $PM $O/m.bin
	SA=$(samples $O/a.bin)
	SM=$(samples $O/m.bin)
	# the samples of each within the time both ran
	ts $O/a.bin > $O/a.ts
	ts $O/m.bin > $O/m.ts
	W=$(awk 'FNR == 1 { if ($1 > lo) lo = $1 } { last[FILENAME] = $1 }
		END { hi = -1; for (f in last) if (hi < 0 || last[f] < hi) hi = last[f]; print lo, hi }' $O/a.ts $O/m.ts)
	NA=$(awk -v lo=${W% *} -v hi=${W#* } '$1 >= lo && $1 <= hi' $O/a.ts | wc -l)
	NM=$(awk -v lo=${W% *} -v hi=${W#* } '$1 >= lo && $1 <= hi' $O/m.ts | wc -l)
	diag "both buffering: $SA accel and $SM magn samples; within the time both ran $NA and $NM"
	check "both buffering: accel samples arrive ($SA)" test "$SA" -ge 30
	check "both buffering: magn samples arrive ($SM)" test "$SM" -ge 30
	D=$((NA - NM)); [ $D -lt 0 ] && D=$((-D))
	check "both buffering: the same rate (within the time both ran $NA accel, $NM magn samples, +- 2)" \
		test $D -le 2
	period_ok "both buffering: accel at 100 Hz" "$(period_us $O/a.bin)" 10000
	period_ok "both buffering: magn at 100 Hz" "$(period_us $O/m.bin)" 10000
	check "both buffering: accel timestamps strictly increasing" monotonic $O/a.bin
	check "both buffering: magn timestamps strictly increasing" monotonic $O/m.bin
	eq "both buffering: every accel z sample 1 g (1024 +- 4)" "$(zbad $O/a.bin)" 0
	eq "both buffering: every magn sample the ambient field (67 -16 -136 +- 1, no overflow)" \
		"$(magn_bad $O/m.bin)" 0
else
	nok_for 12 "as9888-magn: buffer on the data-ready trigger"
fi

# --- 3. magn raw reads while the accel buffer runs --------------------------------
cat $SIM/stats > $O/s0
if accel_start $O/r.bin; then
	t0=$(uptime_s)
	g0=$(stat_get chip_magn_measurements)
	good=0; i=0
	while [ $i -lt 5 ]; do
		if v=$(timeout 10 cat $MDEV/in_magn_x_raw 2> $O/r.err) && [ "$v" -ge 66 ] && [ "$v" -le 68 ]; then
			good=$((good + 1))
		else
			diag "magn raw read $i while the accel buffer runs: '$v' $(cat $O/r.err)"
		fi
		i=$((i + 1))
	done
	g1=$(stat_get chip_magn_measurements)
	check "accel buffer after the magn reads: 20 more samples (stall: 60 s)" \
		wait_grow $O/r.bin $((20 * 16))
	cat $SIM/stats > $O/s1
	t1=$(uptime_s)
	echo 0 > $DEV/buffer/enable
	buf_drain $DEV $PA $O/r.bin
	eq "5 magn raw reads while the accel buffer runs: each succeeds, 67 +- 1" $good 5
	eq "5 magn raw reads: 5 magnetometer measurements" $((g1 - g0)) 5
	S=$(samples $O/r.bin)
	M=$(($(sv $O/s1 chip_measurements) - $(sv $O/s0 chip_measurements)))
	E=$(echo "$t0 $t1" | awk '{ printf "%d", ($2 - $1) * 100 }')
	diag "accel capture with magn reads: $S samples, $M measurements (5 of them magn reads at most), $E expected from 100 Hz over the reads"
	check "accel capture with magn reads: at least half of what 100 Hz gives ($S vs $E)" \
		test $((S * 2)) -ge "$E"
	check "accel capture with magn reads: every accel measurement reached the reader ($S >= $M - 5 - 2)" \
		test "$S" -ge $((M - 7))
	check "accel capture with magn reads: timestamps strictly increasing" monotonic $O/r.bin
	eq "accel capture with magn reads: every z sample 1 g (1024 +- 4)" "$(zbad $O/r.bin)" 0
	period_ok "accel capture with magn reads at 100 Hz" "$(period_us $O/r.bin)" 10000
else
	nok_for 8 "accel buffer for the magn reads"
	buf_stop $DEV "$BUF_PID" $O/r.bin
fi

# --- 4. the magn selftest while the accel buffer runs -----------------------------
if accel_start $O/st.bin; then
	if timeout 30 sh -c "echo 1 > $MDEV/selftest" 2> $O/st.err; then
		ok "magn selftest while the accel buffer runs: accepted"
	else
		nok "magn selftest while the accel buffer runs: accepted" "$(cat $O/st.err)"
	fi
	eq "magn selftest while the accel buffer runs: pass" "$(cat $MDEV/selftest)" pass
	check "the accel buffer keeps delivering after the selftest: 20 more samples (stall: 60 s)" \
		wait_grow $O/st.bin $((20 * 16))
	buf_stop $DEV $PA $O/st.bin
	check "accel capture around the selftest: timestamps strictly increasing" monotonic $O/st.bin
	eq "accel capture around the selftest: every z sample 1 g (1024 +- 4)" "$(zbad $O/st.bin)" 0
else
	nok_for 5 "accel buffer for the selftest"
	buf_stop $DEV "$BUF_PID" $O/st.bin
fi

# --- 5. the trigger and an IIO device of another chip -----------------------------
LOADED=""
if insmod $MODDIR/as9888_sim_other.ko 2> $O/other.err; then
	LOADED=1
fi
OTHER=""
for d in /sys/bus/iio/devices/iio:device*; do
	case "$(cat $d/name 2>/dev/null)" in as9888-accel | as9888-magn) continue ;; esac
	[ -e $d/trigger/current_trigger ] && { OTHER=$d; break; }
done
if [ -z "$OTHER" ]; then
	# the bench's own module makes that device: without it, a failure
	if [ -n "$LOADED" ]; then
		nok_for 4 "an IIO device of another chip with a trigger" \
			"as9888_sim_other.ko loaded but made no such device"
	else
		nok_for 4 "an IIO device of another chip with a trigger" \
			"insmod as9888_sim_other.ko: $(cat $O/other.err)"
	fi
else
	n=$(cat $OTHER/name)
	echo "" > $OTHER/trigger/current_trigger
	if echo "$T" > $OTHER/trigger/current_trigger 2> $O/o.err; then
		nok "$n (another chip): $T refused" "the write was accepted"
	else
		ok "$n (another chip): $T refused ($(sed 's/.*: //' $O/o.err))"
	fi
	eq "$n: no trigger after the refusal" "$(cat $OTHER/trigger/current_trigger)" ""
	# the check can fail: a trigger free for all is taken
	mkdir -p /sys/kernel/config/iio/triggers/hrtimer/as9888t73
	echo as9888t73 > $OTHER/trigger/current_trigger
	eq "$n takes an hrtimer trigger" "$(cat $OTHER/trigger/current_trigger)" as9888t73
	echo "" > $OTHER/trigger/current_trigger
	echo "" > $MDEV/trigger/current_trigger
	echo "$T" > $MDEV/trigger/current_trigger
	eq "as9888-magn (the same chip) takes $T" "$(cat $MDEV/trigger/current_trigger)" "$T"
fi
if [ -n "$LOADED" ]; then
	check "as9888_sim_other unloads" rmmod as9888_sim_other
else
	nok "as9888_sim_other unloads" "it did not load"
fi

# --- 6. unbind and module removal with both buffers running -----------------------
n0=$(dmesg | wc -l)
DRV=$(bus_drv)
C=$(client)
# ended PID: up to 10 s for the reader to return
ended() {
	_i=0
	while kill -0 $1 2>/dev/null; do
		[ $_i -ge 100 ] && return 1
		sleep 0.1; _i=$((_i + 1))
	done
}
for how in unbind rmmod; do
	buf_start $MDEV "$T" $O/gm.bin magn_x magn_y magn_z timestamp
	PM=$BUF_PID
	accel_start $O/ga.bin
	check "$how: both buffers running" wait_grow $O/gm.bin $((10 * 16))
	dev_stale
	case $how in
	unbind) echo $C > $DRV/unbind ;;
	rmmod) rmmod as9888_i2c ;;
	esac
	check "$how with both buffers running: the accel reader returns (10 s)" ended $PA
	check "$how with both buffers running: the magn reader returns (10 s)" ended $PM
	kill $PA $PM 2>/dev/null
	wait $PA $PM 2>/dev/null
	check "$how: both devices and the trigger are gone" chip_gone
	case $how in
	unbind) echo $C > $DRV/bind ;;
	rmmod) insmod $MODDIR/as9888_i2c.ko ;;
	esac
	check "$how: new devices probe" wait_dev 5
	T=$(dr_trig)
	set_cal 0 0 0 25000
	echo 100 > $DEV/sampling_frequency
	if capture "$T" 2 $O/after.bin; then
		check "$how: the new accel device captures ($(samples $O/after.bin) samples in 2 s)" \
			test "$(samples $O/after.bin)" -ge 20
		eq "$how: every z sample 1 g (1024 +- 4)" "$(zbad $O/after.bin)" 0
	else
		nok_for 2 "$how: buffer enable on the new accel device"
	fi
	check "$how: the new magn device reads (67 +- 1)" \
		sh -c "v=\$(cat $MDEV/in_magn_x_raw) && [ \$v -ge 66 ] && [ \$v -le 68 ]"
done
S=$(dmesg | tail -n +$((n0 + 1)) | grep -E 'BUG:|WARNING:|KASAN|Oops|Call Trace|lockdep|possible .* locking|blocked for more than')
[ -z "$S" ] || echo "$S" | head -n 20 | sed 's/^/# /'
eq "no kernel splat in dmesg from the removals with buffers running" "$S" ""
for f in $(se_dir $DEV)/*_en $(se_dir $MDEV)/*_en; do echo 0 > $f; done
