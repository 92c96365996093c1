/* brdfwave acquire: payloads from the co-processor over I2C (docs/I2C.md),
 * woken by its data-ready line (libgpiod 1.6 edge events); the C twin of
 * `python3 -m brdfwave.acquire`. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bw_crc32.h"
#include "bw_features.h"
#include "bw_i2cmap.h"
#include "bwhost.h"
#include "cli_args.h"
#include "cli_errors.h"
#include "commands.h"

#if BW_HAVE_GPIOD
#include <gpiod.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>

static const char acquire_help[] =
    "usage: brdfwave acquire --bus N --chip CHIP --line L --out DIR [--addr 0xNN]\n"
    "                        [--once] [--timeout S] [--retries R] [--retry-interval S]\n"
    "\n"
    "Stores the payloads the co-processor offers over I2C (docs/I2C.md): waits for\n"
    "a rising edge of its data-ready line (GPIO CHIP, line L), reads the payload\n"
    "page by page from /dev/i2c-N, checks each page's CRC-32 (a bad page is asked\n"
    "for again), the payload's CRC-32 and header, decodes it, stores it as\n"
    "DIR/payload-ID-CRC.bwv (a temporary file, fsync, then a link that never\n"
    "replaces a file) and then acknowledges it. Runs until SIGTERM or SIGINT.\n"
    "  --addr A            device address (default 0x42)\n"
    "  --once              one payload, then exit (status 1 if it fails)\n"
    "  --timeout S         with --once: seconds to wait for data-ready (default: forever)\n"
    "  --retries R         reads of a bad page after the first (default 3)\n"
    "  --retry-interval S  seconds before a failed payload is tried again (default 5)\n"
    "  --max-samples N     refuse payloads that decode to more samples (default 67108864)\n";

static volatile sig_atomic_t stop_now;
static void on_signal(int sig) { (void)sig; stop_now = 1; }

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static void logmsg(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("brdfwave acquire: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

typedef struct {
    int fd;
    unsigned addr;
    char name[32];
    char err[256];
} acq_dev_t;

static int smbus(acq_dev_t *d, char rw, uint8_t cmd, int size, union i2c_smbus_data *data)
{
    struct i2c_smbus_ioctl_data a = {.read_write = rw, .command = cmd, .size = size, .data = data};
    if (ioctl(d->fd, I2C_SMBUS, &a) == 0)
        return 0;
    int e = errno;
    if (e == ENXIO || e == ENODEV || e == EREMOTEIO || e == EIO || e == ETIMEDOUT || e == EAGAIN)
        snprintf(d->err, sizeof d->err, "no answer from the device at 0x%02x on %s (NAK: %s)",
                 d->addr, d->name, strerror(e));
    else
        snprintf(d->err, sizeof d->err, "I2C transfer to 0x%02x on %s failed: %s", d->addr,
                 d->name, strerror(e));
    return -1;
}

static int rd_word(acq_dev_t *d, uint8_t reg, uint32_t *v)
{
    union i2c_smbus_data data;
    if (smbus(d, I2C_SMBUS_READ, reg, I2C_SMBUS_WORD_DATA, &data) != 0)
        return -1;
    *v = data.word;
    return 0;
}

static int rd_u32(acq_dev_t *d, uint8_t lo, uint32_t *v)
{
    uint32_t a, b;
    if (rd_word(d, lo, &a) || rd_word(d, (uint8_t)(lo + 1u), &b))
        return -1;
    *v = a | b << 16;
    return 0;
}

static int wr_byte(acq_dev_t *d, uint8_t reg, uint8_t v)
{
    union i2c_smbus_data data;
    data.byte = v;
    return smbus(d, I2C_SMBUS_WRITE, reg, I2C_SMBUS_BYTE_DATA, &data);
}

static int wr_word(acq_dev_t *d, uint8_t reg, uint16_t v)
{
    union i2c_smbus_data data;
    data.word = v;
    return smbus(d, I2C_SMBUS_WRITE, reg, I2C_SMBUS_WORD_DATA, &data);
}

/* 1 when reg reads 0 within timeout seconds, 0 if not, -1 on a bus error */
static int wait_zero(acq_dev_t *d, uint8_t reg, double timeout)
{
    double t_end = now_s() + timeout;
    for (;;) {
        uint32_t v;
        if (rd_word(d, reg, &v))
            return -1;
        if (v == 0)
            return 1;
        if (now_s() > t_end)
            return 0;
        usleep(5000);
    }
}

