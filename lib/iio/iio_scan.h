/* SPDX-License-Identifier: GPL-2.0 */
/*
 * Samples of an IIO buffer as the ABI describes them: each enabled channel
 * has a scan_elements/<channel>_index and a _type such as "le:s12/16>>0";
 * in a sample the channels follow their index, each aligned to its size.
 */
#ifndef AS9888_IIO_SCAN_H
#define AS9888_IIO_SCAN_H

#include <stdbool.h>
#include <stdint.h>

/**
 * struct iio_scan_channel - one channel's place in a buffer sample
 * @index:	its scan index
 * @offset:	first byte in a sample (set by iio_scan_layout())
 * @bytes:	storage size: 1, 2, 4 or 8
 * @realbits:	significant bits
 * @shift:	right shift of the value in its storage
 * @is_signed:	two's complement value
 * @big_endian:	storage byte order
 */
struct iio_scan_channel {
	unsigned int index;
	unsigned int offset;
	unsigned int bytes;
	unsigned int realbits;
	unsigned int shift;
	bool is_signed;
	bool big_endian;
};

/* Parse a _type attribute ("le:s12/16>>0"); 0 or -EINVAL */
int iio_scan_parse_type(const char *s, struct iio_scan_channel *c);

/*
 * Place @n channels (with their index and type set) in a sample; returns
 * the sample size in bytes (padded, as the IIO core pads it, to the
 * largest channel's size). Two channels with the same index: -EINVAL.
 */
int iio_scan_layout(struct iio_scan_channel *c, unsigned int n);

/*
 * The value of @c in @sample, sign-extended: any channel (a timestamp is
 * le:s64/64), and for one of 32 bits or fewer
 */
int64_t iio_scan_value64(const struct iio_scan_channel *c,
			 const uint8_t *sample);
int32_t iio_scan_value(const struct iio_scan_channel *c, const uint8_t *sample);

#endif
