/* SPDX-License-Identifier: BSD-2-Clause */
/* brdfwave acquire: payloads from the co-processor over I2C (docs/I2C.md),
 * woken by its data-ready line (libgpiod 1.6 edge events): the I2C client
 * of the library (bwh_i2c.h) over i2c-dev; `python3 -m brdfwave.acquire`
 * runs the same client over smbus2. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bw_features.h"
#include "bw_i2cmap.h"
#include "bwh_i2c.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "cli_progress.h"
#include "commands.h"

#if BW_HAVE_GPIOD
#include <gpiod.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>

static const char acquire_help[] =
    "usage: brdfwave acquire --bus N --chip CHIP --line L --out DIR [--addr 0xNN]\n"
    "                        [--once] [--timeout S] [--retries R] [--retry-interval S]\n"
    "                        [--resume DIR/payload-ID-CRC.part]\n"
    "\n"
    "Stores the payloads the co-processor offers over I2C (docs/I2C.md): waits for\n"
    "a rising edge of its data-ready line (GPIO CHIP, line L), reads the payload\n"
    "page by page from /dev/i2c-N, checks each page's CRC-32 (a bad page is asked\n"
    "for again), the payload's CRC-32 and header, decodes it, stores it as\n"
    "DIR/payload-ID-CRC.bwv (a temporary file, fsync, then a link that never\n"
    "replaces a file) and then acknowledges it. Runs until SIGTERM or SIGINT.\n"
    "A page that never verifies (or a device that stops answering) leaves the\n"
    "payload incomplete: what arrived is kept as DIR/payload-ID-CRC.part.bwv (the\n"
    "missing pages zero; `brdfwave decode` decodes the segments it holds) and\n"
    "DIR/payload-ID-CRC.part (which pages are missing), and the next attempt\n"
    "reads only the missing pages of that payload (the device offers it until\n"
    "it is acknowledged); once whole it is stored and both files removed.\n"
    "  --addr A            device address (default 0x42)\n"
    "  --once              one payload, then exit (status 1 if it fails, 3 if it\n"
    "                      stays incomplete)\n"
    "  --timeout S         with --once: seconds to wait for data-ready (default: forever)\n"
    "  --retries R         reads of a bad page after the first (default 3)\n"
    "  --retry-interval S  seconds before a failed payload is tried again (default 5)\n"
    "  --max-samples N     refuse payloads that decode to more samples (default 67108864)\n"
    "  --resume FILE       an incomplete payload kept before (its .part or .part.bwv):\n"
    "                      if the device still offers it, only its missing pages are read\n"
    "On a terminal a progress line shows how long it has waited for data-ready.\n";

static volatile sig_atomic_t stop_now;
static void on_signal(int sig) { (void)sig; stop_now = 1; }

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static void logmsg(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void logmsg(const char *fmt, ...)
{
    va_list ap;
    cli_progress_end(); /* the waiting line, if shown, makes room */
    va_start(ap, fmt);
    fputs("brdfwave acquire: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

/* ---- the SMBus transfers over i2c-dev ----------------------------------------- */

static int smbus(int fd, char rw, uint8_t cmd, int size, union i2c_smbus_data *data)
{
    struct i2c_smbus_ioctl_data a = {.read_write = rw, .command = cmd, .size = size, .data = data};
    return ioctl(fd, I2C_SMBUS, &a) == 0 ? 0 : -errno;
}

static int read_word(void *ctx, uint8_t reg, uint16_t *v)
{
    union i2c_smbus_data data;
    int e = smbus(*(int *)ctx, I2C_SMBUS_READ, reg, I2C_SMBUS_WORD_DATA, &data);
    if (!e)
        *v = data.word;
    return e;
}

static int write_byte(void *ctx, uint8_t reg, uint8_t v)
{
    union i2c_smbus_data data;
    data.byte = v;
    return smbus(*(int *)ctx, I2C_SMBUS_WRITE, reg, I2C_SMBUS_BYTE_DATA, &data);
}

static int write_word(void *ctx, uint8_t reg, uint16_t v)
{
    union i2c_smbus_data data;
    data.word = v;
    return smbus(*(int *)ctx, I2C_SMBUS_WRITE, reg, I2C_SMBUS_WORD_DATA, &data);
}

static void log_line(void *ctx, const char *line)
{
    (void)ctx;
    logmsg("%s", line);
}

static int stop_asked(void *ctx)
{
    (void)ctx;
    return stop_now;
}

int bw_cmd_acquire(int argc, char **argv)
{
    uint32_t bus = 0, addr = BW_I2C_ADDR, line = 0, retries = 3, max_samples = 0;
    int has_bus = 0, has_line = 0, once = 0;
    const char *chip = NULL, *dir = NULL, *resume = NULL;
    double timeout = 0, interval = 5;
    const cli_opt_t opts[] = {
        {"bus", 0, CLI_U32, .dest = &bus, .hi = INT32_MAX, .seen = &has_bus},
        {"addr", 0, CLI_U32, .dest = &addr, .lo = 0x03, .hi = 0x77, .hex = 1,
         .what = "--addr must be 0x03..0x77"},
        {"chip", 0, CLI_STRING, .dest = &chip},
        {"line", 0, CLI_U32, .dest = &line, .hi = INT32_MAX, .seen = &has_line},
        {"out", 0, CLI_STRING, .dest = &dir},
        {"once", 0, CLI_FLAG, .dest = &once},
        {"timeout", 0, CLI_REAL, .dest = &timeout, .lo = 0, .hi = 1e9},
        {"retries", 0, CLI_U32, .dest = &retries, .hi = 100},
        {"retry-interval", 0, CLI_REAL, .dest = &interval, .lo = 0, .hi = 1e9},
        {"max-samples", 0, CLI_U32, .dest = &max_samples, .lo = 1, .hi = UINT32_MAX},
        {"resume", 0, CLI_STRING, .dest = &resume},
        {NULL}};
    int st;
    if (!cli_parse(argc, argv, opts, acquire_help, NULL, &st))
        return st;
    if (!has_bus || !has_line || !chip || !dir)
        return cli_usage("needs --bus N, --chip CHIP, --line L and --out DIR");
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return cli_fail("%s is not a directory", dir);
    /* what arrived of a payload not yet whole: its missing pages are read
     * next (bwh_i2c_read_partial) */
    bwh_partial_t part;
    memset(&part, 0, sizeof part);
    if (resume && bwh_partial_load(resume, &part) != 0)
        return cli_fail("%s", bwh_last_error());
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: a wait returns early */
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);

    char bus_name[32];
    snprintf(bus_name, sizeof bus_name, "/dev/i2c-%u", bus);
    int fd = open(bus_name, O_RDWR);
    if (fd < 0) {
        bwh_partial_free(&part);
        return cli_fail("cannot open %s: %s", bus_name, strerror(errno));
    }
    if (ioctl(fd, I2C_SLAVE, (unsigned long)addr) != 0) {
        close(fd);
        bwh_partial_free(&part);
        return cli_fail("cannot address 0x%02x on %s: %s", addr, bus_name, strerror(errno));
    }
    const bwh_i2c_t dev = {read_word, write_byte, write_word, log_line, stop_asked, &fd,
                           addr, bus_name};
    struct gpiod_chip *gc = gpiod_chip_open_lookup(chip);
    if (!gc) {
        close(fd);
        bwh_partial_free(&part);
        return cli_fail("cannot open GPIO chip %s: %s", chip, strerror(errno));
    }
    struct gpiod_line *gl = gpiod_chip_get_line(gc, (unsigned)line);
    if (!gl || gpiod_line_request_rising_edge_events(gl, "brdfwave-acquire") != 0) {
        int e = errno;
        gpiod_chip_close(gc);
        close(fd);
        bwh_partial_free(&part);
        return cli_fail("cannot request line %u of %s: %s", line, chip, strerror(e));
    }
    double t_end = once && timeout > 0 ? now_s() + timeout : 0, holdoff = 0;
    int rc = CLI_EXIT_OK;
    unsigned stored = 0;
    int waiting = 0;
    while (!stop_now) {
        int level = gpiod_line_get_value(gl);
        if (level < 0) {
            logmsg("cannot read line %u of %s: %s", line, chip, strerror(errno));
            rc = CLI_EXIT_FAIL;
            break;
        }
        if (level == 0 || now_s() < holdoff) {
            if (!waiting) { /* a terminal shows how long it has waited */
                cli_progress_start("waiting for data-ready on %s line %u (%u stored)", chip, line,
                                   stored);
                waiting = 1;
            }
            if (t_end > 0)
                cli_progress_set(timeout - (t_end - now_s()), timeout);
            double step = 0.2;
            if (t_end > 0) {
                double left = t_end - now_s();
                if (left <= 0) {
                    logmsg("no data-ready edge on %s line %u within %g s", chip, line, timeout);
                    rc = CLI_EXIT_FAIL;
                    break;
                }
                if (left < step)
                    step = left;
            }
            struct timespec ts = {(time_t)step, (long)((step - (double)(time_t)step) * 1e9)};
            int w = gpiod_line_event_wait(gl, &ts);
            if (w == 1) {
                struct gpiod_line_event ev;
                gpiod_line_event_read(gl, &ev);
                holdoff = 0;
            } else if (w < 0 && errno != EINTR) {
                logmsg("waiting for %s line %u: %s", chip, line, strerror(errno));
                rc = CLI_EXIT_FAIL;
                break;
            }
            continue;
        }
        cli_progress_end();
        waiting = 0;
        bwh_i2c_payload_t got;
        int r = bwh_i2c_read_partial(&dev, retries, max_samples, &part, &got);
        char path[4096];
        if (r == 1) { /* kept as it is; its missing pages read next time */
            char why[600];
            snprintf(why, sizeof why, "%s", bwh_last_error());
            if (bwh_partial_store(dir, &part, path, sizeof path) != 0)
                logmsg("%s; what arrived could not be kept: %s", why, bwh_last_error());
            else
                logmsg("%s; kept as %s.bwv, %u of %u pages missing%s", why, path,
                       bwh_partial_missing(&part), part.parts,
                       once ? "" : "; they are read again next");
        }
        if (r != 0) {
            if (r == BWH_I2C_STOPPED || stop_now)
                break;
            if (r < 0)
                logmsg("%s", bwh_last_error());
            if (once) {
                rc = r == 1 ? CLI_EXIT_INCOMPLETE : CLI_EXIT_FAIL;
                break;
            }
            holdoff = now_s() + interval;
            continue;
        }
        int kept = bwh_store_payload(dir, got.id, got.payload, got.len, path, sizeof path);
        if (kept >= 0) { /* stored whole: what was kept of it goes */
            bwh_partial_forget(dir, got.id, got.payload, got.len);
            if (resume)
                bwh_partial_remove(resume);
        }
        free(got.payload);
        if (kept < 0) {
            logmsg("%s; payload %u not acknowledged", bwh_last_error(), got.id);
            rc = CLI_EXIT_FAIL;
            break;
        }
        int a = bwh_i2c_acknowledge(&dev, got.id, 1.0);
        if (a < 0)
            logmsg("payload %u stored, ACK failed: %s", got.id, bwh_last_error());
        else if (a == 0)
            logmsg("payload %u stored, but the device did not confirm the ACK", got.id);
        printf("stored %s%s: %zu bytes, %u page retries\n", path,
               kept == 1 ? " (already stored)" : "", got.len, got.bad_pages);
        fflush(stdout);
        stored++;
        if (once)
            break;
    }
    cli_progress_end();
    if (stop_now)
        logmsg("stopped after %u payload(s)", stored);
    gpiod_line_release(gl);
    gpiod_chip_close(gc);
    close(fd);
    bwh_partial_free(&part);
    return rc;
}

#else /* !BW_HAVE_GPIOD */

int bw_cmd_acquire(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    return cli_fail("this brdfwave was built without libgpiod (apt-get install libgpiod-dev, "
                    "then rebuild)");
}

#endif
