/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The metadata record's bytes (docs/FORMAT.md, Metadata), both ways: fields
 * of tag, varint length and data; numbers as decimal integers (an arithmetic
 * sequence, or differences Rice-coded) or float32 / float64; strings with
 * their lengths, lists of them sharing prefixes and suffixes.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bw_le.h"
#include "bwh_error.h"
#include "bwh_meta.h"

enum {
    TAG_QUANTITY = 1,
    TAG_SAMPLE_TYPE = 2,
    TAG_WAVELENGTHS = 3,
    TAG_FWHM = 4,
    TAG_BAND_NAMES = 5,
    TAG_INCIDENCE = 6,
    TAG_INSTRUMENT = 7,
    TAG_SERIAL = 8,
    TAG_TIME = 9,
    TAG_LOCATION = 10,
    TAG_SPECTRUM_NAMES = 11,
    TAG_SPECTRUM_TIMES = 12,
    TAG_SPECTRUM_LOCATIONS = 13,
    TAG_MISSING = 14,
    TAG_FIELD = 15
};

enum { FORM_ARITH = 0, FORM_RICE = 1, FORM_F32 = 2, FORM_F64 = 3 };
/* with FORM_ARITH or FORM_RICE: each decimal value rounded to float32 */
#define FORM_F32_ROUNDED 4u
#define MAX_DECIMALS 15
#define RICE_ESCAPE 24 /* a quotient this large is sent as its bit length and bits */
#define MAX_LIST (1u << 24)

/* ---- writing ------------------------------------------------------------- */

typedef struct {
    uint8_t *b;
    size_t n, cap;
    int oom;
    /* the bit writer (Rice codes), MSB first */
    unsigned bits, nbits;
} wbuf_t;

static void put_bytes(wbuf_t *w, const void *p, size_t n)
{
    if (w->oom)
        return;
    if (w->n + n > w->cap) {
        size_t c = w->cap ? w->cap : 256;
        while (c < w->n + n)
            c *= 2;
        uint8_t *nb = realloc(w->b, c);
        if (!nb) {
            w->oom = 1;
            return;
        }
        w->b = nb;
        w->cap = c;
    }
    if (n)
        memcpy(w->b + w->n, p, n);
    w->n += n;
}

static void put_u8(wbuf_t *w, unsigned v)
{
    uint8_t b = (uint8_t)v;
    put_bytes(w, &b, 1);
}

static void put_varint(wbuf_t *w, uint64_t v)
{
    uint8_t b[10];
    size_t n = 0;
    for (;; v >>= 7) {
        b[n++] = (uint8_t)(v | (v > 0x7Fu ? 0x80u : 0u));
        if (v <= 0x7Fu)
            break;
    }
    put_bytes(w, b, n);
}

static uint64_t zigzag(int64_t v) { return v < 0 ? ~((uint64_t)v << 1) : (uint64_t)v << 1; }
static int64_t unzigzag(uint64_t u) { return (u & 1u) ? -(int64_t)(u >> 1) - 1 : (int64_t)(u >> 1); }

static void put_bit(wbuf_t *w, unsigned b)
{
    w->bits = w->bits << 1 | (b & 1u);
    if (++w->nbits == 8) {
        put_u8(w, w->bits);
        w->bits = w->nbits = 0;
    }
}

static void put_bits(wbuf_t *w, uint64_t v, unsigned n)
{
    while (n--)
        put_bit(w, (unsigned)(v >> n) & 1u);
}

static void flush_bits(wbuf_t *w)
{
    while (w->nbits)
        put_bit(w, 0);
}

static unsigned bit_length(uint64_t u)
{
    unsigned l = 0;
    while (u) {
        l++;
        u >>= 1;
    }
    return l;
}

static void put_rice(wbuf_t *w, uint64_t u, unsigned r)
{
    uint64_t q = u >> r;
    if (q >= RICE_ESCAPE) {
        put_bits(w, 0, RICE_ESCAPE);
        unsigned l = bit_length(u);
        put_bits(w, l, 7);
        put_bits(w, u, l);
        return;
    }
    put_bits(w, 0, (unsigned)q);
    put_bit(w, 1);
    put_bits(w, u, r);
}

