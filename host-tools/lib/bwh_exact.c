/* SPDX-License-Identifier: BSD-2-Clause */
/* Float32 values kept bit for bit (bwh_exact.h). */
#include "bwh_exact.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "bwh_ext.h"
#include "bwh_values.h"

#define MAX_S 8u           /* low bits: 2^32 bit patterns over the core's 2^25 */
#define EXC_SHARE 64u      /* a scale may leave one sample in this many to exceptions */
#define EXC_BYTES (5u + 4u) /* an exception in the tail at most: gap, bits */

/* the float's bits as an integer in the order of the values: sign and
 * magnitude to two's complement (-0.0 -> -1, just below +0.0 -> 0); the
 * same operation maps back */
static int32_t monotone(uint32_t b)
{
    return (int32_t)(b & 0x80000000u ? b ^ 0x7FFFFFFFu : b);
}

static uint32_t unmonotone(int32_t m)
{
    uint32_t b = (uint32_t)m;
    return m < 0 ? b ^ 0x7FFFFFFFu : b;
}

void bwh_exact_free(bwh_exact_t *m)
{
    free(m->q);
    free(m->rec);
    free(m->tail);
    memset(m, 0, sizeof *m);
}

/* The record and the tail: map, planes (low[n] of s bits, may be NULL), the
 * exceptions idx[k] of x. */
static int build(bwh_exact_t *m, const float *x, size_t n, const uint8_t *low, const size_t *idx,
                 size_t k)
{
    size_t plane = m->map == BWH_EXACT_PLANES ? (n * m->s + 7u) / 8u : 0u;
    size_t cap = plane + k * EXC_BYTES;
    uint8_t *t = malloc(cap ? cap : 1);
    if (!t)
        return bwh_fail("out of memory");
    size_t tl = 0;
    if (plane) {
        /* the low bits, sample after sample, most significant first */
        memset(t, 0, plane);
        uint64_t acc = 0;
        unsigned nb = 0;
        for (size_t i = 0; i < n; i++) {
            acc = acc << m->s | low[i];
            nb += m->s;
            while (nb >= 8u) {
                t[tl++] = (uint8_t)(acc >> (nb - 8u));
                nb -= 8u;
            }
        }
        if (nb)
            t[tl++] = (uint8_t)(acc << (8u - nb));
    }
    for (size_t j = 0; j < k; j++) {
        size_t gap = idx[j] - (j ? idx[j - 1] + 1u : 0u);
        tl += bwh_varint_put(t + tl, (uint32_t)gap);
        uint32_t b = bwh_float_to_bits(x[idx[j]]);
        for (unsigned i = 0; i < 4; i++)
            t[tl++] = (uint8_t)(b >> (8 * i));
    }
    if (tl > UINT32_MAX) {
        free(t);
        return bwh_fail("float exact: a tail of %zu bytes is too long", tl);
    }
    uint8_t d[5 + 1 + 1 + 4 + 5];
    size_t dl = bwh_varint_put(d, (uint32_t)tl);
    d[dl++] = (uint8_t)m->map;
    if (m->map == BWH_EXACT_PLANES) {
        d[dl++] = (uint8_t)m->s;
        for (unsigned i = 0; i < 4; i++)
            d[dl++] = (uint8_t)((uint32_t)m->c >> (8 * i));
    }
    dl += bwh_varint_put(d + dl, (uint32_t)k);
    m->rec_len = bwh_ext_put(NULL, BW_EXT_FLOAT_EXACT, d, dl);
    m->rec = malloc(m->rec_len);
    if (!m->rec) {
        free(t);
        return bwh_fail("out of memory");
    }
    bwh_ext_put(m->rec, BW_EXT_FLOAT_EXACT, d, dl);
    m->tail = t;
    m->tail_len = tl;
    m->n_exc = k;
    return 0;
}

int bwh_exact_exceptions(const float *x, const size_t *idx, size_t k, bwh_exact_t *m)
{
    memset(m, 0, sizeof *m);
    m->map = BWH_EXACT_VALUES;
    return build(m, x, 0, NULL, idx, k);
}

/* the lowest power k >= 0 with x * 2^k whole, for a finite x; 0 for zeros */
static int binary_exponent(float x)
{
    uint32_t b = bwh_float_to_bits(x) & 0x7FFFFFFFu;
    if (!b)
        return 0;
    uint32_t e = b >> 23, mant = b & 0x7FFFFFu;
    int lsb;
    if (e) {
        mant |= 0x800000u;
        lsb = (int)e - 150;
    } else {
        lsb = -149;
    }
    while (!(mant & 1u)) {
        mant >>= 1;
        lsb++;
    }
    return lsb < 0 ? -lsb : 0;
}

