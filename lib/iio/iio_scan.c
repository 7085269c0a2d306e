// SPDX-License-Identifier: GPL-2.0
/* Samples of an IIO buffer as the ABI describes them (iio_scan.h). */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "iio_scan.h"

#define BITS_PER_BYTE	8
#define IIO_SCAN_MAX	16

int iio_scan_parse_type(const char *s, struct iio_scan_channel *c)
{
	char endian[3] = "", sign, end;
	unsigned int storage, realbits, shift;

	/* "[be|le]:[s|u]bits/storagebits>>shift", nothing after it */
	if (sscanf(s, "%2c:%c%u/%u>>%u%c", endian, &sign, &realbits, &storage,
		   &shift, &end) != 5)
		return -EINVAL;
	if ((sign != 's' && sign != 'u') ||
	    (strcmp(endian, "le") && strcmp(endian, "be")) ||
	    (storage != 8 && storage != 16 && storage != 32 && storage != 64) ||
	    !realbits || realbits > storage || shift > storage - realbits)
		return -EINVAL;
	c->realbits = realbits;
	c->shift = shift;
	c->is_signed = sign == 's';
	c->big_endian = !strcmp(endian, "be");
	c->bytes = storage / BITS_PER_BYTE;

	return 0;
}

int iio_scan_layout(struct iio_scan_channel *c, unsigned int n)
{
	unsigned int order[IIO_SCAN_MAX], i, j, offset = 0, largest = 1;

	if (n > IIO_SCAN_MAX)
		return -EINVAL;
	for (i = 0; i < n; i++) {
		/* insertion sort by index */
		for (j = i; j > 0 && c[order[j - 1]].index > c[i].index; j--)
			order[j] = order[j - 1];
		if (j > 0 && c[order[j - 1]].index == c[i].index)
			return -EINVAL;
		order[j] = i;
	}
	for (i = 0; i < n; i++) {
		struct iio_scan_channel *ch = &c[order[i]];

		offset = (offset + ch->bytes - 1) / ch->bytes * ch->bytes;
		ch->offset = offset;
		offset += ch->bytes;
		if (ch->bytes > largest)
			largest = ch->bytes;
	}

	/* a sample is padded to its largest channel's alignment */
	return (int)((offset + largest - 1) / largest * largest);
}

int64_t iio_scan_value64(const struct iio_scan_channel *c,
			 const uint8_t *sample)
{
	const uint8_t *p = sample + c->offset;
	uint64_t v = 0, mask;
	unsigned int i;

	for (i = 0; i < c->bytes; i++)
		v = v << BITS_PER_BYTE |
		    p[c->big_endian ? i : c->bytes - 1 - i];
	v >>= c->shift;
	mask = c->realbits == 64 ? UINT64_MAX : (1ULL << c->realbits) - 1;
	v &= mask;
	if (c->is_signed && c->realbits < 64 &&
	    (v & (1ULL << (c->realbits - 1))))
		v |= ~mask;

	return (int64_t)v;
}

int32_t iio_scan_value(const struct iio_scan_channel *c, const uint8_t *sample)
{
	return (int32_t)iio_scan_value64(c, sample);
}