static uint64_t rice_bits(uint64_t u, unsigned r)
{
    uint64_t q = u >> r;
    return q >= RICE_ESCAPE ? RICE_ESCAPE + 7u + bit_length(u) : q + 1u + r;
}

static const double pow10_tab[MAX_DECIMALS + 1] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                    1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};

static int same_double(double a, double b) { return !memcmp(&a, &b, sizeof a); }

/* a decimal's value: x / 10^k, or that rounded to float32 */
static double decimal_value(int64_t x, unsigned k, int f32)
{
    double v = (double)x / pow10_tab[k];
    return f32 ? (double)(float)v : v;
}

/* the integers x[i] with decimal_value(x[i], k, f32) == v[i] exactly, for
 * the smallest k; -1 if there is none up to MAX_DECIMALS */
static int decimal_of(const double *v, size_t n, int64_t *x, int f32)
{
    for (int k = 0; k <= MAX_DECIMALS; k++) {
        size_t i;
        for (i = 0; i < n; i++) {
            double s = v[i] * pow10_tab[k];
            if (!(fabs(s) < 9007199254740992.0))
                break;
            x[i] = (int64_t)llround(s);
            if (!same_double(decimal_value(x[i], (unsigned)k, f32), v[i]))
                break;
        }
        if (i == n)
            return k;
    }
    return -1;
}

/* The numbers of docs/FORMAT.md: count, form, then the form's data; the
 * smallest form that gives v back bit for bit. */
static void put_numbers(wbuf_t *w, const double *v, size_t n)
{
    put_varint(w, n);
    if (!n)
        return;
    int64_t *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
    if (!x || !y) {
        free(x);
        free(y);
        w->oom = 1;
        return;
    }
    int f32 = 1;
    for (size_t i = 0; i < n && f32; i++)
        f32 = same_double((double)(float)v[i], v[i]);
    /* decimals, or float32 values that are the nearest to decimals */
    int k = decimal_of(v, n, x, 0), rounded = 0;
    if (k < 0 && f32 && (k = decimal_of(v, n, x, 1)) >= 0)
        rounded = FORM_F32_ROUNDED;
    size_t best = n * (f32 ? 4u : 8u), best_order = 0;
    int form = f32 ? FORM_F32 : FORM_F64;
    unsigned best_r = 0;
    if (k >= 0) {
        int arith = 1;
        for (size_t i = 2; i < n && arith; i++)
            arith = x[i] - x[i - 1] == x[1] - x[0];
        if (arith) {
            form = FORM_ARITH;
        } else {
            /* differences of order 0, 1, 2, each pass keeping its first
             * element, and the Rice parameter of the fewest bits */
            memcpy(y, x, n * sizeof *y);
            for (size_t order = 0; order <= 2; order++) {
                if (order)
                    for (size_t i = n - 1; i > 0; i--)
                        y[i] -= y[i - 1];
                for (unsigned r = 0; r < 64; r++) {
                    uint64_t bits = 0;
                    for (size_t i = 0; i < n; i++)
                        bits += rice_bits(zigzag(y[i]), r);
                    size_t bytes = 3u + (size_t)((bits + 7) / 8);
                    if (bytes < best) {
                        best = bytes;
                        best_order = order;
                        best_r = r;
                        form = FORM_RICE;
                    }
                }
            }
        }
    }
    put_u8(w, (unsigned)form | (form <= FORM_RICE ? (unsigned)rounded : 0u));
    if (form == FORM_ARITH) {
        put_u8(w, (unsigned)k);
        put_varint(w, zigzag(x[0]));
        put_varint(w, zigzag(n > 1 ? x[1] - x[0] : 0));
    } else if (form == FORM_RICE) {
        put_u8(w, (unsigned)k);
        put_u8(w, (unsigned)best_order);
        put_u8(w, best_r);
        memcpy(y, x, n * sizeof *y);
        for (size_t order = 0; order < best_order; order++)
            for (size_t i = n - 1; i > 0; i--)
                y[i] -= y[i - 1];
        for (size_t i = 0; i < n; i++)
            put_rice(w, zigzag(y[i]), best_r);
        flush_bits(w);
    } else {
        for (size_t i = 0; i < n; i++) {
            uint8_t b[8];
            if (form == FORM_F32) {
                float f = (float)v[i];
                uint32_t u;
                memcpy(&u, &f, 4);
                bw_put_u32(b, u);
                put_bytes(w, b, 4);
            } else {
                uint64_t u;
                memcpy(&u, &v[i], 8);
                bw_put_u32(b, (uint32_t)u);
                bw_put_u32(b + 4, (uint32_t)(u >> 32));
                put_bytes(w, b, 8);
            }
        }
    }
    free(x);
    free(y);
}

