/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave receive: payloads from a serial port (hardware or the emulator). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bwh_link.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "commands.h"

static const char receive_help[] =
    "usage: brdfwave receive --port DEV --out DIR [--count N] [--timeout S]\n"
    "                        [--max-samples N]\n"
    "\n"
    "Reads payloads from a serial port (a device's UART or the emulator's\n"
    "pseudo-terminal): checks every frame's CRC, asks the device to resend\n"
    "missing or corrupted chunks, checks and decodes the whole payload, stores it\n"
    "as DIR/payload-ID-CRC.bwv (ID the device's payload id, CRC the payload's\n"
    "CRC-32; a temporary file, fsync, then a link that never replaces a file) and\n"
    "only then acknowledges it. A payload that does not decode is neither stored\n"
    "nor acknowledged.\n"
    "  --count N        stop after N payloads (default 1; 0: until the timeout)\n"
    "  --timeout S      give up after S seconds without progress: no new payload,\n"
    "                   chunk or completed payload (default 60); frames that bring\n"
    "                   nothing new do not extend it\n"
    "  --max-samples N  refuse payloads that decode to more than N samples\n"
    "                   (default 67108864)\n";

int bw_cmd_receive(int argc, char **argv)
{
    const char *port = NULL, *dir = NULL;
    uint32_t count = 1, max_samples = 0, drop = 0;
    int has_drop = 0;
    double timeout = 60;
    const cli_opt_t opts[] = {
        {"port", 0, CLI_STRING, .dest = &port},
        {"out", 0, CLI_STRING, .dest = &dir},
        {"count", 0, CLI_U32, .dest = &count, .lo = 0, .hi = UINT32_MAX},
        {"timeout", 0, CLI_POSITIVE, .dest = &timeout, .hi = 1e7},
        {"max-samples", 0, CLI_U32, .dest = &max_samples, .lo = 1, .hi = UINT32_MAX},
        {"drop-chunk", 0, CLI_U32, .dest = &drop, .lo = 0, .hi = 65535, .seen = &has_drop},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, receive_help, NULL, &st))
        return st;
    if (!port || !dir)
        return cli_usage("needs --port DEV and --out DIR");
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return cli_fail("%s is not a directory", dir);
    int fd = bwh_port_open(port);
    if (fd < 0)
        return cli_fail("%s", bwh_last_error());
    bwh_rx_opts_t o = {timeout, has_drop ? (int)drop : -1, 0, max_samples};
    bwh_link_t link;
    bwh_link_init(&link, fd);
    int rc = CLI_EXIT_OK;
    for (uint32_t got = 0; count == 0 || got < count; got++) {
        bwh_received_t r;
        if (bwh_receive_payload(&link, &o, &r) != 0) {
            if (count == 0 && got > 0)
                break; /* until the timeout: a quiet link ends the run */
            rc = cli_fail("%s", bwh_last_error());
            break;
        }
        char path[4096];
        int kept = bwh_store_payload(dir, r.id, r.payload, r.len, path, sizeof path);
        free(r.payload);
        if (kept < 0 || bwh_acknowledge(&link, r.id) != 0) {
            /* not stored: not acknowledged either, the device keeps it */
            rc = cli_fail("%s", bwh_last_error());
            break;
        }
        printf("received %s%s: %zu bytes, %u resend request(s), %u bad frame(s)\n", path,
               kept == 1 ? " (already stored)" : "", r.len, r.resends, r.bad_frames);
        fflush(stdout);
    }
    close(fd);
    return rc;
}
