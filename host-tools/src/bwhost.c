#define _DEFAULT_SOURCE
#include "bwhost.h"

#include "link.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bw_crc32.h"

static _Thread_local char last_error[512];

const char *bwh_last_error(void) { return last_error; }

static int vfail(const char *fmt, va_list ap)
{
    char tmp[sizeof last_error];
    vsnprintf(tmp, sizeof tmp, fmt, ap); /* the message may quote the last one */
    memcpy(last_error, tmp, sizeof tmp);
    return -1;
}

static int fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfail(fmt, ap);
    va_end(ap);
    return -1;
}

int bwh_fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfail(fmt, ap);
    va_end(ap);
    return -1;
}

int bwh_read_file(const char *path, uint8_t **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    int std = !strcmp(path, "-");
    FILE *f = std ? stdin : fopen(path, "rb");
    if (!f)
        return fail("%s: %s", path, strerror(errno));
    if (std)
        path = "standard input";
    size_t cap = 1 << 16, n = 0;
    uint8_t *b = malloc(cap);
    if (!b) {
        if (!std)
            fclose(f);
        return fail("%s: out of memory", path);
    }
    for (;;) {
        if (n == cap) {
            uint8_t *nb = cap > SIZE_MAX / 2 ? NULL : realloc(b, cap * 2);
            if (!nb) {
                free(b);
                if (!std)
                    fclose(f);
                return fail("%s: out of memory", path);
            }
            b = nb;
            cap *= 2;
        }
        size_t r = fread(b + n, 1, cap - n, f);
        n += r;
        if (r == 0)
            break;
    }
    int err = ferror(f);
    if (!std)
        fclose(f);
    if (err) {
        free(b);
        return fail("%s: read error", path);
    }
    *buf = b;
    *len = n;
    return 0;
}

/* Writes all of buf to fd. */
static int write_fd(int fd, const void *buf, size_t len)
{
    const uint8_t *p = buf;
    while (len) {
        ssize_t w = write(fd, p, len);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        p += w;
        len -= (size_t)w;
    }
    return 0;
}

/* A new file beside `path` (same directory), created exclusively with the
 * mode a new file would get; its name goes to tmp[cap]. */
static int temp_beside(const char *path, char *tmp, size_t cap)
{
    const char *slash = strrchr(path, '/');
    int dl = slash ? (int)(slash - path + 1) : 0;
    if (snprintf(tmp, cap, "%.*s.%s.XXXXXX", dl, path, slash ? slash + 1 : path) >= (int)cap) {
        errno = ENAMETOOLONG;
        return -1;
    }
    int fd = mkstemp(tmp);
    if (fd < 0)
        return -1;
    mode_t um = umask(0);
    umask(um);
    if (fchmod(fd, 0666 & ~um) != 0) {
        close(fd);
        unlink(tmp);
        return -1;
    }
    return fd;
}

int bwh_write_file(const char *path, const void *buf, size_t len)
{
    if (!strcmp(path, "-")) {
        if (write_fd(1, buf, len) != 0)
            return fail("standard output: %s", strerror(errno));
        return 0;
    }
    struct stat st, lst;
    int exists = stat(path, &st) == 0;
    if (!exists && lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode))
        return fail("%s: a symbolic link to a missing file; not replaced", path);
    if (exists && !S_ISREG(st.st_mode)) {
        /* a device, a pipe, a socket: written to as it is, never replaced */
        if (S_ISDIR(st.st_mode))
            return fail("%s: is a directory", path);
        int fd = open(path, O_WRONLY | O_CLOEXEC);
        if (fd < 0)
            return fail("%s: %s", path, strerror(errno));
        int bad = write_fd(fd, buf, len) != 0;
        int e = errno;
        if (close(fd) != 0 && !bad) {
            bad = 1;
            e = errno;
        }
        return bad ? fail("%s: write failed: %s", path, strerror(e)) : 0;
    }
    /* a regular file (a symbolic link to one is followed): written beside
     * its target and renamed over it, so a failure leaves the old file */
    char *real = NULL;
    if (exists && lstat(path, &lst) == 0 && S_ISLNK(lst.st_mode)) {
        real = realpath(path, NULL);
        if (!real)
            return fail("%s: %s", path, strerror(errno));
        path = real;
    }
    char tmp[4096];
    int fd = temp_beside(path, tmp, sizeof tmp);
    if (fd < 0) {
        fail("%s: %s", path, strerror(errno));
        free(real);
        return -1;
    }
    int ok = write_fd(fd, buf, len) == 0;
    if (ok && exists)
        ok = fchmod(fd, st.st_mode & 07777) == 0;
    ok = (close(fd) == 0) && ok;
    if (!ok || rename(tmp, path) != 0) {
        fail("%s: write failed: %s", path, strerror(errno));
        unlink(tmp);
        free(real);
        return -1;
    }
    free(real);
    return 0;
}

