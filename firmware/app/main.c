/* SPDX-License-Identifier: BSD-2-Clause */
#include "app.h"

int main(void) { return bw_app_run(bw_board()); }
