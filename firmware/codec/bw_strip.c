/* SPDX-License-Identifier: BSD-2-Clause */
#include "bw_strip.h"

#include "bw_fixed.h"

size_t bw_sparse_strips_bound(size_t length) { return BW_SPARSE_STRIPS_BOUND(length); }

bw_status_t bw_sparse_init(bw_sparse_t *s, uint32_t length, uint32_t *strip_no, uint32_t *mask,
                           uint32_t *first, uint32_t cap_strips, int32_t *values,
                           uint32_t cap_values)
{
    if (!s || (cap_strips && (!strip_no || !mask || !first)) || (cap_values && !values))
        return BW_ERR_ARG;
    s->length = length;
    s->n_strips = 0;
    s->n_values = 0;
    s->cap_strips = cap_strips;
    s->cap_values = cap_values;
    s->strip_no = strip_no;
    s->mask = mask;
    s->first = first;
    s->values = values;
    return BW_OK;
}

static unsigned popcount32(uint32_t v)
{
#if defined(__GNUC__)
    return (unsigned)__builtin_popcount(v);
#else
    unsigned n = 0;
    while (v) { v &= v - 1u; n++; }
    return n;
#endif
}

static uint32_t strip_len(uint32_t length, uint32_t no)
{
    uint32_t rest = length - no * 32u;
    return rest < 32u ? rest : 32u;
}

/* Appends one strip from up to 32 dense values; skips it when empty. */
static bw_status_t push_strip(bw_sparse_t *s, uint32_t no, const int32_t *v, uint32_t cnt)
{
    uint32_t mask = 0;
    for (uint32_t b = 0; b < cnt; b++)
        if (v[b])
            mask |= 1u << b;
    if (!mask)
        return BW_OK;
    if (s->n_strips >= s->cap_strips || s->n_values + popcount32(mask) > s->cap_values)
        return BW_ERR_OUTPUT_FULL;
    s->strip_no[s->n_strips] = no;
    s->mask[s->n_strips] = mask;
    s->first[s->n_strips] = s->n_values;
    s->n_strips++;
    for (uint32_t b = 0; b < cnt; b++)
        if (v[b])
            s->values[s->n_values++] = v[b];
    return BW_OK;
}

/* Unpacks strip k of s into 32 dense values. */
static void unpack(const bw_sparse_t *s, uint32_t k, int32_t *v)
{
    uint32_t m = s->mask[k];
    const int32_t *p = s->values + s->first[k];
    for (uint32_t b = 0; b < 32u; b++)
        v[b] = (m >> b) & 1u ? *p++ : 0;
}

bw_status_t bw_sparse_from_dense(bw_sparse_t *s, const int32_t *dense, uint32_t threshold)
{
    if (!s || (!dense && s->length))
        return BW_ERR_ARG;
    s->n_strips = s->n_values = 0;
    uint32_t nstrips = (uint32_t)BW_SPARSE_STRIPS_BOUND(s->length);
    for (uint32_t no = 0; no < nstrips; no++) {
        int32_t v[32];
        uint32_t cnt = strip_len(s->length, no);
        for (uint32_t b = 0; b < cnt; b++) {
            int32_t x = dense[no * 32u + b];
            v[b] = bw_abs32(x) > threshold ? x : 0;
        }
        bw_status_t st = push_strip(s, no, v, cnt);
        if (st != BW_OK)
            return st;
    }
    return BW_OK;
}

void bw_sparse_to_dense(const bw_sparse_t *s, int32_t *dense)
{
    for (uint32_t i = 0; i < s->length; i++)
        dense[i] = 0;
    for (uint32_t k = 0; k < s->n_strips; k++) {
        int32_t v[32];
        unpack(s, k, v);
        uint32_t cnt = strip_len(s->length, s->strip_no[k]);
        for (uint32_t b = 0; b < cnt; b++)
            dense[s->strip_no[k] * 32u + b] = v[b];
    }
}

int32_t bw_sparse_get(const bw_sparse_t *s, uint32_t i)
{
    if (i >= s->length)
        return 0;
    uint32_t no = i / 32u, bit = i % 32u;
    /* binary search over the ascending strip numbers */
    uint32_t lo = 0, hi = s->n_strips;
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo) / 2u;
        if (s->strip_no[mid] < no)
            lo = mid + 1u;
        else
            hi = mid;
    }
    if (lo == s->n_strips || s->strip_no[lo] != no || !((s->mask[lo] >> bit) & 1u))
        return 0;
    return s->values[s->first[lo] + popcount32(s->mask[lo] & ((1u << bit) - 1u))];
}