static void put_string(wbuf_t *w, const char *s)
{
    size_t n = strlen(s);
    put_varint(w, n);
    put_bytes(w, s, n);
}

/* count, then per string: bytes shared with the previous one at its start,
 * at its end, and the bytes between */
static void put_strings(wbuf_t *w, const bwh_strings_t *s)
{
    put_varint(w, s->n);
    const char *prev = "";
    for (size_t i = 0; i < s->n; i++) {
        const char *c = s->s[i];
        size_t lp = strlen(prev), lc = strlen(c), p = 0, q = 0;
        while (p < lp && p < lc && prev[p] == c[p])
            p++;
        while (q < lp - p && q < lc - p && prev[lp - 1 - q] == c[lc - 1 - q])
            q++;
        put_varint(w, p);
        put_varint(w, q);
        put_varint(w, lc - p - q);
        put_bytes(w, c + p, lc - p - q);
        prev = c;
    }
}

static unsigned tz_code(int tz)
{
    return tz == BWH_TZ_LOCAL ? 0u : (unsigned)zigzag(tz) + 1u;
}

/* a field: tag, its data's length, its data (from the scratch buffer) */
static void put_field(wbuf_t *w, unsigned tag, wbuf_t *f)
{
    if (f->oom)
        w->oom = 1;
    put_u8(w, tag);
    put_varint(w, f->n);
    put_bytes(w, f->b, f->n);
    f->n = 0;
}

