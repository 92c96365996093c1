#include "app.h"

int main(void) { return bw_app_run(bw_board()); }