static int32_t sat32(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : (int32_t)v;
}

/* Merge of the two ascending strip lists; sign = +1 or -1 for b. */
static bw_status_t merge(const bw_sparse_t *a, const bw_sparse_t *b, int sign, bw_sparse_t *out)
{
    if (!a || !b || !out)
        return BW_ERR_ARG;
    if (a->length != b->length || out->length != a->length)
        return BW_ERR_MISMATCH;
    if (out == a || out == b)
        return BW_ERR_ARG;
    out->n_strips = out->n_values = 0;
    uint32_t i = 0, j = 0;
    while (i < a->n_strips || j < b->n_strips) {
        int32_t va[32] = {0}, vb[32] = {0}, r[32];
        uint32_t no;
        if (j == b->n_strips || (i < a->n_strips && a->strip_no[i] < b->strip_no[j])) {
            no = a->strip_no[i];
            unpack(a, i++, va);
        } else if (i == a->n_strips || b->strip_no[j] < a->strip_no[i]) {
            no = b->strip_no[j];
            unpack(b, j++, vb);
        } else {
            no = a->strip_no[i];
            unpack(a, i++, va);
            unpack(b, j++, vb);
        }
        for (uint32_t k = 0; k < 32u; k++)
            r[k] = sat32((int64_t)va[k] + sign * (int64_t)vb[k]);
        bw_status_t st = push_strip(out, no, r, strip_len(out->length, no));
        if (st != BW_OK)
            return st;
    }
    return BW_OK;
}

bw_status_t bw_sparse_add(const bw_sparse_t *a, const bw_sparse_t *b, bw_sparse_t *out)
{
    return merge(a, b, +1, out);
}

bw_status_t bw_sparse_sub(const bw_sparse_t *a, const bw_sparse_t *b, bw_sparse_t *out)
{
    return merge(a, b, -1, out);
}

bw_status_t bw_sparse_scale(const bw_sparse_t *a, int32_t num, unsigned shift, bw_sparse_t *out)
{
    if (!a || !out || shift > 31u)
        return BW_ERR_ARG;
    if (out->length != a->length)
        return BW_ERR_MISMATCH;
    /* in place works because the result never has more strips or values
     * than a, and is written behind the read position */
    uint32_t ns = a->n_strips;
    out->n_strips = out->n_values = 0;
    for (uint32_t k = 0; k < ns; k++) {
        int32_t v[32];
        uint32_t no = a->strip_no[k];
        unpack(a, k, v);
        for (uint32_t b = 0; b < 32u; b++) {
            int64_t p = (int64_t)v[b] * num;
            v[b] = sat32(shift ? bw_asr64(p + ((int64_t)1 << (shift - 1u)), shift) : p);
        }
        bw_status_t st = push_strip(out, no, v, strip_len(a->length, no));
        if (st != BW_OK)
            return st;
    }
    return BW_OK;
}

bw_status_t bw_sparse_dot(const bw_sparse_t *a, const bw_sparse_t *b, int64_t *result)
{
    if (!a || !b || !result)
        return BW_ERR_ARG;
    if (a->length != b->length)
        return BW_ERR_MISMATCH;
    uint64_t acc = 0; /* wraps instead of overflowing */
    uint32_t i = 0, j = 0;
    while (i < a->n_strips && j < b->n_strips) {
        if (a->strip_no[i] < b->strip_no[j]) {
            i++;
        } else if (b->strip_no[j] < a->strip_no[i]) {
            j++;
        } else {
            uint32_t both = a->mask[i] & b->mask[j];
            const int32_t *pa = a->values + a->first[i], *pb = b->values + b->first[j];
            for (uint32_t bit = 0; bit < 32u; bit++) {
                uint32_t m = 1u << bit;
                if (both & m)
                    acc += (uint64_t)((int64_t)*pa * *pb);
                pa += (a->mask[i] & m) != 0;
                pb += (b->mask[j] & m) != 0;
            }
            i++;
            j++;
        }
    }
    *result = (int64_t)acc;
    return BW_OK;
}

size_t bw_sparse_bytes(const bw_sparse_t *s)
{
    return (size_t)s->n_values * 4u + (size_t)s->n_strips * 12u;
}
