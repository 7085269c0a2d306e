// SPDX-License-Identifier: GPL-2.0
/* The mount matrix as text and applied (iio_mount.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>

#include "iio_mount.h"

/* Beyond any element of a rotation by far: a value that is no matrix */
#define IIO_MOUNT_ELEMENT_MAX	1e6

int iio_mount_parse(const char *s, double m[3][3])
{
	double v[9];
	int i, used = -1;

	if (sscanf(s, " %lf , %lf , %lf ; %lf , %lf , %lf ; %lf , %lf , %lf %n",
		   &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7], &v[8],
		   &used) != 9 || used < 0 || s[used])
		return -EINVAL;
	for (i = 0; i < 9; i++)
		if (!isfinite(v[i]) || fabs(v[i]) > IIO_MOUNT_ELEMENT_MAX)
			return -EINVAL;
	for (i = 0; i < 9; i++)
		m[i / 3][i % 3] = v[i];
	return 0;
}

void iio_mount_apply(const double m[3][3], const double in[3], double out[3])
{
	int i;

	for (i = 0; i < 3; i++)
		out[i] = m[i][0] * in[0] + m[i][1] * in[1] + m[i][2] * in[2];
}