int bwh_meta_encode(const bwh_meta_t *m, uint8_t **area, size_t *len)
{
    *area = NULL;
    *len = 0;
    if (bwh_meta_empty(m))
        return 0;
    wbuf_t w = {0}, f = {0};
    if ((m->present & BWH_M_QUANTITY) || m->unit) {
        put_u8(&f, (unsigned)m->quantity);
        if (m->unit)
            put_bytes(&f, m->unit, strlen(m->unit));
        put_field(&w, TAG_QUANTITY, &f);
    }
    if (m->present & BWH_M_SAMPLE_TYPE) {
        put_u8(&f, (unsigned)m->sample_type);
        put_field(&w, TAG_SAMPLE_TYPE, &f);
    }
    if (m->wavelengths.n) {
        put_u8(&f, (unsigned)m->wl_unit);
        put_numbers(&f, m->wavelengths.v, m->wavelengths.n);
        put_field(&w, TAG_WAVELENGTHS, &f);
    }
    if (m->fwhm.n) {
        put_numbers(&f, m->fwhm.v, m->fwhm.n);
        put_field(&w, TAG_FWHM, &f);
    }
    if (m->band_names.n) {
        put_strings(&f, &m->band_names);
        put_field(&w, TAG_BAND_NAMES, &f);
    }
    if (m->incidence.n) {
        put_u8(&f, (unsigned)m->inc_unit);
        put_numbers(&f, m->incidence.v, m->incidence.n);
        put_field(&w, TAG_INCIDENCE, &f);
    }
    if (m->instrument) {
        put_bytes(&f, m->instrument, strlen(m->instrument));
        put_field(&w, TAG_INSTRUMENT, &f);
    }
    if (m->serial) {
        put_bytes(&f, m->serial, strlen(m->serial));
        put_field(&w, TAG_SERIAL, &f);
    }
    if (m->present & BWH_M_TIME) {
        put_varint(&f, tz_code(m->time_tz));
        put_numbers(&f, &m->time, 1);
        put_field(&w, TAG_TIME, &f);
    }
    if (m->present & BWH_M_LOCATION) {
        put_numbers(&f, &m->lat, 1);
        put_numbers(&f, &m->lon, 1);
        put_numbers(&f, &m->alt, (m->present & BWH_M_ALTITUDE) ? 1u : 0u);
        put_field(&w, TAG_LOCATION, &f);
    }
    if (m->spectrum_names.n) {
        put_strings(&f, &m->spectrum_names);
        put_field(&w, TAG_SPECTRUM_NAMES, &f);
    }
    if (m->spectrum_times.n) {
        put_varint(&f, tz_code(m->spectrum_tz));
        put_numbers(&f, m->spectrum_times.v, m->spectrum_times.n);
        put_field(&w, TAG_SPECTRUM_TIMES, &f);
    }
    if (m->spectrum_lat.n) {
        put_numbers(&f, m->spectrum_lat.v, m->spectrum_lat.n);
        put_numbers(&f, m->spectrum_lon.v, m->spectrum_lon.n);
        put_numbers(&f, m->spectrum_alt.v, m->spectrum_alt.n);
        put_field(&w, TAG_SPECTRUM_LOCATIONS, &f);
    }
    if (m->present & BWH_M_MISSING) {
        uint8_t b[8];
        uint64_t u;
        memcpy(&u, &m->missing_value, 8);
        bw_put_u32(b, (uint32_t)u);
        bw_put_u32(b + 4, (uint32_t)(u >> 32));
        put_bytes(&f, b, 8);
        put_varint(&f, m->n_missing);
        uint64_t end = 0;
        for (size_t i = 0; i < m->n_missing; i++) {
            put_varint(&f, m->missing[i][0] - end);
            put_varint(&f, m->missing[i][1]);
            end = m->missing[i][0] + m->missing[i][1];
        }
        put_field(&w, TAG_MISSING, &f);
    }
    for (size_t i = 0; i < m->n_fields; i++) {
        put_string(&f, m->keys[i]);
        put_string(&f, m->values[i]);
        put_field(&w, TAG_FIELD, &f);
    }
    free(f.b);
    if (w.oom) {
        free(w.b);
        return bwh_fail("out of memory");
    }
    if (w.n > BW_EXT_MAX - 8u) {
        free(w.b);
        return bwh_fail("metadata of %zu bytes, more than a payload holds (%u)", w.n,
                        BW_EXT_MAX - 8u);
    }
    /* the record: type, length, data */
    wbuf_t r = {0};
    put_u8(&r, BW_EXT_METADATA);
    put_varint(&r, w.n);
    put_bytes(&r, w.b, w.n);
    free(w.b);
    if (r.oom) {
        free(r.b);
        return bwh_fail("out of memory");
    }
    *area = r.b;
    *len = r.n;
    return 0;
}

/* ---- reading ------------------------------------------------------------- */

typedef struct {
    const uint8_t *p, *end;
    const char *what; /* the field being read, for the message */
    unsigned bits, nbits;
    uint64_t max_count; /* no list is longer */
} rbuf_t;

static int bad(const rbuf_t *r, const char *why)
{
    return bwh_fail("metadata record: %s: %s", r->what, why);
}

static int get_u8(rbuf_t *r, unsigned *v)
{
    if (r->p >= r->end)
        return bad(r, "cut short");
    *v = *r->p++;
    return 0;
}