/* fsync of the directory that holds path, so that a rename or link in it
 * survives a power loss */
static void sync_dir(const char *dir)
{
    int dfd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        fsync(dfd);
        close(dfd);
    }
}

/* 1 when the file at path holds exactly p[n], else 0 */
static int same_content(const char *path, const uint8_t *p, size_t n)
{
    uint8_t *b;
    size_t bl;
    if (bwh_read_file(path, &b, &bl) != 0)
        return 0;
    int same = bl == n && !memcmp(b, p, n);
    free(b);
    return same;
}

int bwh_store_payload(const char *dir, uint32_t id, const uint8_t *p, size_t n, char *path,
                      size_t cap)
{
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s/.payload-%u.XXXXXX", dir, id);
    int fd = mkstemp(tmp);
    if (fd < 0)
        return fail("cannot store payload %u in %s: %s", id, dir, strerror(errno));
    int ok = fchmod(fd, 0644) == 0 && write_fd(fd, p, n) == 0 && fsync(fd) == 0;
    int e = errno;
    ok = close(fd) == 0 && ok;
    if (!ok) {
        unlink(tmp);
        return fail("cannot store payload %u in %s: %s", id, dir, strerror(e));
    }
    /* the payload's own CRC-32 (of header and body; the CRC of a whole
     * payload, its CRC included, is the same constant for every payload) */
    uint32_t crc = bw_crc32(p, n >= BW_TRAILER_SIZE ? n - BW_TRAILER_SIZE : n);
    int rc = -1, reported = 0;
    for (unsigned k = 1; k < 1000; k++) {
        if (k == 1)
            snprintf(path, cap, "%s/payload-%u-%08x.bwv", dir, id, crc);
        else
            snprintf(path, cap, "%s/payload-%u-%08x-%u.bwv", dir, id, crc, k);
        if (link(tmp, path) == 0) {
            rc = 0;
            break;
        }
        if (errno != EEXIST) {
            fail("cannot store payload %u as %s: %s", id, path, strerror(errno));
            reported = 1;
            break;
        }
        if (same_content(path, p, n)) {
            rc = 1; /* the same payload again (its ACK was lost): kept once */
            break;
        }
    }
    if (rc < 0 && !reported)
        fail("cannot store payload %u in %s: too many files of that name", id, dir);
    unlink(tmp);
    if (rc >= 0)
        sync_dir(dir);
    return rc;
}

/* ---- .sed ------------------------------------------------------------- */

/* Parses a non-negative or negative decimal with at most 5 fraction digits
 * into units of 10^-5, exactly. */
static int parse_fixed5(const char *s, const char **end, int32_t *out)
{
    while (*s == ' ' || *s == '\t')
        s++;
    int neg = 0;
    if (*s == '-' || *s == '+')
        neg = *s++ == '-';
    if (!isdigit((unsigned char)*s) && *s != '.')
        return -1;
    int64_t v = 0;
    int digits = 0;
    while (isdigit((unsigned char)*s)) {
        v = v * 10 + (*s++ - '0');
        if (v > 100000000)
            return -1;
        digits++;
    }
    int frac = 0;
    if (*s == '.') {
        s++;
        while (isdigit((unsigned char)*s)) {
            if (frac == 5)
                return -1; /* more precision than the format carries */
            v = v * 10 + (*s++ - '0');
            frac++;
            digits++;
        }
    }
    if (!digits)
        return -1;
    while (frac++ < 5)
        v *= 10;
    if (*s && !isspace((unsigned char)*s))
        return -1;
    *end = s;
    *out = (int32_t)(neg ? -v : v);
    return 0;
}