static bool is_neg_zero(float x)
{
    return bwh_float_to_bits(x) == 0x80000000u;
}

/* A scale that gives back every value but at most max_exc of them (whose
 * positions go to exc[]): binary 2^-k, or decimal 10^-k. Fills q[] and the
 * map; returns the number of exceptions, or -1 when no scale fits. */
static long try_scale(const float *x, size_t n, bool decimal, int k, int32_t *q, size_t *exc,
                      size_t max_exc, double *maxq)
{
    bwh_value_map_t vm = bwh_value_map(decimal ? (float)pow(10.0, -k) : ldexpf(1.0f, -k), 0.0f,
                                       decimal ? BW_FLAG_DECIMAL_SCALE : 0u);
    double mul = decimal ? pow(10.0, k) : ldexp(1.0, k);
    size_t ne = 0;
    int32_t prev = 0;
    *maxq = 0;
    for (size_t i = 0; i < n; i++) {
        double r = isfinite(x[i]) ? nearbyint((double)x[i] * mul) : 0.0;
        bool ok = isfinite(x[i]) && fabs(r) <= BW_SAMPLE_MAX && !is_neg_zero(x[i]) &&
                  bwh_float_to_bits(bwh_value_of(&vm, (int32_t)r)) == bwh_float_to_bits(x[i]);
        if (!ok) {
            if (ne == max_exc)
                return -1;
            exc[ne++] = i;
            q[i] = prev; /* the sample before: cheap to code */
            continue;
        }
        q[i] = prev = (int32_t)r;
        *maxq = fmax(*maxq, fabs(r));
    }
    return (long)ne;
}

int bwh_exact_map(const float *x, size_t n, bwh_exact_t *m)
{
    memset(m, 0, sizeof *m);
    size_t *exc = malloc((n ? n : 1) * sizeof *exc);
    int32_t *q = malloc((n ? n : 1) * sizeof *q), *q2 = malloc((n ? n : 1) * sizeof *q2);
    uint8_t *low = NULL;
    if (!exc || !q || !q2) {
        free(exc);
        free(q);
        free(q2);
        return bwh_fail("out of memory");
    }
    /* binary: the coarsest 2^-k every finite value is a multiple of */
    int kb = 0;
    size_t n_odd = 0; /* non-finite values and -0.0: exceptions under any scale */
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]) || is_neg_zero(x[i])) {
            n_odd++;
            continue;
        }
        int k = binary_exponent(x[i]);
        kb = k > kb ? k : kb;
    }
    size_t max_exc = n / EXC_SHARE;
    double qb = 0, qd = 0;
    long eb = kb <= 149 ? try_scale(x, n, false, kb, q, exc, max_exc, &qb) : -1;
    /* decimal: the fewest digits that give back the values (and no more
     * exceptions than the binary scale leaves), if its samples are smaller */
    int kd = 0;
    long ed = -1;
    size_t *exc2 = NULL;
    for (int k = 1; k <= 9 && n_odd <= max_exc; k++) {
        if (!exc2 && !(exc2 = malloc((n ? n : 1) * sizeof *exc2)))
            break;
        ed = try_scale(x, n, true, k, q2, exc2, eb >= 0 ? (size_t)eb : max_exc, &qd);
        if (ed >= 0) {
            kd = k;
            break;
        }
    }
    int rc = 0;
    if (ed >= 0 && (eb < 0 || qd < qb)) {
        int32_t *t = q;
        q = q2;
        q2 = t;
        size_t *te = exc;
        exc = exc2;
        exc2 = te;
        eb = ed;
        m->scale = (float)pow(10.0, -kd);
        m->flags = BW_FLAG_DECIMAL_SCALE;
    } else if (eb >= 0) {
        m->scale = ldexpf(1.0f, -kb);
    }
    if (eb >= 0) {
        m->map = BWH_EXACT_VALUES;
        m->q = q;
        q = NULL;
        if (eb > 0)
            rc = build(m, x, n, NULL, exc, (size_t)eb);
        goto done;
    }
    /* the bit planes: NaN and infinities are exceptions, the rest ordered
     * integers split into what the core codes and s raw bits */
    m->map = BWH_EXACT_PLANES;
    m->scale = 1.0f;
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    size_t ne = 0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i])) {
            exc[ne++] = i;
            continue;
        }
        int64_t v = monotone(bwh_float_to_bits(x[i]));
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
    }
    if (lo > hi)
        lo = hi = 0; /* nothing finite */
    unsigned s = 0;
    while (((hi >> s) - (lo >> s)) > 2 * (int64_t)BW_SAMPLE_MAX)
        s++;
    if (s > MAX_S) {
        rc = bwh_fail("float exact: the values need %u low bits", s);
        goto done;
    }
    m->s = s;
    m->c = (int32_t)(((hi >> s) + (lo >> s)) / 2);
    low = malloc(n ? n : 1);
    if (!low) {
        rc = bwh_fail("out of memory");
        goto done;
    }
    int64_t prev = lo;
    for (size_t i = 0; i < n; i++) {
        int64_t v = isfinite(x[i]) ? monotone(bwh_float_to_bits(x[i])) : prev;
        prev = v;
        q[i] = (int32_t)((v >> s) - m->c);
        low[i] = (uint8_t)(v & ((1 << s) - 1));
    }
    m->q = q;
    q = NULL;
    rc = build(m, x, n, low, exc, ne);
