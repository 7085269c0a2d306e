#!/bin/bash
# SPDX-License-Identifier: GPL-2.0
#
# Factory test speed on the simulator (--backend sim), side by side with
# two floors: the shortest time each legal order of the application note's
# transfers can take, computed here from the datasheet timings (t_RSTL,
# t_BOOT, t_EEP, t_PD, t_MAG, t_ACC) and the I2C bit counts at 400 kHz,
# not from our own sequence. INT1 is monitored (no polling); a measurement
# starts no sooner than t_PD after the previous one ended; the project's
# own checks (D10/D2 read-backs, D11 RSTN/INT2 checks, DR2EN) are not in
# either floor. N1 = N, or with --permissible-error max(N, 32): the
# 32-sample pilot that measures sigma (Note 2) is the first level run's
# start.
#
# The note's order: every register of a sample read before the next MS
# write. Reset; WIA; MS = EEPROM, t_EEP, the 21 EEPROM bytes; MS = 0,
# t_PD, the 10 trims in one write; INT1EN, SLCT2; the magnetometer
# measurement (INT1ST, and ST1, HXL..HZH, ST2) and the self-test (ST1,
# HXL..HZH, ST2); SLCT2; N1 accelerometer measurements (MS write, t_ACC,
# ST1, TMPS, EMPT, A1XL..A1ZH, ST2, the cheaper of one 16-byte burst or
# the two transactions); the 3 DAC bytes; N measurements again.
#
# The datasheet's order (section 3: the data registers hold the last sample
# until the end of the next measurement, so only ST1 must be read before
# the next MS write): WIA, INT1EN and SLCT2 during t_EEP (only 0x30..0x39
# are restricted to power-down, and the EEPROM to t_EEP); the trims right
# after MS = 0 (t_PD restricts the next mode, not the writes); the
# magnetometer data read during the self-test, step 3's SLCT2 during it
# too, and each accelerometer sample's TMPS..ST2 during the next
# conversion; only the last sample of each run is read whole (its mean is
# needed next). The table of phases is in docs/DECISIONS.md.
#
# Prints our sequence on the virtual clock (target <= 1.02 x the
# datasheet-order floor) and the median wall time of RUNS real-time runs,
# each with its ratio to both floors.
# Usage: bench-factory-test.sh PATH-TO-as9888-calibd [RUNS]
set -euo pipefail

calibd=${1:?usage: bench-factory-test.sh PATH-TO-as9888-calibd [RUNS]}
runs=${2:-7}
work=$(mktemp -d /tmp/as9888-bench-XXXXXX)
trap 'rm -rf "$work"' EXIT
top=$(cd "$(dirname "$0")/.." && pwd)
regs=$top/drivers/iio/imu/as9888/as9888_regs.h

# us: a datasheet time from the register map
us() { sed -n "s/^#define AS9888_$1_US[[:space:]]*\([0-9]*\).*/\1/p" "$regs"; }