__attribute__((format(printf, 2, 3))) static int failf(acq_dev_t *d, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(d->err, sizeof d->err, fmt, ap);
    va_end(ap);
    return -1;
}

/* Reads page p into buf; *len and *crc as served. */
static int read_page(acq_dev_t *d, unsigned p, unsigned pages, unsigned psize, uint8_t *buf,
                     unsigned *len, uint32_t *crc)
{
    uint32_t pnum, plen;
    if (pages > 255u && wr_byte(d, BW_I2C_PAGE_HI, (uint8_t)(p >> 8)))
        return -1;
    if (wr_byte(d, BW_I2C_PAGE, (uint8_t)p) || rd_word(d, BW_I2C_PNUM, &pnum))
        return -1;
    if (pnum != p)
        return failf(d, "page %u: the window shows page %u", p, pnum);
    if (rd_word(d, BW_I2C_PLEN, &plen))
        return -1;
    if (plen < 1 || plen > psize)
        return failf(d, "page %u: length %u out of range", p, plen);
    if (rd_u32(d, BW_I2C_PCRC_LO, crc))
        return -1;
    for (unsigned k = 0; 2 * k < plen; k++) {
        uint32_t w;
        if (rd_word(d, (uint8_t)(BW_I2C_DATA + k), &w))
            return -1;
        buf[2 * k] = (uint8_t)w;
        if (2 * k + 1 < plen)
            buf[2 * k + 1] = (uint8_t)(w >> 8);
    }
    *len = plen;
    return 0;
}

/* Reads and verifies the offered payload. 0, or -1 with d->err set. */
static int read_payload(acq_dev_t *d, unsigned retries, size_t max_samples, uint32_t *id,
                        uint8_t **out, size_t *out_len, unsigned *bad)
{
    uint32_t magic, version, status, len, pages, crc;
    *out = NULL;
    *bad = 0;
    if (rd_word(d, BW_I2C_MAGIC, &magic))
        return -1;
    if (magic != BW_I2C_MAGIC_VALUE)
        return failf(d, "device at 0x%02x is not a brdfwave co-processor (MAGIC 0x%04x)", d->addr,
                     magic);
    if (rd_word(d, BW_I2C_VERSION, &version))
        return -1;
    unsigned psize = version >> 8;
    if ((version & 0xFFu) != BW_I2C_MAP_VERSION || psize < 2 || psize > 32 || psize % 2)
        return failf(d, "unsupported register map (VERSION 0x%04x)", version);
    if (rd_word(d, BW_I2C_STATUS, &status))
        return -1;
    if (!(status & BW_I2C_ST_READY)) {
        uint32_t code = 0;
        if ((status & BW_I2C_ST_ERROR) && rd_word(d, BW_I2C_ERRCODE, &code) == 0)
            return failf(d, "no payload offered (STATUS 0x%02x): the last job failed with status %d",
                         status, (int)(int16_t)code);
        return failf(d, "no payload offered (STATUS 0x%02x)", status);
    }
    if (rd_u32(d, BW_I2C_ID_LO, id) || rd_u32(d, BW_I2C_LEN_LO, &len) ||
        rd_word(d, BW_I2C_PAGES, &pages) || rd_u32(d, BW_I2C_CRC_LO, &crc))
        return -1;
    if (len == 0 || pages != (len + psize - 1) / psize)
        return failf(d, "payload %u: length %u does not match %u pages", *id, len, pages);
    uint8_t *p = malloc(len);
    if (!p)
        return failf(d, "out of memory");
    int rc = -1;
    for (unsigned pg = 1; pg <= pages; pg++) {
        unsigned want = pg < pages ? psize : len - psize * (pages - 1);
        unsigned attempt;
        for (attempt = 0;; attempt++) {
            if (stop_now) {
                failf(d, "stopped");
                goto out;
            }
            unsigned got = 0;
            uint32_t pcrc = 0;
            if (read_page(d, pg, pages, psize, p + (size_t)(pg - 1) * psize, &got, &pcrc))
                goto out;
            if (got == want && bw_crc32(p + (size_t)(pg - 1) * psize, got) == pcrc)
                break;
            ++*bad;
            if (attempt == retries) {
                failf(d, "payload %u: page %u failed its CRC-32 %u times; payload not acknowledged",
                      *id, pg, retries + 1);
                goto out;
            }
            logmsg("payload %u: page %u failed its CRC-32, asking again (%u/%u)", *id, pg,
                   attempt + 1, retries);
            if (wr_word(d, BW_I2C_RETRY, (uint16_t)pg))
                goto out;
            int z = wait_zero(d, BW_I2C_RETRY, 1.0);
            if (z < 0)
                goto out;
            if (z == 0) {
                failf(d, "payload %u: the device did not answer RETRY of page %u", *id, pg);
                goto out;
            }
        }
    }
    uint32_t c = bw_crc32(p, len);
    if (c != crc) {
        failf(d, "payload %u: CRC-32 0x%08x, the device announced 0x%08x; payload not acknowledged",
              *id, c, crc);
        goto out;
    }
    bw_header_t h;
    if (bwh_payload_check(p, len, max_samples, &h) != 0) {
        failf(d, "payload %u does not decode: %s; payload not acknowledged", *id, bwh_last_error());
        goto out;
    }
    rc = 0;
out:
    (void)wr_byte(d, BW_I2C_PAGE, 0);
    if (rc) {
        free(p);
        return -1;
    }
    *out = p;
    *out_len = len;
    return 0;
}

