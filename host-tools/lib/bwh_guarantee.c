/* SPDX-License-Identifier: BSD-2-Clause */
/* The guarantee a payload was made under (bwh_guarantee.h). */
#include "bwh_guarantee.h"

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_decode.h"
#include "bwh_error.h"
#include "bwh_ext.h"
#include "bwh_values.h"

/* record 0x82, byte 0: the kind, a floor, which bounds are float64 */
#define G_KIND 0x07u
#define G_FLOOR 0x08u   /* F follows R */
#define G_FLOAT64 0x10u /* bound i (in the order E, R, F) is float64: this << i */
#define G_RESERVED 0x80u

static const char *const kind_names[] = {"none", "exact", "absolute", "relative", "both"};

const char *bwh_guarantee_name(int kind)
{
    return kind >= 0 && kind <= BWH_GUARANTEE_BOTH ? kind_names[kind] : "unknown";
}

static bool has_abs(int kind)
{
    return kind == BWH_GUARANTEE_ABSOLUTE || kind == BWH_GUARANTEE_BOTH;
}

static bool has_rel(int kind)
{
    return kind == BWH_GUARANTEE_RELATIVE || kind == BWH_GUARANTEE_BOTH;
}

/* the bounds a guarantee records, in order: E, R, F (F only when not 0) */
static unsigned bounds_of(const bwh_guarantee_t *g, double *b)
{
    unsigned k = 0;
    if (has_abs(g->kind))
        b[k++] = g->max_error;
    if (has_rel(g->kind)) {
        b[k++] = g->max_rel_error;
        if (g->rel_floor != 0)
            b[k++] = g->rel_floor;
    }
    return k;
}

size_t bwh_guarantee_record(const bwh_guarantee_t *g, uint8_t *out)
{
    double b[3];
    unsigned k = bounds_of(g, b);
    uint8_t d[1 + 3 * 8];
    d[0] = (uint8_t)(g->kind | (has_rel(g->kind) && g->rel_floor != 0 ? G_FLOOR : 0u));
    size_t n = 1;
    for (unsigned i = 0; i < k; i++) {
        /* float32 when it holds the bound exactly */
        unsigned w = (double)(float)b[i] == b[i] ? 4u : 8u;
        uint64_t bits;
        if (w == 8) {
            memcpy(&bits, &b[i], 8);
            d[0] |= (uint8_t)(G_FLOAT64 << i);
        } else {
            bits = bwh_float_to_bits((float)b[i]);
        }
        for (unsigned j = 0; j < w; j++)
            d[n++] = (uint8_t)(bits >> (8 * j));
    }
    return bwh_ext_put(out, BW_EXT_GUARANTEE, d, n);
}

int bwh_guarantee_parse(const uint8_t *d, size_t n, bwh_guarantee_t *g)
{
    memset(g, 0, sizeof *g);
    if (n < 1 || (d[0] & G_RESERVED) || (d[0] & G_KIND) > BWH_GUARANTEE_BOTH)
        return -1;
    g->kind = d[0] & G_KIND;
    g->recorded = 1;
    unsigned k = (has_abs(g->kind) ? 1u : 0u) + (has_rel(g->kind) ? 1u : 0u) +
                 (d[0] & G_FLOOR ? 1u : 0u);
    if (((d[0] & G_FLOOR) && !has_rel(g->kind)) || (d[0] >> 4 & 7u) >> k)
        return -1;
    double b[3] = {0, 0, 0};
    size_t at = 1;
    g->width = 4;
    for (unsigned i = 0; i < k; i++) {
        unsigned w = d[0] & (G_FLOAT64 << i) ? 8u : 4u;
        if (n < at + w)
            return -1;
        uint64_t bits = 0;
        for (unsigned j = 0; j < w; j++)
            bits |= (uint64_t)d[at + j] << (8 * j);
        at += w;
        if (w == 8) {
            memcpy(&b[i], &bits, 8);
            g->width = 8;
        } else {
            b[i] = bwh_bits_to_float((uint32_t)bits);
        }
    }
    if (at != n)
        return -1;
    k = 0;
    if (has_abs(g->kind))
        g->max_error = b[k++];
    if (has_rel(g->kind)) {
        g->max_rel_error = b[k++];
        if (d[0] & G_FLOOR)
            g->rel_floor = b[k++];
    }
    /* E and R positive where they count, F positive when recorded, all finite */
    if ((has_abs(g->kind) && !(g->max_error > 0 && isfinite(g->max_error))) ||
        (has_rel(g->kind) && !(g->max_rel_error > 0 && isfinite(g->max_rel_error))) ||
        ((d[0] & G_FLOOR) && !(g->rel_floor > 0 && isfinite(g->rel_floor))))
        return -1;
    return 0;
}

