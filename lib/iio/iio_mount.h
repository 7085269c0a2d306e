/* SPDX-License-Identifier: GPL-2.0 */
/*
 * The mount matrix (in_<type>_mount_matrix, sysfs-bus-iio): the rotation
 * that turns the sensor's frame into the device's, device = m * sensor,
 * as the IIO core prints it: "a, b, c; d, e, f; g, h, i", the rows.
 */
#ifndef AS9888_IIO_MOUNT_H
#define AS9888_IIO_MOUNT_H

/* The attribute's text whole: nine decimals as a device tree spells them */
#define IIO_MOUNT_TEXT_MAX	512

/*
 * "a, b, c; d, e, f; g, h, i" (white space around the separators and at
 * the end taken): 0, or -EINVAL (anything else, a value not finite or
 * beyond 1e6); @m is left untouched on error
 */
int iio_mount_parse(const char *s, double m[3][3]);

/* out = m * in (out may not be in) */
void iio_mount_apply(const double m[3][3], const double in[3], double out[3]);

#endif
