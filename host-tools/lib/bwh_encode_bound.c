/* SPDX-License-Identifier: BSD-2-Clause */
/* Float input under a per-sample guarantee (bwh_encode_bound.h). */
#include "bwh_encode_bound.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_decode.h"
#include "bwh_error.h"
#include "bwh_exact.h"
#include "bwh_ext.h"
#include "bwh_logmap.h"
#include "bwh_values.h"

#define FIX_SHARE 16u /* exceptions a lossy guarantee may need: one sample in 16 */

/* adds recs, record 0x82 of g, and the tail */
static int add_records(uint8_t **out, size_t *len, const bwh_guarantee_t *g, const uint8_t *recs,
                       size_t rlen, const uint8_t *more, size_t mlen, const uint8_t *tail,
                       size_t tlen)
{
    /* lossless mode in the header says "exact" itself */
    size_t gl = g->kind == BWH_GUARANTEE_EXACT ? 0 : bwh_guarantee_record(g, NULL);
    uint8_t *all = malloc(rlen + mlen + gl + 1);
    if (!all)
        return bwh_fail("out of memory");
    if (rlen)
        memcpy(all, recs, rlen);
    if (mlen)
        memcpy(all + rlen, more, mlen);
    if (gl)
        bwh_guarantee_record(g, all + rlen + mlen);
    int rc = bwh_ext_add(out, len, all, rlen + mlen + gl, tail, tlen);
    free(all);
    return rc;
}

/* decodes the payload's values and counts the samples that break g */
static int check(const uint8_t *p, size_t len, const float *x, size_t n,
                 const bwh_guarantee_t *g, size_t *bad, size_t *first, float **vals)
{
    bw_header_t h;
    float *v = NULL;
    if (bwh_decode_limit(p, len, SIZE_MAX, &h, NULL, &v) != 0)
        return -1;
    *bad = bwh_guarantee_check(g, x, v, n, first);
    *vals = v;
    return 0;
}

int bwh_encode_seal(uint8_t **out, size_t *len, const float *x, size_t n,
                    const bwh_guarantee_t *g, const uint8_t *recs, size_t rlen,
                    const uint8_t *tail, size_t tlen, int fix)
{
    uint8_t *bare = malloc(*len);
    size_t blen = *len, bad = 0, first = 0;
    float *v = NULL;
    bwh_exact_t m;
    memset(&m, 0, sizeof m);
    int rc = -1;
    if (!bare) {
        bwh_fail("out of memory");
        goto done;
    }
    memcpy(bare, *out, blen);
    if (add_records(out, len, g, recs, rlen, NULL, 0, tail, tlen) != 0 ||
        check(*out, *len, x, n, g, &bad, &first, &v) != 0)
        goto done;
    if (bad && fix && bad <= n / FIX_SHARE) {
        /* the few values float32 rounding took past the bound, exactly */
        size_t *idx = malloc(bad * sizeof *idx), k = 0;
        if (!idx) {
            bwh_fail("out of memory");
            goto done;
        }
        for (size_t i = 0; i < n; i++)
            if (!bwh_guarantee_holds(g, x[i], v[i]))
                idx[k++] = i;
        int erc = bwh_exact_exceptions(x, idx, k, &m);
        free(idx);
        free(v);
        v = NULL;
        if (erc != 0)
            goto done;
        free(*out);
        *out = bare;
        *len = blen;
        bare = NULL;
        if (add_records(out, len, g, recs, rlen, m.rec, m.rec_len, m.tail, m.tail_len) != 0 ||
            check(*out, *len, x, n, g, &bad, &first, &v) != 0)
            goto done;
    }
    if (bad) {
        char rule[160];
        bwh_guarantee_rule(g, rule, sizeof rule);
        bwh_fail("guarantee %s not met at sample %zu after float conversion (%.9g decoded as "
                 "%.9g; %zu samples)",
                 rule, first, (double)x[first], (double)v[first], bad);
        goto done;
    }
    rc = 0;
done:
    free(bare);
    free(v);
    bwh_exact_free(&m);
    if (rc != 0) {
        free(*out);
        *out = NULL;
        *len = 0;
    }
    return rc;
}

int bwh_encode_exact(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o,
                     const bwh_guarantee_t *g, uint8_t **out, size_t *out_len)
{
    *out = NULL;
    *out_len = 0;
    int st = bw_dims_check(dims);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    size_t n = bw_dims_samples(dims);
    bwh_exact_t m;
    if (bwh_exact_map(x, n, &m) != 0)
        return -1;
    bwh_encode_opts_t io = *o;
    io.mode = BW_MODE_LOSSLESS;
    io.flags = (o->flags & ~(BW_FLAG_DECIMAL_SCALE | BW_FLAG_LOG_VALUE)) | m.flags;
    bwh_guarantee_t exact = {.kind = BWH_GUARANTEE_EXACT};
    int rc = bwh_encode_i32(dims, m.q, &io, m.scale, 0.0f, out, out_len);
    if (rc == 0)
        rc = bwh_encode_seal(out, out_len, x, n, g ? g : &exact, m.rec, m.rec_len, m.tail,
                             m.tail_len, 0);
    bwh_exact_free(&m);
    return rc;
}

/* the largest float32 at or below v (v > 0), 0 below the smallest */
static float float_below(double v)
{
    float f = (float)v;
    while (f > 0 && (double)f > v)
        f = nextafterf(f, 0.0f);
    return f;
}

