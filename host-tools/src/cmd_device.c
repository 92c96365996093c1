/* brdfwave receive: payloads from a serial port (hardware or the emulator). */
#define _GNU_SOURCE
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bwhost.h"
#include "commands.h"
#include "bwh_link.h"

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
    static const struct option opts[] = {{"port", required_argument, 0, 'p'},
                                         {"out", required_argument, 0, 'o'},
                                         {"count", required_argument, 0, 'n'},
                                         {"timeout", required_argument, 0, 't'},
                                         {"max-samples", required_argument, 0, 'M'},
                                         {"drop-chunk", required_argument, 0, 'K'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const char *port = NULL, *dir = NULL;
    long count = 1;
    double timeout = 60;
    unsigned long long max_samples = 0;
    int drop = -1, c;
    char *e;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (c) {
        case 'p': port = optarg; break;
        case 'o': dir = optarg; break;
        case 'n':
            count = strtol(optarg, &e, 10);
            if (*e || count < 0) {
                fprintf(stderr, "brdfwave receive: --count must be >= 0\n");
                return 2;
            }
            break;
        case 't':
            timeout = strtod(optarg, &e);
            if (*e || !(timeout > 0) || timeout > 1e7) {
                fprintf(stderr, "brdfwave receive: --timeout must be a positive number of seconds\n");
                return 2;
            }
            break;
        case 'M':
            errno = 0;
            max_samples = strtoull(optarg, &e, 10);
            if (errno || *e || !max_samples || *optarg == '-') {
                fprintf(stderr, "brdfwave receive: --max-samples must be a positive count\n");
                return 2;
            }
            break;
        case 'K': drop = atoi(optarg); break;
        case 'h': fputs(receive_help, stdout); return 0;
        default:
            fprintf(stderr, "brdfwave receive: unknown option or missing argument (see --help)\n");
            return 2;
        }
    }
    if (!port || !dir || optind != argc) {
        fprintf(stderr, "brdfwave receive: needs --port DEV and --out DIR (see --help)\n");
        return 2;
    }
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        fprintf(stderr, "brdfwave receive: %s is not a directory\n", dir);
        return 1;
    }
    int fd = bwh_port_open(port);
    if (fd < 0) {
        fprintf(stderr, "brdfwave receive: %s\n", bwh_last_error());
        return 1;
    }
    bwh_rx_opts_t o = {timeout, drop, 0, (size_t)max_samples};
    bwh_link_t link;
    bwh_link_init(&link, fd);
    for (long got = 0; count == 0 || got < count; got++) {
        bwh_received_t r;
        if (bwh_receive_payload(&link, &o, &r) != 0) {
            if (count == 0 && got > 0)
                break; /* until the timeout: a quiet link ends the run */
            fprintf(stderr, "brdfwave receive: %s\n", bwh_last_error());
            close(fd);
            return 1;
        }
        char path[4096];
        int st = bwh_store_payload(dir, r.id, r.payload, r.len, path, sizeof path);
        free(r.payload);
        if (st < 0 || bwh_acknowledge(&link, r.id) != 0) {
            /* not stored: not acknowledged either, the device keeps it */
            fprintf(stderr, "brdfwave receive: %s\n", bwh_last_error());
            close(fd);
            return 1;
        }
        printf("received %s%s: %zu bytes, %u resend request(s), %u bad frame(s)\n", path,
               st == 1 ? " (already stored)" : "", r.len, r.resends, r.bad_frames);
        fflush(stdout);
    }
    close(fd);
    return 0;
}