static int get_varint(rbuf_t *r, uint64_t *v)
{
    uint64_t x = 0;
    for (unsigned s = 0; s < 64; s += 7) {
        if (r->p >= r->end)
            return bad(r, "cut short");
        uint8_t b = *r->p++;
        if (s == 63 && b > 1)
            break;
        x |= (uint64_t)(b & 0x7Fu) << s;
        if (!(b & 0x80u)) {
            if (s && !b)
                return bad(r, "a number not in its shortest form");
            *v = x;
            return 0;
        }
    }
    return bad(r, "a number above 64 bits");
}

static int get_count(rbuf_t *r, size_t *n)
{
    uint64_t v;
    if (get_varint(r, &v))
        return -1;
    if (v > r->max_count)
        return bad(r, "a count larger than the measurement's");
    *n = (size_t)v;
    return 0;
}

static int get_bit(rbuf_t *r, unsigned *b)
{
    if (!r->nbits) {
        if (r->p >= r->end)
            return bad(r, "Rice codes cut short");
        r->bits = *r->p++;
        r->nbits = 8;
    }
    r->nbits--;
    *b = (r->bits >> r->nbits) & 1u;
    return 0;
}

static int get_bits(rbuf_t *r, unsigned n, uint64_t *v)
{
    uint64_t x = 0;
    for (unsigned i = 0; i < n; i++) {
        unsigned b = 0;
        if (get_bit(r, &b))
            return -1;
        x = x << 1 | b;
    }
    *v = x;
    return 0;
}

static int get_rice(rbuf_t *r, unsigned k, uint64_t *u)
{
    unsigned q = 0, b = 0;
    for (;;) {
        if (get_bit(r, &b))
            return -1;
        if (b)
            break;
        if (++q == RICE_ESCAPE) {
            uint64_t l;
            if (get_bits(r, 7, &l))
                return -1;
            if (l > 64)
                return bad(r, "an escaped Rice code longer than 64 bits");
            return get_bits(r, (unsigned)l, u);
        }
    }
    uint64_t low;
    if (get_bits(r, k, &low))
        return -1;
    *u = (uint64_t)q << k | low;
    return 0;
}

static int get_numbers(rbuf_t *r, bwh_numbers_t *out)
{
    size_t n = 0;
    unsigned form = 0;
    out->n = 0;
    out->v = NULL;
    if (get_count(r, &n))
        return -1;
    if (!n)
        return 0;
    if (get_u8(r, &form))
        return -1;
    double *v = malloc(n * sizeof *v);
    if (!v)
        return bwh_fail("out of memory");
    int rc = 0;
    int rounded = form == (FORM_ARITH | FORM_F32_ROUNDED) || form == (FORM_RICE | FORM_F32_ROUNDED);
    if (rounded)
        form &= ~FORM_F32_ROUNDED;
    if (form == FORM_ARITH || form == FORM_RICE) {
        unsigned k = 0, order = 0, rp = 0;
        if (get_u8(r, &k) || (k > MAX_DECIMALS && (rc = bad(r, "more than 15 decimals")))) {
            free(v);
            return -1;
        }
        if (form == FORM_ARITH) {
            uint64_t a, d;
            rc = get_varint(r, &a) || get_varint(r, &d);
            for (size_t i = 0; !rc && i < n; i++)
                v[i] = decimal_value(
                    (int64_t)((uint64_t)unzigzag(a) + (uint64_t)unzigzag(d) * i), k, rounded);
        } else {
            rc = get_u8(r, &order) || get_u8(r, &rp);
            if (!rc && (order > 2 || rp > 63))
                rc = bad(r, "bad order or Rice parameter");
            int64_t *x = rc ? NULL : malloc(n * sizeof *x);
            if (!rc && !x)
                rc = bwh_fail("out of memory");
            r->nbits = 0;
            for (size_t i = 0; !rc && i < n; i++) {
                uint64_t u = 0;
                rc = get_rice(r, rp, &u);
                x[i] = unzigzag(u);
            }
            r->nbits = 0; /* padding to the byte */
            for (unsigned o = 0; !rc && o < order; o++)
                for (size_t i = 1; i < n; i++)
                    x[i] = (int64_t)((uint64_t)x[i] + (uint64_t)x[i - 1]);
            for (size_t i = 0; !rc && i < n; i++)
                v[i] = decimal_value(x[i], k, rounded);
            free(x);
        }
    } else if (form == FORM_F32 || form == FORM_F64) {
        size_t es = form == FORM_F32 ? 4u : 8u;
        if ((size_t)(r->end - r->p) / es < n) {
            rc = bad(r, "cut short");
        } else {
            for (size_t i = 0; i < n; i++, r->p += es) {
                if (es == 4) {
                    uint32_t u = bw_get_u32(r->p);
                    float f;
                    memcpy(&f, &u, 4);
                    v[i] = f;
                } else {
                    uint64_t u = bw_get_u32(r->p) | (uint64_t)bw_get_u32(r->p + 4) << 32;
                    memcpy(&v[i], &u, 8);
                }
            }
        }
    } else {
        rc = bad(r, "unknown number form");
    }
    if (rc) {
        free(v);
        return -1;
    }
    out->n = n;
    out->v = v;
    return 0;
}