int bwh_encode_relative(const bw_dims_t *dims, const float *x, const bwh_encode_opts_t *o,
                        uint8_t **out, size_t *out_len)
{
    *out = NULL;
    *out_len = 0;
    int st = bw_dims_check(dims);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    size_t n = bw_dims_samples(dims);
    double R = o->max_rel_error, F = o->rel_floor, E = o->max_error;
    bool both = o->mode == BW_MODE_MAX_ERROR;
    if (!(R > 0 && R < 1))
        return bwh_fail("the relative bound must lie between 0 and 1 (got %g)", R);
    if (!(F >= 0) || !isfinite(F))
        return bwh_fail("the relative bound's floor must be finite and not negative");
    if (o->mode == BW_MODE_BYTES || (o->flags & BW_FLAG_LOG_VALUE))
        return bwh_fail("a relative bound goes with --lossless or --max-error, not a byte budget");
    if (both && !(E > 0 && isfinite(E)))
        return bwh_fail("max error must be positive");
    bwh_guarantee_t g = {both ? BWH_GUARANTEE_BOTH : BWH_GUARANTEE_RELATIVE, 1, 0,
                         both ? E : 0.0, R, F};
    double maxabs = 0, mn = INFINITY;
    bool zeros = false, neg = false;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]))
            return bwh_fail("sample %zu is %s: a relative bound needs finite values (--lossless "
                            "keeps NaN and infinities bit for bit)",
                            i, isnan(x[i]) ? "NaN" : "infinite");
        double a = fabs((double)x[i]);
        maxabs = fmax(maxabs, a);
        if (a > 0)
            mn = fmin(mn, a);
        zeros |= a == 0;
        neg |= x[i] < 0;
    }
    /* the relative error the map may spend: R less the float32 rounding of
     * a decoded value (2^-24 of it) and a margin for the decoder's libm */
    double eff = R * (1.0 - 0x1p-20) - 0x1p-23, Ee = INFINITY;
    if (both) {
        /* the absolute part keeps one ulp of the largest value in hand, as
         * --max-error does */
        float top = (float)(maxabs + E);
        Ee = E - ((double)nextafterf(top, INFINITY) - (double)top);
    }
    if (!(eff > 0) || !(Ee > 0)) /* finer than float32 resolves: exact coding meets it */
        return bwh_encode_exact(dims, x, o, &g, out, out_len);
    double delta = log1p(eff);
    double t1 = F > 0 ? F / R : (mn < INFINITY ? mn : 1.0);
    double t2 = both && maxabs > Ee / R ? Ee / R : 0.0;
    bwh_logmap_t lm = {float_below(t1), float_below(t2), 0.0f, 0u};
    if (!(lm.t1 > 0))
        lm.t1 = nextafterf(0.0f, 1.0f);
    if (lm.t2 > 0 && lm.t1 > lm.t2)
        lm.t1 = lm.t2;
    /* positive values that need neither floor nor cap: the logarithm with
     * the header's scale and offset (BW_FLAG_LOG_VALUE), no record needed */
    bool logv = !zeros && !neg && lm.t2 == 0 && (F == 0 || mn >= t1) &&
                maxabs * (1.0 + R) <= (double)FLT_MAX; /* the header's exp() may not clamp */
    double lo = logv ? log(mn) : 0, hi = logv ? log(maxabs) : 0;
    float off = (float)(0.5 * (lo + hi));
    int32_t *q = malloc((n ? n : 1) * sizeof *q);
    if (!q)
        return bwh_fail("out of memory");
    /* the core's bound in samples: 3 (a grid 3.5 times finer than the
     * bound), or coarser grids when the values span too many of its steps */
    static const unsigned cores[] = {3, 1, 0};
    unsigned ec = 0;
    bool fits = false;
    for (unsigned c = 0; c < 3 && !fits; c++) {
        ec = cores[c];
        float hf = float_below(delta / (ec + 0.5));
        if (!(hf > 0))
            break;
        lm.h = hf;
        lm.z = F > 0 ? 0u : ec;
        fits = true;
        for (size_t i = 0; i < n && fits; i++) {
            double y = logv ? (log((double)x[i]) - (double)off) : bwh_logmap_y(&lm, x[i]);
            double r = nearbyint(y / (double)hf);
            fits = fabs(r) <= BW_SAMPLE_MAX;
            q[i] = fits ? (int32_t)r : 0;
        }
    }
    if (!fits) {
        /* more orders of magnitude than the core's 2^25 steps hold at this
         * bound: exact coding meets it (a floor would keep the grid, and
         * the payload, small) */
        free(q);
        return bwh_encode_exact(dims, x, o, &g, out, out_len);
    }
    bwh_encode_opts_t io = *o;
    io.mode = ec ? BW_MODE_MAX_ERROR : BW_MODE_LOSSLESS;
    io.max_error = ec;
    io.flags = (o->flags & ~BW_FLAG_DECIMAL_SCALE) | (logv ? BW_FLAG_LOG_VALUE : 0u);
    int rc = bwh_encode_i32(dims, q, &io, logv ? lm.h : 1.0f, logv ? off : 0.0f, out, out_len);
    free(q);
    if (rc != 0)
        return rc;
    uint8_t rec[32];
    size_t rl = logv ? 0 : bwh_logmap_record(&lm, rec);
    return bwh_encode_seal(out, out_len, x, n, &g, rec, rl, NULL, 0, 1);
}
