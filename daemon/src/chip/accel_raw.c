// SPDX-License-Identifier: GPL-2.0
/* The chip's own accelerometer output behind compensated samples (accel_raw.h). */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "chip/accel_raw.h"

static const char axis_name[] = "XYZ";

int accel_raw_recover(const struct accel_comp *c,
		      const int16_t out[AS9888_AXES], uint8_t tmps,
		      int16_t raw[AS9888_AXES], char *why, size_t whylen)
{
	int32_t t_mdegc = as9888_tmps_to_mdegc(tmps);
	int16_t r[AS9888_AXES];
	int axis, ret;

	for (axis = 0; axis < AS9888_AXES; axis++) {
		int32_t ot_q16, st_q16;
		int16_t back = 0;

		ret = as9888_accel_correction(&c->ee, &c->cal, axis, c->da[axis],
					      t_mdegc, &ot_q16, &st_q16);
		if (ret) {
			snprintf(why, whylen,
				 "%c: no offset/sensitivity at TMPS 0x%02x with DAC 0x%02x: %s",
				 axis_name[axis], tmps, c->da[axis],
				 strerror(-ret));
			return -EINVAL;
		}
		/*
		 * The driver's mark of a chip reading at its rail: that rail,
		 * which the note's saturation judgment (3-14..3-19) fails
		 */
		if (out[axis] <= AS9888_ACC_OUT_MIN ||
		    out[axis] >= AS9888_ACC_OUT_MAX) {
			r[axis] = out[axis] < 0 ? AS9888_ACC_MIN : AS9888_ACC_MAX;
			continue;
		}
		ret = as9888_accel_uncompensate(out[axis], ot_q16, st_q16,
						&r[axis]);
		/*
		 * The inverse is the daemon's, not a kernel ABI: it must
		 * give the sample back through the same arithmetic
		 */
		if (!ret && (as9888_accel_compensate(r[axis], ot_q16, st_q16,
						     &back) ||
			     back != out[axis])) {
			snprintf(why, whylen,
				 "%c reads %d, but the chip reading %d recovered from it gives %d: the driver does not compensate as this daemon does (use --backend raw)",
				 axis_name[axis], out[axis], r[axis], back);
			return -ERANGE;
		}
		if (ret) {
			snprintf(why, whylen,
				 "%c reads %d, which no chip reading gives with the driver's calibration as read (was it changed during the test?)",
				 axis_name[axis], out[axis]);
			return -ERANGE;
		}
	}
	memcpy(raw, r, sizeof(r));

	return 0;
}