static int check_text(rbuf_t *r, const uint8_t *s, size_t n)
{
    if (memchr(s, 0, n))
        return bad(r, "a text with a NUL byte");
    return 0;
}

static int get_text(rbuf_t *r, size_t n, char **out)
{
    if ((size_t)(r->end - r->p) < n)
        return bad(r, "a text cut short");
    if (check_text(r, r->p, n))
        return -1;
    char *s = malloc(n + 1);
    if (!s)
        return bwh_fail("out of memory");
    memcpy(s, r->p, n);
    s[n] = 0;
    r->p += n;
    *out = s;
    return 0;
}

static int get_string(rbuf_t *r, char **out)
{
    uint64_t n;
    if (get_varint(r, &n))
        return -1;
    if (n > (uint64_t)(r->end - r->p))
        return bad(r, "a text cut short");
    return get_text(r, (size_t)n, out);
}

static int get_strings(rbuf_t *r, bwh_strings_t *out)
{
    size_t n = 0;
    if (get_count(r, &n))
        return -1;
    if (n > (size_t)(r->end - r->p) / 3u)
        return bad(r, "more texts than bytes");
    out->s = n ? calloc(n, sizeof(char *)) : NULL;
    if (n && !out->s)
        return bwh_fail("out of memory");
    out->n = n;
    const char *prev = "";
    for (size_t i = 0; i < n; i++) {
        uint64_t p, q, mid;
        if (get_varint(r, &p) || get_varint(r, &q) || get_varint(r, &mid))
            return -1;
        size_t lp = strlen(prev);
        if (p > lp || q > lp - p)
            return bad(r, "a text shares more than the one before has");
        if (mid > (uint64_t)(r->end - r->p))
            return bad(r, "a text cut short");
        if (check_text(r, r->p, (size_t)mid))
            return -1;
        char *s = malloc((size_t)(p + mid + q) + 1);
        if (!s)
            return bwh_fail("out of memory");
        memcpy(s, prev, (size_t)p);
        memcpy(s + p, r->p, (size_t)mid);
        memcpy(s + p + mid, prev + lp - q, (size_t)q);
        s[p + mid + q] = 0;
        r->p += mid;
        out->s[i] = s;
        prev = s;
    }
    return 0;
}

static int get_tz(rbuf_t *r, int *tz)
{
    uint64_t c;
    if (get_varint(r, &c))
        return -1;
    if (c == 0) {
        *tz = BWH_TZ_LOCAL;
        return 0;
    }
    int64_t z = unzigzag(c - 1);
    if (z < -BWH_TZ_MAX || z > BWH_TZ_MAX)
        return bad(r, "a time zone beyond +-18 h");
    *tz = (int)z;
    return 0;
}

static int one_number(rbuf_t *r, double *v, int may_be_none)
{
    bwh_numbers_t n;
    if (get_numbers(r, &n))
        return -1;
    if (n.n > 1 || (!n.n && !may_be_none)) {
        free(n.v);
        return bad(r, "expected one number");
    }
    if (n.n)
        *v = n.v[0];
    free(n.v);
    return n.n ? 1 : 0;
}

