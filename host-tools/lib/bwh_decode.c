/* SPDX-License-Identifier: BSD-2-Clause */
/* Payloads to samples (bwh_decode.h). */
#include "bwh_decode.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "bw_crc32.h"
#include "bwh_error.h"
#include "bwh_exact.h"
#include "bwh_ext.h"
#include "bwh_logmap.h"
#include "bwh_values.h"
#include "bwr_project.h"
#include "geodesic.h"

/* The header of p[len], checked (with salvage, the fields alone when the
 * payload is not whole: the segment table's CRC vouches for them), and its
 * sample count against the limit. */
int bwh_header_salvage(const uint8_t *p, size_t len, bw_header_t *h)
{
    int st = bw_header_read(p, len, h);
    bw_header_t f;
    if ((st == BW_ERR_CRC || st == BW_ERR_HEADER) && bw_header_parse_cut(p, len, &f) == BW_OK &&
        f.segment_vectors) {
        size_t t = (size_t)f.header_len + BW_SEGMENT_TABLE_SIZE(f.segments) - 4u;
        if (t + 4u <= len && bw_crc32(p, t) == ((uint32_t)p[t] | (uint32_t)p[t + 1] << 8 |
                                                 (uint32_t)p[t + 2] << 16 |
                                                 (uint32_t)p[t + 3] << 24)) {
            *h = f;
            st = BW_OK;
        }
    }
    return st;
}

static int header_within(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                         bool salvage, bool *whole)
{
    int st = bw_header_read(p, len, h);
    if (whole)
        *whole = st == BW_OK;
    if (salvage && st != BW_OK)
        st = bwh_header_salvage(p, len, h);
    if (st == BW_ERR_CRC && !salvage) {
        bw_header_t f;
        if (bwh_header_salvage(p, len, &f) == BW_OK)
            return bwh_fail("%s: its segments can still be decoded in part (brdfwave decode, "
                            "or salvage=True in Python)",
                            bw_strerror(st));
    }
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    size_t n = bw_dims_samples(&h->dims);
    if (!max_samples)
        max_samples = BWH_MAX_SAMPLES_DEFAULT;
    if (n > max_samples)
        return bwh_fail("the payload decodes to %zu samples (%.1f MiB as float32), more than the "
                        "limit of %zu (raise it with --max-samples)",
                        n, (double)n * 4 / 1048576.0, max_samples);
    return 0;
}

/* The integer samples of p[len] in *w (allocated, the decoder's work
 * bound: the samples first), its header in *h, in *whole (may be NULL)
 * whether the payload is whole. With sv (salvage): what a damaged or cut
 * segmented payload holds, the lost samples in *mask (may be NULL);
 * returns 1 when segments were lost. */
