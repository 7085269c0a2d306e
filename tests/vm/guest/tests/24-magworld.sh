# SPDX-License-Identifier: GPL-2.0
# The adapter's magnetic world (issue 28, point 1): the unit keys and the
# live knobs heading, orientation, earth, hard_iron, soft_iron, magn_noise,
# disturbance and tumble, seen through the driver's in_magn_*_raw (the
# driver applies no magnetometer calibration here: calibbias and calibscale
# are at their defaults, or absent). Counts are field / (scale x 100): the
# scale is in gauss.
# The Earth's field 50 uT, inclination 60 deg: level, heading 0 the sensor
# reads (0, 25, -43.301) uT; heading 90 (+Y east) (-25, 0, -43.301).
plan 22
# cnt UT AXIS: the count the driver reports for UT microtesla on AXIS
cnt() {
	awk -v u="$1" -v s="$(cat $MDEV/in_magn_$2_scale)" \
		'BEGIN { v = u / (s * 100); printf "%d", v < 0 ? v - 0.5 : v + 0.5 }'
}
mx() { cat $MDEV/in_magn_x_raw; }
set_unit "earth = 50 60 0" "noise = 0"
check "unit with the Earth's field: device back" wait_dev 5
near "level, heading 0: x reads 0 uT" "$(mx)" 0 1
near "level, heading 0: y reads 25 uT" "$(cat $MDEV/in_magn_y_raw)" "$(cnt 25 y)" 1
near "level, heading 0: z reads -43.3 uT" "$(cat $MDEV/in_magn_z_raw)" "$(cnt -43.301 z)" 1
eq "earth reads back" "$(cat $SIM/earth)" "50.000 60.000 0.000"
ino=$(dev_id $MDEV)

echo 90 > $SIM/heading
eq "heading 90 reads back" "$(cat $SIM/heading)" 90.000
near "heading 90: x reads -25 uT (north is -X)" "$(mx)" "$(cnt -25 x)" 1
near "heading 90: y reads 0" "$(cat $MDEV/in_magn_y_raw)" 0 1

echo "100 0 0" > $SIM/hard_iron
near "hard iron 100 uT on x: -25 + 100" "$(mx)" "$(cnt 75 x)" 1
echo "1.1 0 0  0 1 0  0 0 1" > $SIM/soft_iron
near "soft iron 1.1 on x: 1.1 x -25 + 100" "$(mx)" "$(cnt 72.5 x)" 1
eq "soft_iron reads back" "$(cat $SIM/soft_iron)" \
	"1.100000 0.000000 0.000000 0.000000 1.000000 0.000000 0.000000 0.000000 1.000000"
echo "300 0 0 0" > $SIM/disturbance
# the magnet's field meets the soft iron too: 1.1 x (-25 + 300) + 100
near "a magnet that stays: 300 uT more on x" "$(mx)" "$(cnt 402.5 x)" 1
echo "0 0 0 0" > $SIM/disturbance
near "the magnet gone" "$(mx)" "$(cnt 72.5 x)" 1
echo "0 0 0" > $SIM/hard_iron
echo "1 0 0 0 1 0 0 0 1" > $SIM/soft_iron

# a quarter turn about X: the sensor's +Y points up
echo "1 1 0 0" > $SIM/orientation
eq "orientation reads back normalised" "$(cat $SIM/orientation)" \
	"0.707106 0.707106 0.000000 0.000000"
up=$(cat $SIM/up)
eq "up follows the orientation: 0 1 0 ($up)" "$(echo "$up" | awk \
	'{ print ($1 * $1 < 1e-10 && $3 * $3 < 1e-10 && $2 > 0.99999) ? "yes" : "no" }')" yes
near "the accelerometer follows: y reads 1 g" "$(cat $DEV/in_accel_y_raw)" 1024 60
near "the field follows: y reads the vertical -43.3 uT" \
	"$(cat $MDEV/in_magn_y_raw)" "$(cnt -43.301 y)" 1

# tumble: every measurement turns the device by 5 degrees
echo 5 > $SIM/tumble
vals=$(for i in 1 2 3 4 5 6 7 8; do mx; done | sort -u | wc -l)
check "tumble: 8 reads of x, at least 6 different values ($vals)" [ "$vals" -ge 6 ]
echo 0 > $SIM/tumble
a=$(mx); b=$(mx)
# (two failed reads would be equal too: both must be readings)
if is_int "$a" && [ "$a" = "$b" ]; then
	ok "tumble 0: the device stays still"
else
	nok "tumble 0: the device stays still" "read '$a', then '$b'"
fi
echo 0.6 > $SIM/magn_noise
eq "magn_noise reads back" "$(cat $SIM/magn_noise)" 0.600
# refused by the knob, not failing for want of one: it exists, is
# readable and keeps its value
earth0=$(cat $SIM/earth 2>/dev/null)
inclination_refused() {
	[ -n "$earth0" ] && ! sh -c "echo '50 91 0' > $SIM/earth" 2>/dev/null &&
		[ "$(cat $SIM/earth)" = "$earth0" ]
}
check "an inclination of 91 deg is refused, the earth knob as it was ('$earth0')" \
	inclination_refused
eq "the knobs re-created no device" "$(dev_id $MDEV)" "$ino"
# the knobs hold until the next unit: leave a plain one to the next file
set_unit "noise = 0"
wait_dev 5
