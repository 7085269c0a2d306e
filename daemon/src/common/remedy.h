/* SPDX-License-Identifier: GPL-2.0 */
/*
 * What to do about the errors a new integrator meets first: the remedy
 * that follows the reason in a message ("<what failed>: <why>: <remedy>").
 */
#ifndef AS9888_REMEDY_H
#define AS9888_REMEDY_H

#include <stddef.h>

/* No AS9888 IIO device */
#define REMEDY_NO_DRIVER \
	"the driver is not bound: load as9888_i2c (or as9888_spi) with modprobe (dkms install puts it there) and check dmesg for its probe, or use --backend raw with the driver unbound"

/* A record whose chip fingerprint is not this chip's */
#define REMEDY_OTHER_CHIP \
	"the sensor was replaced, or the record is another board's: run factory-test on this unit, or name its own record with --record"

/* The daemon may not create its socket */
#define REMEDY_SOCKET_CREATE \
	"run the daemon as root (its unit does), or give --socket a path in a directory you may write"

/* No record at the path */
#define REMEDY_NO_RECORD \
	"no record yet: run factory-test first (or name the record with --record)"

/*
 * The remedy for @errnum (positive) met on the record's files or its
 * directory at @path, or NULL when there is none to give
 */
const char *remedy_record(int errnum);

#define REMEDY_LEN	384

/*
 * What to do when connecting to the daemon's socket at @path failed with
 * @errnum: written into @buf. Permission denied names the socket's group.
 */
void remedy_socket(int errnum, const char *path, char *buf, size_t size);

#endif