static const char *const tag_names[] = {
    "", "quantity", "sample type", "wavelengths", "bandwidths", "band names",
    "incidence angles", "instrument", "serial", "time", "location", "spectrum names",
    "spectrum times", "spectrum locations", "missing samples", "free field"};

/* one field's data, all of r */
static int get_field(rbuf_t *r, unsigned tag, bwh_meta_t *m)
{
    unsigned u = 0;
    switch (tag) {
    case TAG_QUANTITY:
        if (get_u8(r, &u))
            return -1;
        if (u >= BWH_Q_COUNT)
            return bad(r, "unknown quantity");
        m->quantity = (int)u;
        m->present |= BWH_M_QUANTITY;
        return r->p < r->end ? get_text(r, (size_t)(r->end - r->p), &m->unit) : 0;
    case TAG_SAMPLE_TYPE:
        if (get_u8(r, &u))
            return -1;
        if (u == 0 || u >= BWH_ST_COUNT)
            return bad(r, "unknown sample type");
        m->sample_type = (int)u;
        m->present |= BWH_M_SAMPLE_TYPE;
        return 0;
    case TAG_WAVELENGTHS:
        if (get_u8(r, &u))
            return -1;
        if (u >= BWH_WL_COUNT)
            return bad(r, "unknown wavelength unit");
        m->wl_unit = (int)u;
        return get_numbers(r, &m->wavelengths);
    case TAG_FWHM:
        return get_numbers(r, &m->fwhm);
    case TAG_BAND_NAMES:
        return get_strings(r, &m->band_names);
    case TAG_INCIDENCE:
        if (get_u8(r, &u))
            return -1;
        if (u >= BWH_ANGLE_COUNT)
            return bad(r, "unknown angle unit");
        m->inc_unit = (int)u;
        return get_numbers(r, &m->incidence);
    case TAG_INSTRUMENT:
        return get_text(r, (size_t)(r->end - r->p), &m->instrument);
    case TAG_SERIAL:
        return get_text(r, (size_t)(r->end - r->p), &m->serial);
    case TAG_TIME:
        if (get_tz(r, &m->time_tz) || one_number(r, &m->time, 0) < 0)
            return -1;
        m->present |= BWH_M_TIME;
        return 0;
    case TAG_LOCATION: {
        int a;
        if (one_number(r, &m->lat, 0) < 0 || one_number(r, &m->lon, 0) < 0 ||
            (a = one_number(r, &m->alt, 1)) < 0)
            return -1;
        m->present |= BWH_M_LOCATION | (a ? BWH_M_ALTITUDE : 0u);
        return 0;
    }
    case TAG_SPECTRUM_NAMES:
        return get_strings(r, &m->spectrum_names);
    case TAG_SPECTRUM_TIMES:
        return get_tz(r, &m->spectrum_tz) || get_numbers(r, &m->spectrum_times) ? -1 : 0;
    case TAG_SPECTRUM_LOCATIONS:
        if (get_numbers(r, &m->spectrum_lat) || get_numbers(r, &m->spectrum_lon) ||
            get_numbers(r, &m->spectrum_alt))
            return -1;
        if (m->spectrum_lat.n != m->spectrum_lon.n || !m->spectrum_lat.n ||
            (m->spectrum_alt.n && m->spectrum_alt.n != m->spectrum_lat.n))
            return bad(r, "latitudes, longitudes and altitudes of different counts");
        return 0;
    case TAG_MISSING: {
        if (r->end - r->p < 8)
            return bad(r, "cut short");
        uint64_t bits = bw_get_u32(r->p) | (uint64_t)bw_get_u32(r->p + 4) << 32;
        memcpy(&m->missing_value, &bits, 8);
        r->p += 8;
        /* runs are not bounded by the bands or the spectra, only by the
         * bytes (2 at least each) */
        uint64_t n = 0;
        if (get_varint(r, &n))
            return -1;
        if (!n || n > (uint64_t)(r->end - r->p) / 2u)
            return bad(r, "a bad number of runs");
        m->missing = malloc(n * sizeof *m->missing);
        if (!m->missing)
            return bwh_fail("out of memory");
        uint64_t end = 0;
        for (size_t i = 0; i < n; i++) {
            uint64_t gap, len;
            if (get_varint(r, &gap) || get_varint(r, &len))
                return -1;
            if (!len || gap > UINT64_MAX / 4 - end || len > UINT64_MAX / 4 - end - gap)
                return bad(r, "an empty or overflowing run");
            m->missing[i][0] = end + gap;
            m->missing[i][1] = len;
            m->n_missing = i + 1;
            end += gap + len;
        }
        m->present |= BWH_M_MISSING;
        return 0;
    }
    case TAG_FIELD: {
        char *k = NULL, *v = NULL;
        int rc = get_string(r, &k) || get_string(r, &v) ? -1 : 0;
        if (!rc && !*k)
            rc = bad(r, "a free field without a name");
        if (!rc)
            rc = bwh_meta_add_field(m, k, v);
        free(k);
        free(v);
        return rc;
    }
    default:
        r->p = r->end; /* a later version's field: skipped */
        return 0;
    }
}

