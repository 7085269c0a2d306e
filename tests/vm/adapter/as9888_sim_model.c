// SPDX-License-Identifier: GPL-2.0
/* The shared chip model, compiled into the test adapter unchanged. */
#include "../../model/as9888_model.c"