/* 1 when the device released the payload, 0 if it did not confirm, -1 bus error */
static int acknowledge(acq_dev_t *d, uint32_t id)
{
    if (wr_word(d, BW_I2C_ACK_LO, (uint16_t)id) || wr_word(d, BW_I2C_ACK_HI, (uint16_t)(id >> 16)) ||
        wr_byte(d, BW_I2C_CMD, BW_I2C_CMD_ACK))
        return -1;
    int z = wait_zero(d, BW_I2C_CMD, 1.0);
    if (z <= 0)
        return z;
    uint32_t st, now_id;
    if (rd_word(d, BW_I2C_STATUS, &st) || rd_u32(d, BW_I2C_ID_LO, &now_id))
        return -1;
    if (st & BW_I2C_ST_NAK)
        return 0;
    return !(st & BW_I2C_ST_READY) || now_id != id;
}

int bw_cmd_acquire(int argc, char **argv)
{
    uint32_t bus = 0, addr = BW_I2C_ADDR, line = 0, retries = 3, max_samples = 0;
    int has_bus = 0, has_line = 0, once = 0;
    const char *chip = NULL, *dir = NULL;
    double timeout = 0, interval = 5;
    const cli_opt_t opts[] = {
        {"bus", 0, CLI_U32, .dest = &bus, .lo = 0, .hi = INT32_MAX, .seen = &has_bus},
        {"addr", 0, CLI_U32, .dest = &addr, .lo = 0x03, .hi = 0x77, .hex = 1,
         .what = "--addr must be 0x03..0x77"},
        {"chip", 0, CLI_STRING, .dest = &chip},
        {"line", 0, CLI_U32, .dest = &line, .lo = 0, .hi = INT32_MAX, .seen = &has_line},
        {"out", 0, CLI_STRING, .dest = &dir},
        {"once", 0, CLI_FLAG, .dest = &once},
        {"timeout", 0, CLI_REAL, .dest = &timeout, .lo = 0, .hi = 1e9},
        {"retries", 0, CLI_U32, .dest = &retries, .lo = 0, .hi = 100},
        {"retry-interval", 0, CLI_REAL, .dest = &interval, .lo = 0, .hi = 1e9},
        {"max-samples", 0, CLI_U32, .dest = &max_samples, .lo = 1, .hi = UINT32_MAX},
        {NULL}};
    int first, st;
    if (!cli_parse(argc, argv, opts, acquire_help, &first, &st))
        return st;
    if (!has_bus || !has_line || !chip || !dir || first != argc)
        return cli_usage("needs --bus N, --chip CHIP, --line L and --out DIR");
    struct stat sb;
    if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode))
        return cli_fail("%s is not a directory", dir);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal; /* no SA_RESTART: a wait returns early */
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);

    acq_dev_t d;
    memset(&d, 0, sizeof d);
    d.addr = (unsigned)addr;
    snprintf(d.name, sizeof d.name, "/dev/i2c-%u", bus);
    d.fd = open(d.name, O_RDWR);
    if (d.fd < 0) {
        logmsg("cannot open %s: %s", d.name, strerror(errno));
        return 1;
    }
    if (ioctl(d.fd, I2C_SLAVE, (unsigned long)addr) != 0) {
        logmsg("cannot address 0x%02x on %s: %s", addr, d.name, strerror(errno));
        close(d.fd);
        return 1;
    }
    struct gpiod_chip *gc = gpiod_chip_open_lookup(chip);
    if (!gc) {
        logmsg("cannot open GPIO chip %s: %s", chip, strerror(errno));
        close(d.fd);
        return 1;
    }
    struct gpiod_line *gl = gpiod_chip_get_line(gc, (unsigned)line);
    if (!gl || gpiod_line_request_rising_edge_events(gl, "brdfwave-acquire") != 0) {
        logmsg("cannot request line %u of %s: %s", line, chip, strerror(errno));
        gpiod_chip_close(gc);
        close(d.fd);
        return 1;
    }
    double t_end = once && timeout > 0 ? now_s() + timeout : 0, holdoff = 0;
    int rc = 0;
    unsigned stored = 0;
    while (!stop_now) {
        int level = gpiod_line_get_value(gl);
        if (level < 0) {
            logmsg("cannot read line %u of %s: %s", line, chip, strerror(errno));
            rc = 1;
            break;
        }
        if (level == 0 || now_s() < holdoff) {
            double step = 0.2;
            if (t_end > 0) {
                double left = t_end - now_s();
                if (left <= 0) {
                    logmsg("no data-ready edge on %s line %u within %g s", chip, line, timeout);
                    rc = 1;
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
                rc = 1;
                break;
            }
            continue;
        }
        uint32_t id = 0;
        uint8_t *p = NULL;
        size_t n = 0;
        unsigned bad = 0;
        if (read_payload(&d, (unsigned)retries, (size_t)max_samples, &id, &p, &n, &bad) != 0) {
            if (stop_now)
                break;
            logmsg("%s", d.err);
            if (once) {
                rc = 1;
                break;
            }
            holdoff = now_s() + interval;
            continue;
        }
        char path[4096];
        int kept = bwh_store_payload(dir, id, p, n, path, sizeof path);
        free(p);
        if (kept < 0) {
            logmsg("%s; payload %u not acknowledged", bwh_last_error(), id);
            rc = 1;
            break;
        }
        int a = acknowledge(&d, id);
        if (a < 0)
            logmsg("payload %u stored, ACK failed: %s", id, d.err);
        else if (a == 0)
            logmsg("payload %u stored, but the device did not confirm the ACK", id);
        printf("stored %s%s: %zu bytes, %u page retries\n", path,
               kept == 1 ? " (already stored)" : "", n, bad);
        fflush(stdout);
        stored++;
        if (once)
            break;
    }
    if (stop_now)
        logmsg("stopped after %u payload(s)", stored);
    gpiod_line_release(gl);
    gpiod_chip_close(gc);
    close(d.fd);
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