int bwh_sed_read(const char *path, int32_t **values, uint32_t *bands, double **wavelengths)
{
    *values = NULL;
    if (wavelengths)
        *wavelengths = NULL;
    FILE *f = fopen(path, "r");
    if (!f)
        return fail("%s: %s", path, strerror(errno));
    char line[4096];
    long channels = -1;
    int in_data = 0, header_seen = 0;
    uint32_t n = 0;
    int32_t *v = NULL;
    double *wl = NULL;
    int lineno = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (!in_data) {
            if (!strncmp(line, "Channels:", 9))
                channels = strtol(line + 9, NULL, 10);
            if (!strncmp(line, "Data:", 5)) {
                if (channels < 1 || channels > (long)BW_MAX_BANDS) {
                    fclose(f);
                    return fail("%s: missing or invalid 'Channels:' header", path);
                }
                v = calloc((size_t)channels, sizeof *v);
                wl = calloc((size_t)channels, sizeof *wl);
                if (!v || !wl) {
                    free(v);
                    free(wl);
                    fclose(f);
                    return fail("%s: out of memory", path);
                }
                in_data = 1;
            }
            continue;
        }
        if (!header_seen) { /* column titles */
            header_seen = 1;
            continue;
        }
        if (!strchr(line, '\n')) {
            int cut = feof(f) || strlen(line) + 1 < sizeof line;
            free(v);
            free(wl);
            fclose(f);
            if (cut)
                return fail("%s:%d: the last row has no line end (the file is cut short)", path,
                            lineno);
            return fail("%s:%d: line longer than %zu bytes", path, lineno, sizeof line - 1);
        }
        const char *s = line;
        while (*s == ' ' || *s == '\t')
            s++;
        if (*s == '\n' || *s == '\r' || *s == 0)
            continue;
        if (n >= (uint32_t)channels) {
            free(v);
            free(wl);
            fclose(f);
            return fail("%s:%d: more data rows than 'Channels: %ld'", path, lineno, channels);
        }
        /* Wvl, Rad.(Ref.), Rad.(Target), -log Reflect., Reflect. */
        char *e;
        double cols[4];
        for (int c = 0; c < 4; c++) {
            errno = 0;
            cols[c] = strtod(s, &e);
            if (e == s || errno || !isfinite(cols[c])) {
                free(v);
                free(wl);
                fclose(f);
                return fail("%s:%d: expected 5 numeric columns", path, lineno);
            }
            s = e;
        }
        const char *end;
        if (parse_fixed5(s, &end, &v[n]) != 0) {
            free(v);
            free(wl);
            fclose(f);
            return fail("%s:%d: bad reflectance value", path, lineno);
        }
        wl[n] = cols[0];
        n++;
    }
    fclose(f);
    if (!in_data || n != (uint32_t)channels) {
        free(v);
        free(wl);
        return fail("%s: %s (%u of %ld rows)", path, in_data ? "truncated data" : "no 'Data:' section",
                    n, channels);
    }
    *values = v;
    *bands = n;
    if (wavelengths)
        *wavelengths = wl;
    else
        free(wl);
    return 0;
}

/* ---- float mapping ------------------------------------------------------ */