int bwh_meta_decode(const uint8_t *data, size_t len, bwh_meta_t *m)
{
    return bwh_meta_decode_limit(data, len, MAX_LIST, m);
}

int bwh_meta_decode_limit(const uint8_t *data, size_t len, uint64_t max_count, bwh_meta_t *m)
{
    bwh_meta_init(m);
    /* (no arithmetic on a NULL pointer: an empty record may come as one) */
    rbuf_t r = {data, len ? data + len : data, "field", 0, 0, max_count};
    unsigned last = 0;
    while (r.p < r.end) {
        unsigned tag = 0;
        uint64_t n = 0;
        r.what = "field";
        if (get_u8(&r, &tag) || get_varint(&r, &n))
            goto fail;
        if (tag == 0 || tag < last || (tag == last && tag != TAG_FIELD)) {
            bad(&r, "fields out of order or repeated");
            goto fail;
        }
        last = tag;
        if (n > (uint64_t)(r.end - r.p)) {
            r.what = tag < sizeof tag_names / sizeof *tag_names ? tag_names[tag] : "field";
            bad(&r, "longer than the record");
            goto fail;
        }
        rbuf_t f = {r.p, r.p + n,
                    tag < sizeof tag_names / sizeof *tag_names ? tag_names[tag] : "field", 0, 0,
                    max_count};
        if (get_field(&f, tag, m))
            goto fail;
        if (f.p != f.end) {
            bad(&f, "bytes left over");
            goto fail;
        }
        r.p += n;
    }
    return 0;
fail:
    bwh_meta_free(m);
    return -1;
}

int bwh_meta_of_payload(const uint8_t *p, size_t len, const bw_header_t *h, bwh_meta_t *m)
{
    bwh_meta_init(m);
    if (!h->ext_len)
        return 0;
    if ((size_t)h->ext_off + h->ext_len > len)
        return bwh_fail("metadata: the extension area lies outside the payload");
    size_t pos = 0;
    uint8_t type;
    const uint8_t *d;
    uint32_t dl;
    int found = 0;
    while (bw_ext_next(p + h->ext_off, h->ext_len, &pos, &type, &d, &dl)) {
        if (type != BW_EXT_METADATA)
            continue;
        if (found++) {
            bwh_meta_free(m);
            return bwh_fail("metadata record: more than one");
        }
        /* no list is longer than the bands or the spectra */
        uint64_t most = h->dims.bands > h->dims.n_in ? h->dims.bands : h->dims.n_in;
        if (bwh_meta_decode_limit(d, dl, most < 3 ? 3 : most, m) != 0)
            return -1;
    }
    if (found && bwh_meta_check(m, &h->dims) != 0) {
        bwh_meta_free(m);
        return -1;
    }
    return 0;
}