static int decode_ints(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                       int32_t **w, uint8_t **mask, bwh_salvage_t *sv, bool *whole)
{
    *w = NULL;
    if (mask)
        *mask = NULL;
    if (header_within(p, len, max_samples, h, sv != NULL, whole) != 0)
        return -1;
    size_t wb = bw_work_bound(bw_dims_samples(&h->dims), h->dims.bands);
    int32_t *b = malloc(wb * sizeof *b);
    if (!b)
        return bwh_fail("out of memory");
    if (!sv) {
        int st = bw_decode(p, len, b, wb, b, wb, h);
        if (st != BW_OK) {
            free(b);
            return bwh_fail("%s", bw_strerror(st));
        }
        *w = b;
        return 0;
    }
    memset(sv, 0, sizeof *sv);
    size_t nv = (size_t)h->dims.n_in * h->dims.n_out, n = bw_dims_samples(&h->dims);
    uint8_t *lost = malloc(nv ? nv : 1), *seg_ok = malloc(h->segments);
    bw_ctx_t *ctx = malloc(sizeof *ctx);
    int st = !lost || !seg_ok || !ctx ? BW_ERR_ARG
                                      : bw_decode_salvage(ctx, p, len, b, wb, b, wb, h, seg_ok,
                                                          h->segments, lost);
    bool oom = !lost || !seg_ok || !ctx;
    free(ctx);
    if (st != BW_OK && st != BW_ERR_INCOMPLETE) {
        free(b);
        free(lost);
        free(seg_ok);
        return bwh_fail("%s", oom ? "out of memory" : bw_strerror(st));
    }
    sv->segments = h->segments;
    for (uint32_t s = 0; s < h->segments; s++)
        sv->lost_segments += !seg_ok[s];
    free(seg_ok);
    if (st == BW_OK) { /* whole: every sample exact */
        free(lost);
        if (mask && !(*mask = calloc(n ? n : 1, 1))) {
            free(b);
            return bwh_fail("out of memory");
        }
        *w = b;
        return 0;
    }
    /* per direction pair, then per sample */
    uint8_t *dm = malloc(nv ? nv : 1), *sm = mask ? malloc(n ? n : 1) : NULL;
    int32_t *tmp = malloc((nv ? nv : 1) * sizeof *tmp);
    if (!dm || !tmp || (mask && !sm)) {
        free(dm);
        free(sm);
        free(tmp);
        free(lost);
        free(b);
        return bwh_fail("out of memory");
    }
    bw_salvage_mask(h, lost, dm, tmp);
    free(tmp);
    free(lost);
    uint32_t bands = h->dims.bands;
    for (size_t v = 0; v < nv; v++) {
        sv->approx += dm[v] == BW_SAMPLE_APPROX ? bands : 0u;
        sv->missing += dm[v] == BW_SAMPLE_MISSING ? bands : 0u;
        if (sm)
            memset(sm + v * bands, dm[v], bands);
    }
    free(dm);
    if (mask)
        *mask = sm;
    *w = b;
    return st == BW_ERR_INCOMPLETE ? 1 : 0;
}

int bwh_payload_check(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h)
{
    int32_t *w;
    if (decode_ints(p, len, max_samples, h, &w, NULL, NULL, NULL) != 0)
        return -1;
    free(w);
    return 0;
}

/* The samples and values of a decode (decode_ints), *w taken over; with
 * tail_lost (may be NULL) a payload that is not whole: a float tail is not
 * used, and *tail_lost says whether that left values approximate. */
static int values_of(const uint8_t *p, bw_header_t *h, int32_t *w, int32_t **samples,
                     float **values, int *tail_lost);
static int decode_any(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                      int32_t **samples, float **values, uint8_t **mask, bwh_salvage_t *sv);

int bwh_decode_limit(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                     int32_t **samples, float **values)
{
    return decode_any(p, len, max_samples, h, samples, values, NULL, NULL);
}

int bwh_decode_salvage(const uint8_t *p, size_t len, size_t max_samples, bw_header_t *h,
                       int32_t **samples, float **values, uint8_t **mask, bwh_salvage_t *info)
{
    bwh_salvage_t tmp;
    return decode_any(p, len, max_samples, h, samples, values, mask,
                                     info ? info : &tmp);
}

static int decode_any(const uint8_t *p, size_t len, size_t max_samples,
                                     bw_header_t *h, int32_t **samples, float **values,
                                     uint8_t **mask, bwh_salvage_t *sv)
{
    if (samples)
        *samples = NULL;
    if (values)
        *values = NULL;
    int32_t *w;
    bool whole;
    int got = decode_ints(p, len, max_samples, h, &w, mask, sv, &whole);
    if (got < 0)
        return -1;
    /* a payload that is not whole: its float tail, which no CRC of its own
     * covers, is not used */
    int lost = 0, *tl = sv && !whole ? &lost : NULL;
    if (values_of(p, h, w, samples, values, tl) != 0) {
        if (mask) {
            free(*mask);
            *mask = NULL;
        }
        return -1;
    }
    if (lost) { /* every exact sample's value is approximate now */
        size_t n = bw_dims_samples(&h->dims);
        sv->tail_lost = 1;
        sv->approx = n - sv->missing;
        for (size_t i = 0; mask && *mask && i < n; i++)
            (*mask)[i] = (*mask)[i] == BW_SAMPLE_EXACT ? BW_SAMPLE_APPROX : (*mask)[i];
        got = 1;
    }
    return got;
}