float bwh_bits_to_float(uint32_t bits)
{
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

uint32_t bwh_float_to_bits(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

/* The float value of an integer sample. With BW_FLAG_DECIMAL_SCALE the
 * scale stands for 10^-k exactly (1e-5 for .sed reflectance) and samples are
 * divided by 10^k in double, so decimal data comes back as the float nearest
 * its decimal value rather than one ulp off through the rounded float32
 * scale. */
typedef struct {
    double scale, offset, divisor;
    int log; /* BW_FLAG_LOG_VALUE: value = exp(offset + scale * q) */
} value_map_t;

int bwh_decimal_exponent(float scale)
{
    for (int k = 1; k <= 9; k++)
        if ((float)pow(10.0, -k) == scale)
            return k;
    return 0;
}

static value_map_t value_map(float scale, float offset, unsigned flags)
{
    value_map_t m = {scale, offset, 0, (flags & BW_FLAG_LOG_VALUE) != 0};
    int k = bwh_decimal_exponent(scale);
    if ((flags & BW_FLAG_DECIMAL_SCALE) && k)
        m.divisor = pow(10.0, k);
    return m;
}

static float map_value(const value_map_t *m, int32_t q)
{
    double v = m->offset + (m->divisor ? (double)q / m->divisor : m->scale * (double)q);
    return (float)(m->log ? exp(v) : v);
}

static int status_fail(int st)
{
    return fail("%s", bw_strerror(st));
}

static double sse_of(const int32_t *x, const int32_t *y, size_t n)
{
    double e = 0.0;
    for (size_t i = 0; i < n; i++)
        e += ((double)y[i] - x[i]) * ((double)y[i] - x[i]);
    return e;
}

#define SYM_FLAGS (BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL)

/* The same encode with the symmetry flags sym instead of *p0's; keeps
 * whichever payload is smaller (a byte budget: whichever decodes closer,
 * then the smaller), and sets the flags in *p0 when it keeps the new one.
 * *buf holds the payload of status st0 and *e0 the squared error of its
 * decoded samples; ver is scratch. */
static int try_symmetry(const bw_dims_t *dims, bw_params_t *p0, unsigned sym, const int32_t *x,
                        size_t n, int32_t *work, int32_t *ver, uint8_t **buf, size_t cap,
                        size_t *len, int st0, double *e0)
{
    bw_params_t p = *p0;
    p.flags = (uint8_t)((p.flags & ~SYM_FLAGS) | sym);
    uint8_t *alt = malloc(cap);
    size_t alen = 0;
    if (!alt)
        return st0;
    int st = bw_encode(dims, &p, x, work, ver, alt, cap, &alen);
    int take = 0;
    double e = st == BW_OK ? sse_of(x, ver, n) : 0.0;
    if (st == BW_OK) {
        if (st0 != BW_OK)
            take = 1;
        else if (p.mode == BW_MODE_BYTES)
            take = e < *e0 || (e == *e0 && alen < *len);
        else
            take = alen < *len;
    }
    if (take) {
        free(*buf);
        *buf = alt;
        *len = alen;
        *e0 = e;
        p0->flags = p.flags;
        return BW_OK;
    }
    free(alt);
    return st0;
}

int bwh_encode_i32(const bw_dims_t *dims, const int32_t *x, const bwh_encode_opts_t *o,
                   float scale, float offset, uint8_t **out, size_t *out_len)
{
    *out = NULL;
    *out_len = 0;
    int st = bw_dims_check(dims);
    if (st != BW_OK)
        return status_fail(st);
    size_t n = bw_dims_samples(dims);
    bw_params_t p;
    memset(&p, 0, sizeof p);
    p.mode = (uint8_t)o->mode;
    p.basis = (uint8_t)o->basis;
    p.scale_bits = bwh_float_to_bits(scale);
    p.offset_bits = bwh_float_to_bits(offset);
    p.flags = (uint8_t)(o->flags & BW_FLAGS_KNOWN);
    if (o->mode == BW_MODE_MAX_ERROR) {
        if (!(o->max_error >= 1.0) || o->max_error > BW_SAMPLE_MAX)
            return fail("max error must be at least 1 sample unit (and below %d)", BW_SAMPLE_MAX);
        p.max_error = (uint32_t)floor(o->max_error);
    }
    if (o->mode == BW_MODE_BYTES) {
        if (o->byte_budget > UINT32_MAX)
            p.byte_budget = UINT32_MAX;
        else
            p.byte_budget = (uint32_t)o->byte_budget;
    }
    for (size_t i = 0; i < n; i++)
        if (x[i] > BW_SAMPLE_MAX || x[i] < -BW_SAMPLE_MAX)
            return fail("sample %zu = %d is outside the codec's range +-%d", i, x[i], BW_SAMPLE_MAX);
    size_t wb = bw_work_bound(n, dims->bands), cap = bw_payload_bound(n);
    int32_t *work = malloc(wb * sizeof *work), *ver = malloc(wb * sizeof *ver);
    uint8_t *buf = malloc(cap);
    if (!work || !ver || !buf) {
        free(work);
        free(ver);
        free(buf);
        return fail("out of memory");
    }
    size_t len = 0;
    bool auto_sym = !(o->flags & (SYM_FLAGS | BWH_NO_MIRROR)) &&
                    dims->shape != BW_SHAPE_SPECTRA && !(o->flags & BW_FLAG_STREAM_ORDER);
    if (!o->device || auto_sym) {
        /* the host's encode (with auto, every symmetry that applies); before
         * a device encode it only makes the choice, so that the device's
         * payload is the host's */
        st = bw_encode(dims, &p, x, work, ver, buf, cap, &len);
        double e0 = st == BW_OK ? sse_of(x, ver, n) : 0.0;
        bool recip = dims->shape == BW_SHAPE_BRDF_FULL && dims->level_in == dims->level_out;
        static const unsigned syms[3] = {BW_FLAG_MIRROR, BW_FLAG_RECIPROCAL,
                                         BW_FLAG_MIRROR | BW_FLAG_RECIPROCAL};
        for (unsigned k = 0; auto_sym && k < (recip ? 3u : 1u); k++)
            if (st == BW_OK || st == BW_ERR_BUDGET)
                st = try_symmetry(dims, &p, syms[k], x, n, work, ver, &buf, cap, &len, st, &e0);
    }
    if (o->device) {
        /* the emulated co-processor encodes; the host checks what came back */
        bwh_rx_opts_t ro = {o->device_timeout > 0 ? o->device_timeout : 120.0, o->drop_chunk, 0,
                            SIZE_MAX};
        bwh_received_t r;
        if (strcmp(o->device, "qemu") != 0 && strcmp(o->device, "linux") != 0) {
            free(work);
            free(ver);
            free(buf);
            return fail("unknown device '%s' (known: qemu, linux)", o->device);
        }
        if (bwh_device_encode(o->device, o->firmware, dims, &p, x, &ro, &r) != 0) {
            free(work);
            free(ver);
            free(buf);
            return -1;
        }
        free(buf);
        buf = r.payload;
        len = r.len;
        if (o->device_instructions)
            *o->device_instructions = r.instructions;
        st = bw_decode(buf, len, ver, wb, ver, wb, NULL);
        for (size_t i = 0; st == BW_OK && i < n; i++) {
            int64_t e = (int64_t)ver[i] - x[i];
            if ((o->mode == BW_MODE_LOSSLESS && e != 0) ||
                (o->mode == BW_MODE_MAX_ERROR && (e > p.max_error || -e > p.max_error)))
                st = BW_ERR_VERIFY;
        }
        if (st == BW_OK && o->mode == BW_MODE_BYTES && len > o->byte_budget)
            st = BW_ERR_VERIFY;
    }
    free(work);
    free(ver);
    if (st != BW_OK) {
        free(buf);
        if (st == BW_ERR_BUDGET)
            return fail("byte budget %zu is too small for this measurement", o->byte_budget);
        return status_fail(st);
    }
    *out = buf;
    *out_len = len;
    return 0;
}

/* BW_FLAG_LOG_VALUE: the samples are round((log x - offset) / scale) on 2^20
 * levels each side of the mid-range offset, so the byte-budget search spends
 * its bits on relative rather than absolute error. */
static int encode_log(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o,
                      uint8_t **out, size_t *out_len)
{
    size_t n = bw_dims_samples(dims);
    if (o->mode != BW_MODE_BYTES)
        return fail("--relative needs --bytes or --ratio");
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || !(x[i] > 0))
            return fail("--relative needs positive finite values (sample %zu = %g)", i,
                        (double)x[i]);
        double l = log((double)x[i]);
        lo = fmin(lo, l);
        hi = fmax(hi, l);
    }
    float offset = (float)(0.5 * (lo + hi));
    double half = fmax(fabs(hi - (double)offset), fabs(lo - (double)offset));
    float scale = (float)(half > 0 ? half / 1048576.0 : 1.0);
    if (!(scale > 0) || !isfinite(scale) || !isfinite(offset))
        return fail("--relative: the value range cannot be represented");
    int32_t *q = malloc((n ? n : 1) * sizeof *q);
    if (!q)
        return fail("out of memory");
    for (size_t i = 0; i < n; i++)
        q[i] = (int32_t)nearbyint((log((double)x[i]) - (double)offset) / (double)scale);
    int rc = bwh_encode_i32(dims, q, o, scale, offset, out, out_len);
    free(q);
    return rc;
}

