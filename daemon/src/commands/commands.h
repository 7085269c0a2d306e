/* SPDX-License-Identifier: GPL-2.0 */
/* The commands of as9888-calibd; each returns the exit status. */
#ifndef AS9888_COMMANDS_H
#define AS9888_COMMANDS_H

#include "commands/cli.h"

int cmd_factory_test(const struct cli_opts *o);
int cmd_restore(const struct cli_opts *o);
int cmd_show(const struct cli_opts *o);
int cmd_recalibrate(const struct cli_opts *o);
int cmd_rollback(const struct cli_opts *o);
int cmd_check(const struct cli_opts *o);
int cmd_daemon(const struct cli_opts *o);
int cmd_request(const struct cli_opts *o);
int cmd_magn_show(const struct cli_opts *o);
int cmd_magn_calibrate(const struct cli_opts *o);
int cmd_magn_feed(const struct cli_opts *o);

#endif