static int values_of(const uint8_t *p, bw_header_t *h, int32_t *w, int32_t **samples,
                     float **values, int *tail_lost)
{
    size_t n = bw_dims_samples(&h->dims);
    if (values) {
        float scale = bwh_bits_to_float(h->scale_bits), off = bwh_bits_to_float(h->offset_bits);
        if (!isfinite(scale) || !isfinite(off) || scale == 0) {
            free(w);
            return bwh_fail("payload header has a zero or non-finite scale or offset");
        }
        /* without the integers the values take their place */
        float *v = samples ? malloc((n ? n : 1) * sizeof *v) : (float *)(void *)w;
        if (!v) {
            free(w);
            return bwh_fail("out of memory");
        }
        bwh_value_map_t vm = bwh_value_map(scale, off, h->flags);
        /* the critical records 0x01 (float bits, exceptions) and 0x02 (the
         * log map) take the place of the header's scale, or follow it */
        const uint8_t *xd = NULL, *ld = NULL, *tail;
        uint32_t xl = 0, ll = 0;
        bwh_logmap_t lm;
        int fx = bwh_ext_find(p, h, BW_EXT_FLOAT_EXACT, &xd, &xl);
        int fl = bwh_ext_find(p, h, BW_EXT_LOG_MAP, &ld, &ll);
        int planes = fx == 1 && bwh_exact_map_of(xd, xl) == BWH_EXACT_PLANES;
        bool plain = scale == 1.0f && bwh_float_to_bits(off) == 0 &&
                     !(h->flags & (BW_FLAG_DECIMAL_SCALE | BW_FLAG_LOG_VALUE));
        if (fx < 0 || fl < 0 || (fx == 1 && bwh_exact_map_of(xd, xl) < 0) ||
            (fl == 1 && bwh_logmap_parse(ld, ll, &lm) != 0) || ((planes || fl == 1) && !plain) ||
            (planes && fl == 1)) {
            if (v != (float *)(void *)w)
                free(v);
            free(w);
            return bwh_fail("the payload's value records are malformed or conflict");
        }
        for (size_t i = 0; i < n && !planes; i++) {
            int32_t q = w[i];
            float x = fl == 1 ? bwh_logmap_value(&lm, q) : bwh_value_of(&vm, q);
            if (!isfinite(x)) {
                bwh_fail("sample %zu (%d) decodes to %g, beyond float32 (scale %g, offset %g%s)",
                         i, q, (double)x, (double)scale, (double)off,
                         h->flags & BW_FLAG_LOG_VALUE ? ", logarithmic" : "");
                if (v != (float *)(void *)w)
                    free(v);
                free(w);
                return -1;
            }
            v[i] = x;
        }
        int map, ea = 0;
        size_t tl = bwh_ext_tail(p, h, &tail);
        if (fx == 1 && (ea = bwh_exact_apply(xd, xl, tail_lost ? NULL : tail, tl, w, v, n,
                                             &map)) < 0) {
            if (v != (float *)(void *)w)
                free(v);
            free(w);
            return -1;
        }
        if (tail_lost)
            *tail_lost = ea == 1;
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

/* The header for a partial decode: in segments the core checks the CRCs
 * of what it reads (the table's, the segments'), not the whole payload's;
 * then the refusals every partial decode shares. */
static int header_partial(const uint8_t *p, size_t len, bw_header_t *h, int32_t **samples,
                          float **values)
{
    if (samples)
        *samples = NULL;
    if (values)
        *values = NULL;
    bw_header_t f;
    if (bw_header_parse_fields(p, len, &f) == BW_OK && (f.segment_vectors || f.band_access)) {
        *h = f;
        if (bw_dims_samples(&f.dims) > BWH_MAX_SAMPLES_DEFAULT)
            return bwh_fail("the payload decodes to %zu samples, more than the limit of %zu",
                            bw_dims_samples(&f.dims), BWH_MAX_SAMPLES_DEFAULT);
    } else if (header_within(p, len, 0, h, false, NULL) != 0) {
        return -1;
    }
    const uint8_t *xd;
    uint32_t xl;
    if (h->flags & BW_FLAG_RECIPROCAL)
        return bwh_fail("a full BRDF coded with the reciprocity step: every incoming direction "
                        "depends on all the others; decode it whole");
    const uint8_t *tail;
    if (bwh_ext_find(p, h, BW_EXT_FLOAT_EXACT, &xd, &xl) == 1 && bwh_ext_tail(p, h, &tail))
        return bwh_fail("float values kept bit for bit in the payload's tail: decode it whole");
    return 0;
}

/* Runs a partial decode of rn samples into *r (allocated), the full work
 * area lent to it; arg points to what the decode takes (a row, a level,
 * the rows' marks). */
typedef bw_status_t (*partial_fn)(bw_ctx_t *ctx, const uint8_t *p, size_t len, const void *arg,
                                  int32_t *out, size_t cap, int32_t *work, size_t wcap);

static int run_partial(partial_fn fn, const uint8_t *p, size_t len, const void *arg,
                       const bw_header_t *h, size_t rn, int32_t **r)
{
    size_t n = bw_dims_samples(&h->dims), wb = bw_work_bound(n, h->dims.bands);
    int32_t *w = malloc(wb * sizeof *w);
    bw_ctx_t *ctx = malloc(sizeof *ctx);
    *r = malloc((rn ? rn : 1) * sizeof **r);
    int st = !w || !*r || !ctx ? BW_ERR_ARG : fn(ctx, p, len, arg, *r, rn, w, wb);
    bool oom = !w || !*r || !ctx;
    free(w);
    free(ctx);
    if (st != BW_OK) {
        free(*r);
        *r = NULL;
        return bwh_fail("%s", oom ? "out of memory" : bw_strerror(st));
    }
    return 0;
}

/* The values of a partial decode's samples r: the payload's maps, on a
 * header of the dimensions decoded. */
static int partial_values(const uint8_t *p, const bw_header_t *h, const bw_dims_t *dims,
                          int32_t *r, int32_t **samples, float **values)
{
    bw_header_t hp = *h;
    hp.dims = *dims;
    return values_of(p, &hp, r, samples, values, NULL);
}

static bw_status_t level_fn(bw_ctx_t *ctx, const uint8_t *p, size_t len, const void *arg,
                            int32_t *out, size_t cap, int32_t *work, size_t wcap)
{
    const unsigned *lv = arg; /* outgoing, incoming */
    return bw_decode_lod(ctx, p, len, lv[0], lv[1], out, cap, work, wcap, NULL);
}

static bw_status_t incoming_fn(bw_ctx_t *ctx, const uint8_t *p, size_t len, const void *arg,
                               int32_t *out, size_t cap, int32_t *work, size_t wcap)
{
    return bw_decode_incoming(ctx, p, len, *(const uint32_t *)arg, out, cap, work, wcap, NULL);
}

static bw_status_t rows_fn(bw_ctx_t *ctx, const uint8_t *p, size_t len, const void *arg,
                           int32_t *out, size_t cap, int32_t *work, size_t wcap)
{
    return bw_decode_rows(ctx, p, len, arg, out, cap, work, wcap, NULL);
}

int bwh_decode_levels(const uint8_t *p, size_t len, int level_out, int level_in, bw_header_t *h,
                      bw_dims_t *lod, int32_t **samples, float **values)
{
    if (header_partial(p, len, h, samples, values) != 0)
        return -1;
    const bw_dims_t *d = &h->dims;
    if (d->shape == BW_SHAPE_SPECTRA)
        return bwh_fail("a set of spectra has no outgoing hemisphere to coarsen");
    if (level_out > (int)d->level_out)
        return bwh_fail("level %d is finer than the payload's own (%u)", level_out, d->level_out);
    unsigned level = level_out < 0 ? d->level_out : (unsigned)level_out;
    if (level_in >= 0 && d->shape != BW_SHAPE_BRDF_FULL)
        return bwh_fail("only a full BRDF has an incoming hemisphere to coarsen");
    if (level_in > (int)d->level_in)
        return bwh_fail("incoming level %d is finer than the payload's own (%u)", level_in,
                        d->level_in);
    unsigned lv[2] = {level, level_in < 0 ? BW_LEVEL_OWN : (unsigned)level_in};
    *lod = *d;
    lod->level_out = (uint8_t)level;
    lod->n_out = 4u << (2u * level);
    if (level_in >= 0) {
        lod->level_in = (uint8_t)level_in;
        lod->n_in = 4u << (2u * level_in);
    }
    int32_t *r;
    if (run_partial(level_fn, p, len, lv, h, bw_dims_samples(lod), &r) != 0)
        return -1;
    return partial_values(p, h, lod, r, samples, values);
}

int bwh_decode_level(const uint8_t *p, size_t len, unsigned level, bw_header_t *h, bw_dims_t *lod,
                     int32_t **samples, float **values)
{
    return bwh_decode_levels(p, len, (int)(level > BW_MAX_LEVEL ? BW_MAX_LEVEL + 1u : level),
                             -1, h, lod, samples, values);
}

int bwh_decode_incoming(const uint8_t *p, size_t len, uint32_t in, bw_header_t *h, bw_dims_t *row,
                        int32_t **samples, float **values)
{
    if (header_partial(p, len, h, samples, values) != 0)
        return -1;
    const bw_dims_t *d = &h->dims;
    if (d->shape == BW_SHAPE_REFLECTANCE)
        return bwh_fail("a reflectance has no incoming directions to choose from");
    if (in >= d->n_in)
        return bwh_fail("%s %u is past the last (%u)",
                        d->shape == BW_SHAPE_SPECTRA ? "spectrum" : "incoming direction", in,
                        d->n_in - 1u);
    int32_t *r;
    if (run_partial(incoming_fn, p, len, &in, h, (size_t)d->n_out * d->bands, &r) != 0)
        return -1;
    memset(row, 0, sizeof *row);
    if (d->shape == BW_SHAPE_SPECTRA)
        bw_dims_make(row, BW_SHAPE_SPECTRA, 0, 0, 1, d->bands);
    else
        bw_dims_make(row, BW_SHAPE_REFLECTANCE, d->level_out, 0, 1, d->bands);
    return partial_values(p, h, row, r, samples, values);
}

int bwh_decode_rows(const uint8_t *p, size_t len, const uint8_t *rows, bw_header_t *h,
                    bw_dims_t *sub, int32_t **samples, float **values)
{
    if (header_partial(p, len, h, samples, values) != 0)
        return -1;
    const bw_dims_t *d = &h->dims;
    if (d->shape == BW_SHAPE_REFLECTANCE)
        return bwh_fail("a reflectance has no incoming directions to choose from");
    uint32_t k = 0;
    for (uint32_t t = 0; t < d->n_in; t++)
        k += rows[t] != 0u;
    if (!k)
        return bwh_fail("no %s chosen", d->shape == BW_SHAPE_SPECTRA ? "spectrum"
                                                                     : "incoming direction");
    int32_t *r;
    if (run_partial(rows_fn, p, len, rows, h, (size_t)k * d->n_out * d->bands, &r) != 0)
        return -1;
    memset(sub, 0, sizeof *sub);
    if (d->shape == BW_SHAPE_SPECTRA)
        bw_dims_make(sub, BW_SHAPE_SPECTRA, 0, 0, k, d->bands);
    else
        bw_dims_make(sub, BW_SHAPE_BRDF_ISO, d->level_out, 0, k, d->bands);
    return partial_values(p, h, sub, r, samples, values);
}

int bwh_decode_bands(const uint8_t *p, size_t len, uint32_t b0, uint32_t b1, bw_header_t *h,
                     bw_dims_t *sub, int32_t **samples, float **values)
{
    if (header_partial(p, len, h, samples, values) != 0)
        return -1;
    const bw_dims_t *d = &h->dims;
    if (b0 >= b1 || b1 > d->bands)
        return bwh_fail("bands %u to %u: the payload has bands 0 to %u", b0, b1 - 1u,
                        d->bands - 1u);
    size_t nr = (size_t)d->n_in * d->n_out * (b1 - b0);
    int32_t *r = malloc((nr ? nr : 1) * sizeof *r);
    if (!r)
        return bwh_fail("out of memory");
    if (h->band_access) {
        /* the columns those bands depend on */
        size_t wb = bw_band_range_work(d->n_in, b1 - b0);
        int32_t *w = malloc(wb * sizeof *w);
        bw_status_t st = w ? bw_decode_band_range(p, len, b0, b1, r, nr, w, wb, NULL) : BW_ERR_ARG;
        free(w);
        if (st != BW_OK) {
            free(r);
            return bwh_fail("%s", w ? bw_strerror(st) : "out of memory");
        }
    } else {
        /* every other body: the whole decode, then the bands */
        int32_t *x;
        if (decode_ints(p, len, 0, h, &x, NULL, NULL, NULL) != 0) {
            free(r);
            return -1;
        }
        for (size_t v = 0, nv = (size_t)d->n_in * d->n_out; v < nv; v++)
            memcpy(r + v * (b1 - b0), x + v * d->bands + b0, (b1 - b0) * sizeof *r);
        free(x);
    }
    *sub = *d;
    sub->bands = b1 - b0;
    return partial_values(p, h, sub, r, samples, values);
}

int bwh_region_rows(const bw_header_t *h, const double *incidence_deg, double theta_deg,
                    double phi_deg, double radius_deg, uint8_t *rows)
{
    const bw_dims_t *d = &h->dims;
    if (d->shape != BW_SHAPE_BRDF_FULL && d->shape != BW_SHAPE_BRDF_ISO)
        return bwh_fail("a region of the incoming hemisphere needs a BRDF (incoming "
                        "directions)");
    if (!(theta_deg >= 0 && theta_deg <= 90) || !(phi_deg >= -360 && phi_deg <= 360) ||
        !(radius_deg >= 0 && radius_deg <= 180))
        return bwh_fail("a region is THETA (0..90), PHI (-360..360) and a RADIUS (0..180), "
                        "in degrees");
    int k = 0;
    if (d->shape == BW_SHAPE_BRDF_ISO) { /* the incidences; the azimuth plays no part */
        for (uint32_t i = 0; i < d->n_in; i++) {
            double th = incidence_deg ? incidence_deg[i] : (i + 0.5) * 90.0 / (double)d->n_in;
            rows[i] = fabs(th - theta_deg) <= radius_deg;
            k += rows[i];
        }
        return k;
    }
    double(*c)[3] = malloc((size_t)d->n_in * sizeof *c);
    if (!c || bwh_grid_centres(d->level_in, c, NULL) != 0) {
        free(c);
        return bwh_fail("out of memory");
    }
    double u[3], lim = cos(radius_deg * 3.14159265358979323846 / 180);
    bwr_dir_from_degrees(theta_deg, phi_deg, u);
    for (uint32_t i = 0; i < d->n_in; i++) {
        rows[i] = c[i][0] * u[0] + c[i][1] * u[1] + c[i][2] * u[2] >= lim;
        k += rows[i];
    }
    free(c);
    return k;
}

int bwh_keep_bands(bw_dims_t *d, const uint8_t *bands, int32_t *s, float *v, uint8_t *mask)
{
    uint32_t nb = d->bands, kept = 0;
    for (uint32_t k = 0; k < nb; k++)
        kept += bands[k] != 0;
    if (!kept)
        return bwh_fail("no band chosen");
    /* forwards: every sample moves to an index at most its own */
    size_t vecs = (size_t)d->n_in * d->n_out, to = 0;
    for (size_t i = 0; i < vecs; i++) {
        size_t from = i * nb;
        for (uint32_t k = 0; k < nb; k++) {
            if (!bands[k])
                continue;
            if (s)
                s[to] = s[from + k];
            if (v)
                v[to] = v[from + k];
            if (mask)
                mask[to] = mask[from + k];
            to++;
        }
    }
    d->bands = kept;
    return 0;
}