# floor ORDER N1 N: the note's or the datasheet's order in ms
floor() {
	awk -v order="$1" -v n1="$2" -v n="$3" -v rstl="$(us T_RSTL)" \
	    -v boot="$(us T_BOOT)" -v eep="$(us T_EEP)" -v pd="$(us T_PD)" \
	    -v mag="$(us T_MAG)" -v acc="$(us T_ACC)" '
	function w(len) { return (1 + 9 + 9 + 9 * len + 1) * 2.5 }	# us at 400 kHz
	function r(len) { return (1 + 9 + 9 + 1 + 9 + 9 * len + 1) * 2.5 }
	function max(a, b) { return a > b ? a : b }
	function note() {
		sample = r(1) + r(9) < r(16) ? r(1) + r(9) : r(16)
		msample = r(7) + r(1) < r(16) ? r(7) + r(1) : r(16)
		t = rstl + boot + r(1) + w(1) + eep + r(21) + w(1) + pd + w(10)
		t += w(1) + w(1)					# INT1EN, SLCT2
		t += w(1) + mag + r(1) + msample			# 2-3..2-13
		t += max(pd - r(1) - msample, 0) + w(1) + mag + msample	# 2-14..2-23
		t += w(1)						# 3-1
		t += n1 * (w(1) + acc) + (n1 - 1) * max(pd, sample) + sample
		t += w(3) + max(pd - sample - w(3), 0)			# 3-24..3-26
		t += n * (w(1) + acc) + (n - 1) * max(pd, sample) + sample
		return t
	}
	function datasheet() {
		gap = max(pd, r(1))		# ST1, then t_PD since the end
		t = rstl + boot + w(1)				# reset, MS = EEPROM
		t += max(eep, r(1) + w(1) + w(1))		# WIA, INT1EN, SLCT2 in t_EEP
		t += r(21) + w(1) + w(10)			# EEPROM, MS = 0, trims
		t += w(1) + mag					# 2-3, 2-4
		t += max(pd, r(1) + r(1))			# INT1ST, ST1
		t += w(1) + max(mag, r(6) + r(1) + w(1))	# self-test; HXL..ST2, SLCT2
		t += n1 * (gap + w(1) + acc)			# run 1, ST1 before each MS
		t += r(1) + r(9) + w(3)				# its last sample, the DAC
		t += n * (w(1) + acc) + (n - 1) * gap		# run 2
		t += r(1) + r(9)				# its last sample
		return t
	}
	BEGIN { printf "%.3f", (order == "note" ? note() : datasheet()) / 1000 }'
}

# ratio A B: A / B to 3 decimals
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a / b }'; }

# one RUNS-long measurement: LABEL UNIT-TEXT OPTIONS...
bench() {
	local label=$1 unit=$2 times=() n n1 fn fd median virt vnote
	shift 2
	printf '%s\n' "$unit" >"$work/unit"
	for _ in $(seq "$runs"); do
		"$calibd" factory-test --backend sim --unit "$work/unit" --json \
			--record "$work/cal" "$@" >"$work/r.json"
		times+=("$(sed -n 's/^  "duration_ms": \(.*\),$/\1/p' "$work/r.json")")
	done
	virt=$("$calibd" factory-test --backend sim --sim-clock virtual --unit "$work/unit" \
		--json --record "$work/cal" "$@" | tee "$work/v.json" |
		sed -n 's/^  "duration_ms": \(.*\),$/\1/p')
	vnote=$("$calibd" factory-test --backend sim --sim-clock virtual --unit "$work/unit" \
		--json --record "$work/cal" --sequence note "$@" |
		sed -n 's/^  "duration_ms": \(.*\),$/\1/p')
	n=$(python3 -c "import json; print(json.load(open('$work/v.json'))['calibration']['samples'])")
	n1=$n
	case " $* " in *" --permissible-error "*) [ "$n" -ge 32 ] || n1=32 ;; esac
	fn=$(floor note "$n1" "$n")
	fd=$(floor datasheet "$n1" "$n")
	median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(( (runs + 1) / 2 ))p")
	echo "$label (N=$n): floors: note order ${fn} ms, datasheet order ${fd} ms"
	echo "  virtual clock: ${virt} ms = $(ratio "$virt" "$fd") x the datasheet-order floor" \
	     "(target <= 1.02), $(ratio "$virt" "$fn") x the note-order floor;" \
	     "--sequence note ${vnote} ms = $(ratio "$vnote" "$fn") x the note-order floor"
	echo "  wall time: ${median} ms (median of $runs) = $(ratio "$median" "$fd") x the" \
	     "datasheet-order floor, $(ratio "$median" "$fn") x the note-order floor"
	echo "  all runs (ms): ${times[*]}"
}

bench "factory-test --samples 16" "seed = 1" --samples 16
bench "factory-test --permissible-error 0.25, noise 2" "noise = 2
seed = 5" --permissible-error 0.25