int bwh_encode_f32(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o, uint8_t **out,
                   size_t *out_len)
{
    if (o->flags & BW_FLAG_LOG_VALUE)
        return encode_log(dims, x, o, out, out_len);
    *out = NULL;
    *out_len = 0;
    int st = bw_dims_check(dims);
    if (st != BW_OK)
        return status_fail(st);
    size_t n = bw_dims_samples(dims);
    double maxabs = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]))
            return fail("sample %zu is %s", i, isnan(x[i]) ? "NaN" : "infinite");
        double a = fabs((double)x[i]);
        if (a > maxabs)
            maxabs = a;
    }
    double scale = o->scale;
    bwh_encode_opts_t io = *o;
    /* MAX_ERROR: the decoded value is rounded to float32, so one ulp of the
     * largest value is kept in hand; the rest is split into 3 integer steps
     * of coding error plus half a step of rounding to the integer grid. */
    double budget = 0;
    if (o->mode == BW_MODE_MAX_ERROR) {
        if (!(o->max_error > 0))
            return fail("max error must be positive");
        float top = (float)(maxabs + o->max_error);
        budget = o->max_error - ((double)nextafterf(top, INFINITY) - (double)top);
        if (!(budget > 0))
            return fail("max error %g is below the float32 resolution of the data (max |x| = %g)",
                        o->max_error, maxabs);
        io.max_error = 3;
    }
    if (!(scale > 0)) {
        switch (o->mode) {
        case BW_MODE_LOSSLESS:
            scale = 1.0;
            break;
        case BW_MODE_MAX_ERROR:
            scale = budget / 3.5;
            break;
        default:
            /* 2^23 levels: fine enough that the quantiser, not the grid,
             * sets the size between the exact coding and step 1 */
            scale = maxabs > 0 ? maxabs / 8388608.0 : 1.0;
            break;
        }
    }
    /* the header carries the scale as float32: use exactly that value */
    float scale_f = (float)scale;
    if (o->mode == BW_MODE_MAX_ERROR && !(o->scale > 0))
        while (scale_f > 0 && 3.5 * (double)scale_f > budget)
            scale_f = nextafterf(scale_f, 0);
    if (!(scale_f > 0) || !isfinite(scale_f))
        return fail("scale %g is not representable", scale);
    scale = scale_f;
    if (maxabs / scale > BW_SAMPLE_MAX)
        return fail("the data range (max |x| = %g) needs a coarser step than %g: %s", maxabs, scale,
                    o->mode == BW_MODE_MAX_ERROR ? "raise --max-error" : "give a larger --scale");
    if (o->mode == BW_MODE_MAX_ERROR && o->scale > 0) {
        io.max_error = floor((budget - 0.5 * scale) / scale);
        if (io.max_error < 1)
            return fail("max error %g is below 1.5 steps of the given scale %g", o->max_error, scale);
    }
    unsigned flags = o->scale > 0 && bwh_decimal_exponent(scale_f) ? BW_FLAG_DECIMAL_SCALE : 0u;
    value_map_t vm = value_map(scale_f, 0.0f, flags);
    int32_t *q = malloc(n * sizeof *q);
    if (!q)
        return fail("out of memory");
    for (size_t i = 0; i < n; i++) {
        double v = (double)x[i] / scale;
        double r = nearbyint(v);
        /* lossless: the value must come back as the very same float */
        if (o->mode == BW_MODE_LOSSLESS && map_value(&vm, (int32_t)r) != x[i]) {
            free(q);
            return fail("lossless needs values that are whole multiples of the scale %g "
                        "(sample %zu = %.9g); use --max-error, --bytes or --scale",
                        scale, i, (double)x[i]);
        }
        q[i] = (int32_t)r;
    }
    io.flags = o->flags | flags;
    int rc = bwh_encode_i32(dims, q, &io, scale_f, 0.0f, out, out_len);
    free(q);
    if (rc != 0)
        return rc;
    if (o->mode == BW_MODE_LOSSLESS || o->mode == BW_MODE_MAX_ERROR) {
        /* check the guarantee where the user sees it: in float32 */
        bw_header_t h;
        int32_t *s = NULL;
        float *v = NULL;
        if (bwh_decode_limit(*out, *out_len, SIZE_MAX, &h, &s, &v) != 0) {
            free(*out);
            *out = NULL;
            return -1;
        }
        double bound = o->mode == BW_MODE_LOSSLESS ? 0.0 : o->max_error;
        for (size_t i = 0; i < n; i++) {
            if (fabs((double)v[i] - (double)x[i]) > bound) {
                fail("error bound not met at sample %zu after float conversion (|%.9g - %.9g| > %g)",
                     i, (double)v[i], (double)x[i], bound);
                free(s);
                free(v);
                free(*out);
                *out = NULL;
                return -1;
            }
        }
        free(s);
        free(v);
    }
    return 0;
}

