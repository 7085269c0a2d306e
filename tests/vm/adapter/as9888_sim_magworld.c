// SPDX-License-Identifier: GPL-2.0
/* The shared magnetic world of the chip model, compiled in unchanged. */
#include "../../model/as9888_magworld.c"
