// SPDX-License-Identifier: GPL-2.0
/* The shared unit description parser, compiled into the adapter unchanged. */
#include "../../model/as9888_unit.c"