/* The header of p[len], checked, and its sample count against the limit. */
static int header_within(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h)
{
    int st = bw_header_read(p, len, h);
    if (st != BW_OK)
        return status_fail(st);
    size_t n = bw_dims_samples(&h->dims);
    if (!max_samples)
        max_samples = BWH_MAX_SAMPLES_DEFAULT;
    if (n > max_samples)
        return fail("the payload decodes to %zu samples (%.1f MiB as float32), more than the "
                    "limit of %zu (raise it with --max-samples)",
                    n, (double)n * 4 / 1048576.0, max_samples);
    return 0;
}

int bwh_payload_check(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h)
{
    if (header_within(p, len, max_samples, h) != 0)
        return -1;
    size_t n = bw_dims_samples(&h->dims);
    size_t wb = bw_work_bound(n, h->dims.bands);
    int32_t *w = malloc(wb * sizeof *w);
    if (!w)
        return fail("out of memory");
    int st = bw_decode(p, len, w, wb, w, wb, h);
    free(w);
    return st == BW_OK ? 0 : status_fail(st);
}

int bwh_decode_limit(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                     int32_t **samples, float **values)
{
    if (samples)
        *samples = NULL;
    if (values)
        *values = NULL;
    if (header_within(p, len, max_samples, h) != 0)
        return -1;
    size_t n = bw_dims_samples(&h->dims);
    size_t wb = bw_work_bound(n, h->dims.bands);
    int32_t *w = malloc(wb * sizeof *w);
    if (!w)
        return fail("out of memory");
    int st = bw_decode(p, len, w, wb, w, wb, h);
    if (st != BW_OK) {
        free(w);
        return status_fail(st);
    }
    if (values) {
        float scale = bwh_bits_to_float(h->scale_bits), off = bwh_bits_to_float(h->offset_bits);
        if (!isfinite(scale) || !isfinite(off) || scale == 0) {
            free(w);
            return fail("payload header has a zero or non-finite scale or offset");
        }
        /* without the integers the values take their place */
        float *v = samples ? malloc((n ? n : 1) * sizeof *v) : (float *)(void *)w;
        if (!v) {
            free(w);
            return fail("out of memory");
        }
        value_map_t vm = value_map(scale, off, h->flags);
        for (size_t i = 0; i < n; i++) {
            int32_t q = w[i];
            float x = map_value(&vm, q);
            if (!isfinite(x)) {
                fail("sample %zu (%d) decodes to %g, beyond float32 (scale %g, offset %g%s)", i,
                     q, (double)x, (double)scale, (double)off,
                     h->flags & BW_FLAG_LOG_VALUE ? ", logarithmic" : "");
                if (v != (float *)(void *)w)
                    free(v);
                free(w);
                return -1;
            }
            v[i] = x;
        }
        *values = v;
    }
    if (samples)
        *samples = w;
    else if (!values)
        free(w);
    return 0;
}

