/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave receive: payloads from a serial port (hardware or the emulator). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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
    "       brdfwave receive --port DEV --resume DIR/payload-ID-CRC.part [--out DIR]\n"
    "\n"
    "Reads payloads from a serial port (a device's UART or the emulator's\n"
    "pseudo-terminal): checks every frame's CRC, asks the device to resend\n"
    "missing or corrupted chunks, checks and decodes the whole payload, stores it\n"
    "as DIR/payload-ID-CRC.bwv (ID the device's payload id, CRC the payload's\n"
    "CRC-32; a temporary file, fsync, then a link that never replaces a file) and\n"
    "only then acknowledges it. A payload that does not decode is neither stored\n"
    "nor acknowledged.\n"
    "\n"
    "A payload the device stops sending before it is whole (the timeout passes)\n"
    "is kept as it arrived: DIR/payload-ID-CRC.part.bwv (the missing chunks zero;\n"
    "`brdfwave decode` decodes the segments it holds) and DIR/payload-ID-CRC.part\n"
    "(which chunks are missing; CRC as the device announced it), exit status 3.\n"
    "The device keeps a payload until it is acknowledged: --resume asks it for\n"
    "the missing chunks only, then stores the whole payload as above, removes\n"
    "the two files and acknowledges it.\n"
    "  --count N        stop after N payloads (default 1; 0: until the timeout)\n"
    "  --timeout S      give up after S seconds without progress: no new payload,\n"
    "                   chunk or completed payload (default 60); frames that bring\n"
    "                   nothing new do not extend it\n"
    "  --max-samples N  refuse payloads that decode to more than N samples\n"
    "                   (default 67108864)\n"
    "  --resume FILE    complete the incomplete payload FILE (its .part or\n"
    "                   .part.bwv); --out defaults to FILE's directory\n";

/* The directory of a path ("." for none), in buf[cap]. */
static const char *dir_of(const char *path, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s", path);
    char *s = strrchr(buf, '/');
    if (!s)
        return ".";
    *s = s == buf ? (s[1] = '\0', '/') : '\0';
    return buf;
}

/* Keeps what arrived of a payload given up on; CLI_EXIT_INCOMPLETE, or
 * CLI_EXIT_FAIL when it cannot be stored (or nothing arrived). */
static int keep_partial(const char *dir, bwh_partial_t *part, const char *why)
{
    char path[4096];
    uint32_t missing = bwh_partial_missing(part);
    int rc = CLI_EXIT_FAIL;
    if (missing == part->parts) {
        cli_fail("%s", why);
    } else if (bwh_partial_store(dir, part, path, sizeof path) != 0) {
        cli_fail("%s; what arrived could not be kept: %s", why, bwh_last_error());
    } else {
        cli_fail("%s; kept as %s.bwv (%u of %u chunks missing): `brdfwave receive --resume %s` "
                 "asks the device for them",
                 why, path, missing, part->parts, path);
        rc = CLI_EXIT_INCOMPLETE;
    }
    bwh_partial_free(part);
    return rc;
}

int bw_cmd_receive(int argc, char **argv)
{
    const char *port = NULL, *dir = NULL, *resume = NULL;
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
        {"resume", 0, CLI_STRING, .dest = &resume},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, receive_help, NULL, &st))
        return st;
    char rdir[4096];
    if (resume && !dir)
        dir = dir_of(resume, rdir, sizeof rdir);
    if (!port || !dir)
        return cli_usage("needs --port DEV and --out DIR (or --resume FILE)");
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return cli_fail("%s is not a directory", dir);
    bwh_partial_t before;
    memset(&before, 0, sizeof before);
    if (resume) {
        if (bwh_partial_load(resume, &before) != 0)
            return cli_fail("%s", bwh_last_error());
        count = 1;
    }
    int fd = bwh_port_open(port);
    if (fd < 0) {
        bwh_partial_free(&before);
        return cli_fail("%s", bwh_last_error());
    }
    bwh_rx_opts_t o = {timeout, has_drop ? (int)drop : -1, 0, max_samples, 1,
                       resume ? &before : NULL};
    bwh_link_t link;
    bwh_link_init(&link, fd);
    int rc = CLI_EXIT_OK;
    for (uint32_t got = 0; count == 0 || got < count; got++) {
        bwh_received_t r;
        if (bwh_receive_payload(&link, &o, &r) != 0) {
            if (r.partial.payload) {
                char why[600];
                snprintf(why, sizeof why, "%s", bwh_last_error());
                rc = keep_partial(dir, &r.partial, why);
                break;
            }
            if (count == 0 && got > 0)
                break; /* until the timeout: a quiet link ends the run */
            rc = cli_fail("%s", bwh_last_error());
            break;
        }
        char path[4096];
        int kept = bwh_store_payload(dir, r.id, r.payload, r.len, path, sizeof path);
        if (kept >= 0) /* stored whole: a record of it kept before goes */
            bwh_partial_forget(dir, r.id, r.payload, r.len);
        free(r.payload);
        if (kept < 0 || bwh_acknowledge(&link, r.id) != 0) {
            /* not stored: not acknowledged either, the device keeps it */
            rc = cli_fail("%s", bwh_last_error());
            break;
        }
        if (resume)
            bwh_partial_remove(resume);
        printf("received %s%s: %zu bytes, %u resend request(s), %u bad frame(s)%s\n", path,
               kept == 1 ? " (already stored)" : "", r.len, r.resends, r.bad_frames,
               resume ? ", completed from what arrived before" : "");
        fflush(stdout);
    }
    bwh_partial_free(&before);
    close(fd);
    return rc;
}
