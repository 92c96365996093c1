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
#include "link.h"

static const char receive_help[] =
    "usage: brdfwave receive --port DEV --out DIR [--count N] [--timeout S]\n"
    "\n"
    "Reads payloads from a serial port (a device's UART or the emulator's\n"
    "pseudo-terminal): checks every frame's CRC, asks the device to resend\n"
    "missing or corrupted chunks, checks the whole payload, acknowledges it and\n"
    "stores it as DIR/payload-ID.bwv (written to a temporary name, then renamed).\n"
    "  --count N     stop after N payloads (default 1; 0: until the timeout)\n"
    "  --timeout S   give up after S seconds without a frame (default 60)\n";

int bw_cmd_receive(int argc, char **argv)
{
    static const struct option opts[] = {{"port", required_argument, 0, 'p'},
                                         {"out", required_argument, 0, 'o'},
                                         {"count", required_argument, 0, 'n'},
                                         {"timeout", required_argument, 0, 't'},
                                         {"drop-chunk", required_argument, 0, 'K'},
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const char *port = NULL, *dir = NULL;
    long count = 1;
    double timeout = 60;
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
            if (*e || !(timeout > 0)) {
                fprintf(stderr, "brdfwave receive: --timeout must be positive\n");
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
    bwh_rx_opts_t o = {timeout, drop, 0};
    for (long got = 0; count == 0 || got < count; got++) {
        bwh_received_t r;
        if (bwh_receive_payload(fd, &o, &r) != 0) {
            if (count == 0 && got > 0)
                break; /* until the timeout: a quiet link ends the run */
            fprintf(stderr, "brdfwave receive: %s\n", bwh_last_error());
            close(fd);
            return 1;
        }
        char path[4096];
        snprintf(path, sizeof path, "%s/payload-%u.bwv", dir, r.id);
        if (bwh_write_file(path, r.payload, r.len) != 0) {
            fprintf(stderr, "brdfwave receive: %s\n", bwh_last_error());
            free(r.payload);
            close(fd);
            return 1;
        }
        printf("received %s: %zu bytes, %u resend request(s), %u bad frame(s)\n", path, r.len,
               r.resends, r.bad_frames);
        free(r.payload);
    }
    close(fd);
    return 0;
}