int bwh_decode(const uint8_t *p, size_t len, bw_header_t *h, int32_t **samples, float **values)
{
    return bwh_decode_limit(p, len, 0, h, samples, values);
}

/* ---- metrics ------------------------------------------------------------ */

void bwh_metrics(const float *ref, const float *test, size_t n, bwh_metrics_t *m)
{
    memset(m, 0, sizeof *m);
    m->n = n;
    double l1 = 0, l2 = 0, se = 0, peak = 0;
    size_t nz = 0;
    for (size_t i = 0; i < n; i++) {
        double f = ref[i], g = test[i], d = g - f;
        se += d * d;
        if (fabs(d) > m->max_abs)
            m->max_abs = fabs(d);
        if (fabs(f) > peak)
            peak = fabs(f);
        if (f == 0) {
            m->zero_ref++;
            continue;
        }
        l1 += fabs(d) / fabs(f);
        l2 += (d * d) / (f * f);
        nz++;
    }
    m->rel_l1 = nz ? 100.0 * l1 / (double)nz : 0;
    m->rel_l2 = nz ? 100.0 * sqrt(l2 / (double)nz) : 0;
    m->rmse = n ? sqrt(se / (double)n) : 0;
    m->psnr = m->rmse > 0 && peak > 0 ? 20.0 * log10(peak / m->rmse) : INFINITY;
}

const char *bwh_shape_name(unsigned s)
{
    static const char *names[] = {"spectra", "reflectance", "brdf-iso", "brdf-full"};
    return s < 4 ? names[s] : "?";
}

const char *bwh_basis_name(unsigned b)
{
    static const char *names[] = {"haar", "53", "97", "pred"};
    return b < 4 ? names[b] : "?";
}

const char *bwh_mode_name(unsigned m)
{
    static const char *names[] = {"lossless", "max-error", "bytes", "step"};
    return m < 4 ? names[m] : "?";
}