done:
    free(low);
    free(exc);
    free(exc2);
    free(q);
    free(q2);
    if (rc != 0)
        bwh_exact_free(m);
    return rc;
}

/* the fields of record 0x01 */
typedef struct {
    uint32_t tail, n_exc;
    int map;
    unsigned s;
    int32_t c;
} exact_rec_t;

static int parse(const uint8_t *d, uint32_t dl, exact_rec_t *r)
{
    const uint8_t *q = d, *end = d + dl;
    memset(r, 0, sizeof *r);
    if (bwh_varint_get(&q, end, &r->tail) != 0 || q == end)
        return -1;
    r->map = *q++;
    if (r->map == BWH_EXACT_PLANES) {
        if (end - q < 5)
            return -1;
        r->s = *q++;
        uint32_t c = 0;
        for (unsigned i = 0; i < 4; i++)
            c |= (uint32_t)q[i] << (8 * i);
        r->c = (int32_t)c;
        q += 4;
        if (r->s > MAX_S)
            return -1;
    } else if (r->map != BWH_EXACT_VALUES) {
        return -1;
    }
    if (bwh_varint_get(&q, end, &r->n_exc) != 0 || q != end)
        return -1;
    return 0;
}

int bwh_exact_map_of(const uint8_t *d, uint32_t dl)
{
    exact_rec_t r;
    return parse(d, dl, &r) == 0 ? r.map : -1;
}

int bwh_exact_fields(const uint8_t *d, uint32_t dl, int *map, unsigned *s, uint32_t *n_exc)
{
    exact_rec_t r;
    if (parse(d, dl, &r) != 0)
        return -1;
    *map = r.map;
    *s = r.s;
    *n_exc = r.n_exc;
    return 0;
}

int bwh_exact_apply(const uint8_t *d, uint32_t dl, const uint8_t *tail, size_t tail_len,
                    const int32_t *q, float *v, size_t n, int *map)
{
    exact_rec_t r;
    if (parse(d, dl, &r) != 0 || (tail && r.tail != tail_len))
        return bwh_fail("the payload's float exact record is malformed");
    *map = r.map;
    size_t k = 0;
    if (r.map == BWH_EXACT_PLANES) {
        size_t plane = (n * r.s + 7u) / 8u;
        if (tail && plane > tail_len)
            return bwh_fail("the payload's float exact tail is too short");
        uint64_t acc = 0;
        unsigned nb = 0;
        uint32_t mask = (1u << r.s) - 1u, mid = r.s ? 1u << (r.s - 1u) : 0u;
        for (size_t i = 0; i < n; i++) {
            while (tail && nb < r.s) {
                acc = acc << 8 | tail[k++];
                nb += 8u;
            }
            uint32_t lowbits = tail ? (uint32_t)(acc >> (nb - r.s)) & mask : mid;
            nb -= tail ? r.s : 0u;
            int64_t m = ((int64_t)q[i] + r.c) * ((int64_t)1 << r.s) + lowbits;
            if (m < INT32_MIN || m > INT32_MAX)
                return bwh_fail("sample %zu decodes outside the float32 bit patterns", i);
            v[i] = bwh_bits_to_float(unmonotone((int32_t)m));
        }
        k = plane;
    }
    if (!tail)
        return (r.map == BWH_EXACT_PLANES && r.s) || r.n_exc ? 1 : 0;
    size_t at = 0;
    const uint8_t *p = tail + k, *end = tail + tail_len;
    for (uint32_t j = 0; j < r.n_exc; j++) {
        uint32_t gap;
        if (bwh_varint_get(&p, end, &gap) != 0 || end - p < 4 || gap >= n - at)
            return bwh_fail("the payload's float exact exceptions are malformed");
        at += gap;
        uint32_t b = 0;
        for (unsigned i = 0; i < 4; i++)
            b |= (uint32_t)p[i] << (8 * i);
        p += 4;
        v[at++] = bwh_bits_to_float(b);
    }
    if (p != end)
        return bwh_fail("the payload's float exact tail has %zu bytes too many", (size_t)(end - p));
    return 0;
}
