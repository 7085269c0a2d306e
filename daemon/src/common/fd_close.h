/* SPDX-License-Identifier: GPL-2.0 */
/* Closing every descriptor from one up, in a child between fork() and _exit(). */
#ifndef AS9888_FD_CLOSE_H
#define AS9888_FD_CLOSE_H

/*
 * Close every descriptor >= @lowfd. close_range() where the C library
 * has it (glibc >= 2.34, bionic API 34; not musl) and the kernel takes
 * it (5.9); otherwise fd_close_scan(). Async-signal-safe: for a child
 * between fork() and exec() or _exit().
 */
void fd_close_from(int lowfd);

/*
 * The fallback: the descriptors listed in /proc/self/fd (read with the
 * getdents64 system call, no allocation), or, without /proc, every one
 * below the soft RLIMIT_NOFILE. 0, or -errno of the /proc scan when the
 * limit loop was used.
 */
int fd_close_scan(int lowfd);

#endif