int bwh_guarantee_of(const uint8_t *p, const bw_header_t *h, bwh_guarantee_t *g)
{
    const uint8_t *d;
    uint32_t dl;
    int f = bwh_ext_find(p, h, BW_EXT_GUARANTEE, &d, &dl);
    if (f < 0 || (f == 1 && bwh_guarantee_parse(d, dl, g) != 0))
        return bwh_fail("the payload's guarantee record is malformed");
    if (f == 1)
        return 0;
    memset(g, 0, sizeof *g);
    if (h->mode == BW_MODE_LOSSLESS) {
        g->kind = BWH_GUARANTEE_EXACT;
    } else if (h->mode == BW_MODE_MAX_ERROR) {
        g->kind = BWH_GUARANTEE_ABSOLUTE;
        g->max_error = h->max_error * fabs((double)bwh_bits_to_float(h->scale_bits));
    }
    return 0;
}

int bwh_guarantee_read(const uint8_t *p, size_t len, bwh_guarantee_t *g)
{
    bw_header_t h;
    int st = bwh_header_salvage(p, len, &h);
    if (st != BW_OK)
        return bwh_fail("%s", bw_strerror(st));
    return bwh_guarantee_of(p, &h, g);
}

double bwh_guarantee_bound(const bwh_guarantee_t *g, double x)
{
    double rel = fmax(g->max_rel_error * fabs(x), g->rel_floor);
    switch (g->kind) {
    case BWH_GUARANTEE_EXACT:
        return 0.0;
    case BWH_GUARANTEE_ABSOLUTE:
        return g->max_error;
    case BWH_GUARANTEE_RELATIVE:
        return rel;
    case BWH_GUARANTEE_BOTH:
        return fmin(g->max_error, rel);
    default:
        return -1.0;
    }
}

int bwh_guarantee_holds(const bwh_guarantee_t *g, float x, float v)
{
    if (g->kind == BWH_GUARANTEE_NONE)
        return 1;
    if (g->kind == BWH_GUARANTEE_EXACT || !isfinite(x))
        return bwh_float_to_bits(x) == bwh_float_to_bits(v);
    return isfinite(v) && fabs((double)v - (double)x) <= bwh_guarantee_bound(g, x);
}

size_t bwh_guarantee_check(const bwh_guarantee_t *g, const float *x, const float *v, size_t n,
                           size_t *first)
{
    size_t bad = 0;
    for (size_t i = 0; i < n; i++) {
        if (bwh_guarantee_holds(g, x[i], v[i]))
            continue;
        if (!bad && first)
            *first = i;
        bad++;
    }
    return bad;
}

void bwh_shortest(double v, char *buf, size_t cap)
{
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, cap, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            return;
    }
}

void bwh_guarantee_rule(const bwh_guarantee_t *g, char *buf, size_t cap)
{
    char e[32], r[32], fl[32], rel[100];
    bwh_shortest(g->max_error, e, sizeof e);
    bwh_shortest(g->max_rel_error, r, sizeof r);
    bwh_shortest(g->rel_floor, fl, sizeof fl);
    if (g->rel_floor > 0)
        snprintf(rel, sizeof rel, "max(%s |x|, %s)", r, fl);
    else
        snprintf(rel, sizeof rel, "%s |x|", r);
    switch (g->kind) {
    case BWH_GUARANTEE_EXACT:
        snprintf(buf, cap, "x' = x bit for bit");
        break;
    case BWH_GUARANTEE_ABSOLUTE:
        snprintf(buf, cap, "|x' - x| <= %s", e);
        break;
    case BWH_GUARANTEE_RELATIVE:
        snprintf(buf, cap, "|x' - x| <= %s", rel);
        break;
    case BWH_GUARANTEE_BOTH:
        snprintf(buf, cap, "|x' - x| <= min(%s, %s)", e, rel);
        break;
    default:
        snprintf(buf, cap, "no per-sample bound");
        break;
    }
}
