/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Band access (record 0x06, docs/FORMAT.md "Band access"): a set of spectra
 * coded so that a band, or a range of bands, decodes from the few columns
 * it depends on. Each spectrum is predicted coarse to fine along its bands
 * (each odd sample of a level from the mean of its two even neighbours, the
 * error quantised in the loop with a max-error bound); the errors are
 * coded column by column (a column: the errors at one position of every
 * spectrum) with a static code per level, each column found through a
 * table of lengths and checked by the CRC-32 of its group of 32 columns.
 */
#include <string.h>

#include "bw_crc32.h"
#include "bw_internal.h"
#include "bw_le.h"

#if BW_CFG_BANDS

#define GROUP 32u       /* columns per group */
#define NSYM 64u        /* symbols: three values capped at 3, two bits each */
#define MAXLEN 15u      /* the longest code */
#define LEVEL_BYTES 33u /* a level's table: k and the difference flag, 64 lengths */
#define GROUP_BYTES 9u  /* a group's: data bytes, CRC-32, width of its columns' lengths */
#define ZBITS 28u       /* coded values (zigzag) stay below 2^ZBITS */
#define VMAX ((int64_t)1 << 25) /* a prediction error, or a quantised one */
#define LEVELS_MAX 18u  /* prediction levels of 65535 bands: 15 */

/* The columns of a spectrum of `bands` samples: coding level 0 holds the
 * coarse samples (those at multiples of 2^J), coding level l >= 1 the
 * errors of prediction level j = J - l, at the odd multiples of 2^j. */
typedef struct {
    uint32_t bands, n;            /* samples per spectrum, spectra */
    unsigned J;                   /* prediction levels */
    uint32_t off[LEVELS_MAX + 1]; /* first column of each coding level, then bands */
} geo_t;

static void geo_make(geo_t *g, uint32_t bands, uint32_t n)
{
    unsigned J = 0;
    for (uint32_t m = bands; m > 2u; m = (m + 1u) >> 1)
        J++;
    g->bands = bands;
    g->n = n;
    g->J = J;
    g->off[0] = 0;
    g->off[1] = ((bands - 1u) >> J) + 1u; /* the coarse samples */
    for (unsigned l = 1; l <= J; l++) {
        unsigned j = J - l;
        g->off[l + 1u] = g->off[l] + ((((bands - 1u) >> j) + 1u) >> 1);
    }
}

/* The position in its spectrum of column c of coding level l. */
static inline uint32_t col_pos(const geo_t *g, unsigned l, uint32_t c)
{
    uint32_t m = c - g->off[l];
    return l ? (2u * m + 1u) << (g->J - l) : m << g->J;
}

static inline int32_t clamp_sample(int64_t v)
{
    return (int32_t)(v > BW_SAMPLE_MAX ? BW_SAMPLE_MAX : v < -BW_SAMPLE_MAX ? -BW_SAMPLE_MAX : v);
}

/* A sample from its prediction p and its coded error u: p + u q, within
 * the samples' range (an error outside it in a lossless payload is
 * corrupt: -1). */
static inline int rebuild(int64_t p, int32_t u, uint32_t q, int32_t *x)
{
    int64_t v = p + (int64_t)u * q;
    if (q == 1u && (v > BW_SAMPLE_MAX || v < -BW_SAMPLE_MAX))
        return -1;
    *x = clamp_sample(v);
    return 0;
}

/* The prediction of the sample at pos of prediction level j from the
 * rebuilt samples x of its spectrum. */
static inline int64_t predict_at(const int32_t *x, uint32_t bands, uint32_t pos, unsigned j)
{
    int64_t l = x[pos - (1u << j)];
    int64_t r = pos + (1u << j) < bands ? x[pos + (1u << j)] : l;
    return (l + r) >> 1;
}

/* ---- the tables ------------------------------------------------------------ */

/* A level's code, canonical: counts per length, symbols by (length, value). */
typedef struct {
    uint16_t cnt[MAXLEN + 1u];
    uint8_t sym[NSYM];
    uint8_t k, diff;
} code_t;

/* Reads a level's table at t: 0, or -1 when it is not one the encoder
 * writes (a code that is not complete, unless it has one symbol of length
 * 1). */
static int code_read(const uint8_t *t, code_t *c)
{
    if (t[0] & 0x60u || (t[0] & 31u) >= ZBITS)
        return -1;
    c->k = t[0] & 31u;
    c->diff = t[0] >> 7;
    memset(c->cnt, 0, sizeof c->cnt);
    for (unsigned s = 0; s < NSYM; s++)
        c->cnt[t[1u + s / 2u] >> (4u * (s & 1u)) & 15u]++;
    unsigned used = NSYM - c->cnt[0];
    int32_t left = 1;
    for (unsigned l = 1; l <= MAXLEN; l++) {
        left = 2 * left - c->cnt[l];
        if (left < 0)
            return -1;
    }
    if (!used || (left && !(used == 1u && c->cnt[1] == 1u)))
        return -1;
    unsigned idx[MAXLEN + 1u];
    idx[1] = 0;
    for (unsigned l = 1; l < MAXLEN; l++)
        idx[l + 1u] = idx[l] + c->cnt[l];
    for (unsigned s = 0; s < NSYM; s++) {
        unsigned l = t[1u + s / 2u] >> (4u * (s & 1u)) & 15u;
        if (l)
            c->sym[idx[l]++] = (uint8_t)s;
    }
    return 0;
}

/* Where a payload's tables and data lie. */
typedef struct {
    geo_t g;
    const uint8_t *levels, *groups, *lens, *data, *end;
    uint32_t ngroups;
    uint32_t q; /* the quantiser of the errors: 2E + 1, 1 lossless */
} layout_t;

/* Where the tables of payload p (header h) lie in L (its geometry made):
 * their bytes after the header before their CRC-32, or 0 when they do not
 * fit the body with that CRC or a width is above 32; *data: the groups'
 * bytes they give. */
static size_t tables_of(const bw_header_t *h, const uint8_t *p, layout_t *L, uint64_t *data)
{
    const bw_dims_t *d = &h->dims;
    geo_make(&L->g, d->bands, d->n_in);
    L->ngroups = (d->bands - 1u) / GROUP + 1u;
    size_t lt = (size_t)(L->g.J + 1u) * LEVEL_BYTES, gt = (size_t)L->ngroups * GROUP_BYTES;
    if (h->body_len < lt + gt)
        return 0;
    L->levels = p + h->header_len;
    L->groups = L->levels + lt;
    L->lens = L->groups + gt;
    uint64_t lbits = 0;
    *data = 0;
    for (uint32_t gi = 0; gi < L->ngroups; gi++) {
        const uint8_t *e = L->groups + (size_t)gi * GROUP_BYTES;
        uint32_t cols = gi + 1u < L->ngroups ? GROUP : d->bands - gi * GROUP;
        if (e[8] > 32u)
            return 0;
        lbits += (uint64_t)cols * e[8];
        *data += bw_get_u32(e);
    }
    size_t t = lt + gt + (size_t)((lbits + 7u) >> 3);
    return t + 4u <= h->body_len ? t : 0u;
}

static bw_status_t layout_of(const bw_header_t *h, const uint8_t *p, layout_t *L)
{
    uint64_t dbytes;
    size_t tables = tables_of(h, p, L, &dbytes), bl = h->body_len;
    if (!tables || dbytes != bl - tables - 4u)
        return BW_ERR_CORRUPT;
    /* the tables' CRC covers the header too */
    if (bw_get_u32(L->levels + tables) != bw_crc32(p, h->header_len + tables))
        return BW_ERR_CRC;
    L->q = h->mode == BW_MODE_MAX_ERROR ? 2u * h->max_error + 1u : 1u;
    L->data = L->levels + tables + 4u;
    L->end = L->levels + bl;
    return BW_OK;
}

size_t bw_bands_tables(const bw_header_t *h, const uint8_t *p)
{
    layout_t L;
    uint64_t dbytes;
    return tables_of(h, p, &L, &dbytes);
}

/* ---- bits --------------------------------------------------------------- */

typedef struct {
    const uint8_t *p;
    uint64_t pos, end; /* bits from p */
} reader_t;

/* The next bits (at most 57; zero past the end), least significant first:
 * the bytes read stay within those the reader's bits lie in. */
static inline uint64_t peek(const reader_t *r)
{
    uint64_t at = r->pos >> 3, left = ((r->end + 7u) >> 3) - at, v = 0;
    const uint8_t *q = r->p + at;
    if (left >= 8u) {
        for (unsigned i = 0; i < 8u; i++)
            v |= (uint64_t)q[i] << (8u * i);
    } else {
        for (unsigned i = 0; i < left; i++)
            v |= (uint64_t)q[i] << (8u * i);
    }
    v >>= r->pos & 7u;
    uint64_t avail = r->end - r->pos;
    return avail < 57u ? v & (((uint64_t)1 << avail) - 1u) : v & (((uint64_t)1 << 57) - 1u);
}

/* n <= 32 bits, least significant first; -1 past the end */
static inline int64_t get_bits(reader_t *r, unsigned n)
{
    if (r->end - r->pos < n)
        return -1;
    uint64_t v = n ? peek(r) & (((uint64_t)1 << n) - 1u) : 0u;
    r->pos += n;
    return (int64_t)v;
}

static int get_sym(reader_t *r, const code_t *c)
{
    uint64_t v = peek(r), avail = r->end - r->pos;
    int code = 0, first = 0, index = 0;
    for (unsigned l = 1; l <= MAXLEN && l <= avail; l++, v >>= 1) {
        code |= (int)(v & 1u);
        int count = c->cnt[l];
        if (code - first < count) {
            r->pos += l;
            return c->sym[index + code - first];
        }
        index += count;
        first = (first + count) << 1;
        code <<= 1;
    }
    return -1;
}

/* The n errors of a column, exactly its bits, into dst[i * stride]. */
static bw_status_t get_column(reader_t *r, const code_t *c, uint32_t n, int32_t *dst,
                              size_t stride)
{
    int64_t prev = 0;
    if (r->pos == r->end) { /* no bits: every error 0 */
        for (uint32_t i = 0; i < n; i++)
            dst[(size_t)i * stride] = 0;
        return BW_OK;
    }
    for (uint32_t i = 0; i < n; i += 3u) {
        int s = get_sym(r, c);
        unsigned m = n - i < 3u ? n - i : 3u;
        if (s < 0 || s >> (2u * m))
            return BW_ERR_CORRUPT; /* (a short tuple's missing values are 0) */
        for (unsigned e = 0; e < m; e++) {
            uint64_t hi = (unsigned)s >> (2u * e) & 3u;
            if (hi == 3u) { /* exp-Golomb of hi - 3: z zeros, a one, z bits */
                uint64_t v = peek(r);
                unsigned z = 0;
                while (z <= ZBITS && !(v >> z & 1u))
                    z++;
                if (z > ZBITS || r->end - r->pos < z + 1u)
                    return BW_ERR_CORRUPT;
                r->pos += z + 1u;
                int64_t rest = get_bits(r, z);
                if (rest < 0)
                    return BW_ERR_CORRUPT;
                hi = 3u + ((uint64_t)1 << z) - 1u + (uint64_t)rest;
            }
            int64_t lo = get_bits(r, c->k);
            if (lo < 0 || hi >= (uint64_t)1 << (ZBITS - c->k))
                return BW_ERR_CORRUPT;
            uint64_t zz = hi << c->k | (uint64_t)lo;
            int64_t v = (int64_t)(zz >> 1) ^ -(int64_t)(zz & 1u);
            if (c->diff)
                v += prev;
            prev = v;
            if (v >= VMAX || v <= -VMAX)
                return BW_ERR_CORRUPT;
            dst[(size_t)(i + e) * stride] = (int32_t)v;
        }
    }
    return r->pos == r->end ? BW_OK : BW_ERR_CORRUPT;
}

/* Walks the columns in order: the group each lies in (checked once, when
 * it is first entered) and the bits of its data. */
typedef struct {
    const layout_t *L;
    uint32_t at;          /* the group gdata and lens_bit begin */
    bool checked;         /* its CRC and lengths checked */
    const uint8_t *gdata; /* its data */
    uint64_t lens_bit;    /* its columns' length fields */
    uint64_t at_bit[GROUP + 1u]; /* where each of its columns begins, checked */
} cursor_t;

static void cursor_init(cursor_t *cu, const layout_t *L)
{
    cu->L = L;
    cu->at = 0;
    cu->checked = false;
    cu->gdata = L->data;
    cu->lens_bit = 0;
}

/* The w-bit field at bit `bit` of lens (w <= 32; the tables hold it). */
static uint32_t len_field(const uint8_t *lens, uint64_t bit, unsigned w)
{
    const uint8_t *q = lens + (bit >> 3);
    unsigned sh = (unsigned)(bit & 7u), nb = (sh + w + 7u) >> 3;
    uint64_t v = 0;
    for (unsigned i = 0; i < nb; i++)
        v |= (uint64_t)q[i] << (8u * i);
    return w ? (uint32_t)(v >> sh & (((uint64_t)1 << w) - 1u)) : 0u;
}

/* Column c (at or after the last one asked for): its reader. */
static bw_status_t cursor_column(cursor_t *cu, uint32_t c, reader_t *r)
{
    const layout_t *L = cu->L;
    uint32_t g = c / GROUP;
    for (; cu->at < g; cu->at++) { /* (every group before the last has GROUP columns) */
        const uint8_t *e = L->groups + (size_t)cu->at * GROUP_BYTES;
        cu->gdata += bw_get_u32(e);
        cu->lens_bit += (uint64_t)GROUP * e[8];
        cu->checked = false;
    }
    if (!cu->checked) {
        /* where its columns begin; its CRC, and its columns' lengths fill
         * its bytes exactly */
        const uint8_t *e = L->groups + (size_t)g * GROUP_BYTES;
        unsigned w = e[8];
        uint32_t cols = g + 1u < L->ngroups ? GROUP : L->g.bands - g * GROUP, gb = bw_get_u32(e);
        uint64_t bits = 0;
        for (uint32_t k = 0; k < cols; k++) {
            cu->at_bit[k] = bits;
            bits += len_field(L->lens, cu->lens_bit + (uint64_t)k * w, w);
        }
        cu->at_bit[cols] = bits;
        if ((bits + 7u) >> 3 != gb || (bits & 7u && cu->gdata[gb - 1u] >> (bits & 7u)))
            return BW_ERR_CORRUPT;
        if (bw_crc32(cu->gdata, gb) != bw_get_u32(e + 4))
            return BW_ERR_CRC;
        cu->checked = true;
    }
    r->p = cu->gdata;
    r->pos = cu->at_bit[c - g * GROUP];
    r->end = cu->at_bit[c - g * GROUP + 1u];
    return BW_OK;
}

/* ---- the decoders ------------------------------------------------------- */

static BW_NOINLINE bw_status_t bands_decode(const bw_header_t *h, const uint8_t *p, int32_t *x);

/* (the payload's CRC-32 vouched for the bytes: a table's or a group's CRC
 * that fails is a corrupt body) */
BW_NOINLINE bw_status_t bw_bands_decode(const bw_header_t *h, const uint8_t *p, int32_t *x)
{
    bw_status_t st = bands_decode(h, p, x);
    return st == BW_ERR_CRC ? BW_ERR_CORRUPT : st;
}

static BW_NOINLINE bw_status_t bands_decode(const bw_header_t *h, const uint8_t *p, int32_t *x)
{
    layout_t L;
    bw_status_t st = layout_of(h, p, &L);
    if (st != BW_OK)
        return st;
    const geo_t *g = &L.g;
    uint32_t B = g->bands;
    cursor_t cu;
    cursor_init(&cu, &L);
    for (unsigned l = 0; l <= g->J; l++) {
        code_t c;
        if (code_read(L.levels + (size_t)l * LEVEL_BYTES, &c) != 0)
            return BW_ERR_CORRUPT;
        for (uint32_t col = g->off[l]; col < g->off[l + 1u]; col++) {
            reader_t r;
            st = cursor_column(&cu, col, &r);
            if (st == BW_OK)
                st = get_column(&r, &c, g->n, x + col_pos(g, l, col), B);
            if (st != BW_OK)
                return st;
        }
    }
    /* every spectrum coarse to fine, in place */
    for (uint32_t s = 0; s < g->n; s++) {
        int32_t *y = x + (size_t)s * B;
        for (uint32_t pos = 0; pos < B; pos += 1u << g->J)
            if (rebuild(0, y[pos], L.q, &y[pos]) != 0)
                return BW_ERR_CORRUPT;
        for (unsigned l = 1; l <= g->J; l++) {
            unsigned j = g->J - l;
            for (uint32_t pos = 1u << j; pos < B; pos += 2u << j)
                if (rebuild(predict_at(y, B, pos, j), y[pos], L.q, &y[pos]) != 0)
                    return BW_ERR_CORRUPT;
        }
    }
    return BW_OK;
}

size_t bw_band_range_work(uint32_t n_in, uint32_t bands)
{
    return (2u * (size_t)bands + 4u * LEVELS_MAX + 8u) * ((size_t)n_in + 1u);
}

bw_status_t bw_decode_band_range(const uint8_t *payload, size_t len, uint32_t b0, uint32_t b1,
                                 int32_t *out, size_t out_cap, int32_t *work, size_t work_cap,
                                 bw_header_t *hdr_out)
{
    bw_header_t h;
    if (!payload || !out || !work)
        return BW_ERR_ARG;
    bw_status_t st = bw_header_parse_fields(payload, len, &h);
    if (hdr_out)
        *hdr_out = h;
    if (st != BW_OK)
        return st;
    if (!h.band_access || b0 >= b1 || b1 > h.dims.bands)
        return BW_ERR_ARG;
    layout_t L;
    const geo_t *g = &L.g;
    uint32_t R = b1 - b0, N = h.dims.n_in;
    if (out_cap < (size_t)N * R || work_cap < bw_band_range_work(N, R))
        return BW_ERR_WORK;
    st = layout_of(&h, payload, &L);
    if (st != BW_OK)
        return st;
    /* the range of indices each prediction level needs, fine to coarse:
     * an odd index its two even neighbours (the right one when there is
     * one), an even one itself */
    uint32_t lo[LEVELS_MAX], hi[LEVELS_MAX];
    lo[0] = b0;
    hi[0] = b1 - 1u;
    for (unsigned j = 0; j < g->J; j++) {
        uint32_t nn = ((g->bands - 1u) >> (j + 1u)) + 1u;
        lo[j + 1u] = lo[j] >> 1;
        hi[j + 1u] = (hi[j] + 1u) >> 1 < nn ? (hi[j] + 1u) >> 1 : nn - 1u;
    }
    /* the columns, coarse first: the coarse samples lo[J]..hi[J], then at
     * each level the errors of its odd indices */
    int32_t *cols = work;
    size_t nc = 0;
    cursor_t cu;
    cursor_init(&cu, &L);
    for (unsigned l = 0; l <= g->J; l++) {
        /* coarse: lo[J]..hi[J]; a level's errors: its odd indices a..e,
         * error (i - 1) / 2 of the level for index i */
        unsigned j = g->J - l;
        uint32_t a = l ? (lo[j] | 1u) : lo[j], e = l ? ((hi[j] - 1u) | 1u) : hi[j];
        if (a > hi[j])
            continue;
        uint32_t first = l ? (a - 1u) / 2u : a, count = l ? (e - a) / 2u + 1u : e - a + 1u;
        code_t c;
        if (code_read(L.levels + (size_t)l * LEVEL_BYTES, &c) != 0)
            return BW_ERR_CORRUPT;
        for (uint32_t m = 0; m < count; m++, nc++) {
            reader_t r;
            st = cursor_column(&cu, g->off[l] + first + m, &r);
            if (st == BW_OK)
                st = get_column(&r, &c, N, cols + nc * N, 1u);
            if (st != BW_OK)
                return st;
        }
    }
    /* each spectrum: the needed samples of each level, coarse to fine */
    int32_t *lv = cols + nc * N, *buf[LEVELS_MAX];
    for (unsigned j = g->J + 1u; j-- > 0u;) {
        buf[j] = lv;
        lv += hi[j] - lo[j] + 1u;
    }
    for (uint32_t s = 0; s < N; s++) {
        size_t t = 0;
        int32_t *y = buf[g->J];
        for (uint32_t i = lo[g->J]; i <= hi[g->J]; i++, t++)
            if (rebuild(0, cols[t * N + s], L.q, &y[i - lo[g->J]]) != 0)
                return BW_ERR_CORRUPT;
        for (unsigned l = 1; l <= g->J; l++) {
            unsigned j = g->J - l;
            const int32_t *up = buf[j + 1u];
            y = buf[j];
            for (uint32_t i = lo[j]; i <= hi[j]; i++) {
                if (!(i & 1u)) {
                    y[i - lo[j]] = up[i / 2u - lo[j + 1u]];
                    continue;
                }
                int64_t pl = up[(i - 1u) / 2u - lo[j + 1u]];
                int64_t pr = (i + 1u) << j < g->bands ? up[(i + 1u) / 2u - lo[j + 1u]] : pl;
                if (rebuild((pl + pr) >> 1, cols[t * N + s], L.q, &y[i - lo[j]]) != 0)
                    return BW_ERR_CORRUPT;
                t++;
            }
        }
        memcpy(out + (size_t)s * R, buf[0], R * sizeof *out);
    }
    return BW_OK;
}

/* ---- the encoder -------------------------------------------------------- */

typedef struct {
    uint8_t *p;
    size_t cap; /* bytes */
    uint64_t pos;
} writer_t;

static inline void put_bits(writer_t *w, uint64_t v, unsigned n)
{
    for (unsigned i = 0; i < n; i++, w->pos++)
        if ((w->pos >> 3) < w->cap)
            w->p[w->pos >> 3] |= (uint8_t)((v >> i & 1u) << (w->pos & 7u));
}

/* The zigzag value of element s of column col, and the previous error. */
static inline uint32_t zig(const int32_t *e, const geo_t *g, uint32_t pos, uint32_t s, bool diff)
{
    int64_t v = e[(size_t)s * g->bands + pos];
    if (diff && s)
        v -= e[(size_t)(s - 1u) * g->bands + pos];
    return (uint32_t)(v < 0 ? -2 * v - 1 : 2 * v);
}

static unsigned bitlen(uint64_t v)
{
    unsigned n = 0;
    while (v) {
        n++;
        v >>= 1;
    }
    return n;
}

/* Bits beside the code of value z: the escape and the k low bits. */
static inline unsigned extra_bits(uint32_t z, unsigned k)
{
    uint32_t hi = z >> k;
    return k + (hi >= 3u ? 2u * bitlen(hi - 2u) - 1u : 0u);
}

/* Code lengths of at most MAXLEN bits for the frequencies f (Huffman's,
 * the frequencies halved until the longest fits). */
static void huff_lengths(const uint32_t *f0, uint8_t *len)
{
    uint32_t f[NSYM];
    memcpy(f, f0, sizeof f);
    for (;;) {
        uint32_t w[2u * NSYM]; /* (at most the tuples of a level: below 2^32) */
        int16_t parent[2u * NSYM];
        bool live[2u * NSYM];
        unsigned nn = 0, used = 0;
        for (unsigned s = 0; s < NSYM; s++) {
            w[s] = f[s];
            live[s] = f[s] != 0u;
            parent[s] = -1;
            used += live[s];
        }
        nn = NSYM;
        memset(len, 0, NSYM);
        if (used == 1u) {
            for (unsigned s = 0; s < NSYM; s++)
                len[s] = f[s] ? 1u : 0u;
            return;
        }
        for (unsigned m = 1; m < used; m++) {
            int a = -1, b = -1;
            for (unsigned i = 0; i < nn; i++) {
                if (!live[i])
                    continue;
                if (a < 0 || w[i] < w[a]) {
                    b = a;
                    a = (int)i;
                } else if (b < 0 || w[i] < w[b]) {
                    b = (int)i;
                }
            }
            w[nn] = w[a] + w[b];
            live[nn] = true;
            parent[nn] = -1;
            live[a] = live[b] = false;
            parent[a] = parent[b] = (int16_t)nn;
            nn++;
        }
        unsigned longest = 0;
        for (unsigned s = 0; s < NSYM; s++) {
            unsigned d = 0;
            for (int i = f[s] ? (int)s : -1; i >= 0 && parent[i] >= 0; i = parent[i])
                d++;
            len[s] = (uint8_t)d;
            longest = d > longest ? d : longest;
        }
        if (longest <= MAXLEN)
            return;
        for (unsigned s = 0; s < NSYM; s++)
            f[s] = f[s] ? (f[s] + 1u) / 2u : 0u;
    }
}

/* The canonical codes of the lengths len. */
static void huff_codes(const uint8_t *len, uint16_t *code)
{
    uint16_t cnt[MAXLEN + 2u] = {0}, next[MAXLEN + 2u];
    for (unsigned s = 0; s < NSYM; s++)
        cnt[len[s]]++;
    cnt[0] = 0;
    uint16_t c = 0;
    for (unsigned l = 1; l <= MAXLEN; l++) {
        c = (uint16_t)((c + cnt[l - 1u]) << 1);
        next[l] = c;
    }
    for (unsigned s = 0; s < NSYM; s++)
        code[s] = len[s] ? next[len[s]]++ : 0u;
}

static inline unsigned tuple_sym(const int32_t *e, const geo_t *g, uint32_t pos, uint32_t i,
                                 bool diff, unsigned k)
{
    unsigned s = 0;
    for (unsigned t = 0; t < 3u && i + t < g->n; t++) {
        uint32_t hi = zig(e, g, pos, i + t, diff) >> k;
        s |= (hi < 3u ? hi : 3u) << (2u * t);
    }
    return s;
}

/* Whether every error of column c (at pos) is 0: it is coded in no bits. */
static bool zero_column(const int32_t *e, const geo_t *g, uint32_t pos)
{
    for (uint32_t s = 0; s < g->n; s++)
        if (e[(size_t)s * g->bands + pos])
            return false;
    return true;
}

/* The symbols' frequencies and the extra bits of coding level l with k and
 * diff (its columns of errors 0 apart). */
static uint64_t level_stats(const int32_t *e, const geo_t *g, unsigned l, bool diff, unsigned k,
                            uint32_t *f)
{
    uint64_t extra = 0;
    memset(f, 0, NSYM * sizeof *f);
    for (uint32_t c = g->off[l]; c < g->off[l + 1u]; c++) {
        uint32_t pos = col_pos(g, l, c);
        if (zero_column(e, g, pos))
            continue;
        for (uint32_t i = 0; i < g->n; i += 3u) {
            f[tuple_sym(e, g, pos, i, diff, k)]++;
            for (unsigned t = 0; t < 3u && i + t < g->n; t++)
                extra += extra_bits(zig(e, g, pos, i + t, diff), k);
        }
    }
    return extra;
}

/* Chooses coding level l's k and difference flag (the fewest bits) and
 * writes its table at t. */
static void level_choose(const int32_t *e, const geo_t *g, unsigned l, uint8_t *t)
{
    uint32_t f[NSYM], zmax = 0;
    uint8_t len[NSYM];
    uint64_t best = UINT64_MAX;
    for (uint32_t c = g->off[l]; c < g->off[l + 1u]; c++)
        for (uint32_t s = 0; s < g->n; s++) {
            uint32_t a = zig(e, g, col_pos(g, l, c), s, false), b = zig(e, g, col_pos(g, l, c), s, true);
            zmax = a > zmax ? a : zmax;
            zmax = b > zmax ? b : zmax;
        }
    unsigned kmax = bitlen(zmax);
    for (unsigned diff = 0; diff < 2u; diff++)
        for (unsigned k = 0; k <= kmax && k < ZBITS; k++) {
            uint64_t bits = level_stats(e, g, l, diff, k, f);
            if (!bits && !f[0]) /* (every column 0: a code of one symbol, never used) */
                f[0] = 1u;
            huff_lengths(f, len);
            for (unsigned s = 0; s < NSYM; s++)
                bits += (uint64_t)f[s] * len[s];
            if (bits < best) {
                best = bits;
                t[0] = (uint8_t)(k | diff << 7);
                memset(t + 1, 0, LEVEL_BYTES - 1u);
                for (unsigned s = 0; s < NSYM; s++)
                    t[1u + s / 2u] |= (uint8_t)(len[s] << (4u * (s & 1u)));
            }
        }
}

/* Codes column c of coding level l (w NULL: counts its bits). */
static uint64_t put_column(writer_t *w, const int32_t *e, const geo_t *g, unsigned l, uint32_t c,
                           const uint8_t *t, const uint16_t *code)
{
    unsigned k = t[0] & 31u;
    bool diff = t[0] >> 7;
    uint32_t pos = col_pos(g, l, c);
    uint64_t bits = 0;
    if (zero_column(e, g, pos))
        return 0;
    for (uint32_t i = 0; i < g->n; i += 3u) {
        unsigned s = tuple_sym(e, g, pos, i, diff, k);
        unsigned ln = t[1u + s / 2u] >> (4u * (s & 1u)) & 15u;
        bits += ln;
        for (unsigned b = ln; w && code && b-- > 0u;)
            put_bits(w, code[s] >> b & 1u, 1u);
        for (unsigned u = 0; u < 3u && i + u < g->n; u++) {
            uint32_t z = zig(e, g, pos, i + u, diff), hi = z >> k;
            bits += extra_bits(z, k);
            if (!w)
                continue;
            if (hi >= 3u) {
                uint32_t v = hi - 2u; /* exp-Golomb of hi - 3: v = hi - 3 + 1 */
                unsigned nb = bitlen(v);
                put_bits(w, 0u, nb - 1u);
                put_bits(w, 1u, 1u);
                put_bits(w, v & (((uint64_t)1 << (nb - 1u)) - 1u), nb - 1u);
            }
            put_bits(w, z & (((uint64_t)1 << k) - 1u), k);
        }
    }
    return bits;
}

bw_status_t bw_bands_encode(const bw_plan_t *pl, const bw_params_t *pa, const int32_t *x,
                            int32_t *work, uint8_t *out, size_t out_cap, size_t *out_len)
{
    geo_t g;
    const bw_dims_t *d = &pl->dims;
    geo_make(&g, d->bands, d->n_in);
    uint32_t B = d->bands, q = pa->mode == BW_MODE_MAX_ERROR ? 2u * pa->max_error + 1u : 1u;
    size_t n = (size_t)B * g.n;
    int32_t *e = work, *rec = work + n;
    for (size_t i = 0; i < n; i++) /* (every error then within +-VMAX) */
        if (x[i] > BW_SAMPLE_MAX || x[i] < -BW_SAMPLE_MAX)
            return BW_ERR_RANGE;
    /* the errors, each sample predicted from the rebuilt ones */
    for (uint32_t s = 0; s < g.n; s++) {
        const int32_t *xs = x + (size_t)s * B;
        int32_t *es = e + (size_t)s * B;
        for (unsigned l = 0; l <= g.J; l++) {
            unsigned j = g.J - l;
            for (uint32_t c = g.off[l]; c < g.off[l + 1u]; c++) {
                uint32_t pos = col_pos(&g, l, c);
                int64_t p = l ? predict_at(rec, B, pos, j) : 0, r = xs[pos] - p;
                int64_t u = r >= 0 ? (r + (int64_t)(q / 2u)) / q : -((-r + (int64_t)(q / 2u)) / q);
                es[pos] = (int32_t)u;
                rec[pos] = clamp_sample(p + u * q);
            }
        }
    }
    /* the header, then the tables, the lengths, their CRC, the data */
    size_t hl = bw_header_write(NULL, pl, pa, pa->mode);
    uint32_t ng = (B - 1u) / GROUP + 1u;
    size_t lt = (size_t)(g.J + 1u) * LEVEL_BYTES, gt = (size_t)ng * GROUP_BYTES;
    if (out_cap < hl + lt + gt + 8u)
        return BW_ERR_OUTPUT_FULL;
    memset(out, 0, hl + lt + gt);
    bw_header_write(out, pl, pa, pa->mode);
    uint8_t *lev = out + hl, *grp = lev + lt;
    uint32_t *lens = (uint32_t *)rec; /* (the rebuilt spectrum is no longer needed) */
    uint16_t codes[NSYM];
    for (unsigned l = 0; l <= g.J; l++) {
        level_choose(e, &g, l, lev + (size_t)l * LEVEL_BYTES);
        for (uint32_t c = g.off[l]; c < g.off[l + 1u]; c++)
            lens[c] = (uint32_t)put_column(NULL, e, &g, l, c, lev + (size_t)l * LEVEL_BYTES, NULL);
    }
    uint64_t lbits = 0, dbytes = 0;
    for (uint32_t gi = 0; gi < ng; gi++) {
        uint32_t c0 = gi * GROUP, c1 = c0 + GROUP < B ? c0 + GROUP : B, mx = 0;
        uint64_t bits = 0;
        for (uint32_t c = c0; c < c1; c++) {
            mx = lens[c] > mx ? lens[c] : mx;
            bits += lens[c];
        }
        grp[(size_t)gi * GROUP_BYTES + 8u] = (uint8_t)bitlen(mx);
        bw_put_u32(grp + (size_t)gi * GROUP_BYTES, (uint32_t)((bits + 7u) >> 3));
        lbits += (uint64_t)(c1 - c0) * bitlen(mx);
        dbytes += (bits + 7u) >> 3;
    }
    size_t tables = lt + gt + (size_t)((lbits + 7u) >> 3);
    size_t total = hl + tables + 4u + (size_t)dbytes + BW_TRAILER_SIZE;
    if (dbytes > UINT32_MAX || total > out_cap)
        return BW_ERR_OUTPUT_FULL;
    memset(out + hl + lt + gt, 0, total - (hl + lt + gt));
    writer_t lw = {out + hl + lt + gt, tables - lt - gt, 0};
    for (uint32_t gi = 0; gi < ng; gi++) {
        unsigned wd = grp[(size_t)gi * GROUP_BYTES + 8u];
        for (uint32_t c = gi * GROUP; c < B && c < (gi + 1u) * GROUP; c++)
            put_bits(&lw, lens[c], wd);
    }
    uint8_t *data = out + hl + tables + 4u;
    for (uint32_t gi = 0, l = 0, coded = UINT32_MAX; gi < ng; gi++) {
        uint32_t gb = bw_get_u32(grp + (size_t)gi * GROUP_BYTES);
        writer_t w = {data, gb, 0};
        for (uint32_t c = gi * GROUP; c < B && c < (gi + 1u) * GROUP; c++) {
            while (c >= g.off[l + 1u])
                l++;
            const uint8_t *t = lev + (size_t)l * LEVEL_BYTES;
            if (coded != l) { /* the level's canonical codes */
                uint8_t len[NSYM];
                for (unsigned s = 0; s < NSYM; s++)
                    len[s] = t[1u + s / 2u] >> (4u * (s & 1u)) & 15u;
                huff_codes(len, codes);
                coded = l;
            }
            put_column(&w, e, &g, l, c, t, codes);
        }
        bw_put_u32(grp + (size_t)gi * GROUP_BYTES + 4u, bw_crc32(data, gb));
        data += gb;
    }
    bw_put_u32(out + hl + tables, bw_crc32(out, hl + tables));
    bw_put_u32(out + total - BW_TRAILER_SIZE, bw_crc32(out, total - BW_TRAILER_SIZE));
    *out_len = total;
    return BW_OK;
}

#else /* a core without band access: its payloads are refused */

size_t bw_band_range_work(uint32_t n_in, uint32_t bands)
{
    (void)n_in;
    (void)bands;
    return 0;
}

size_t bw_bands_tables(const bw_header_t *h, const uint8_t *payload)
{
    (void)h;
    (void)payload;
    return 0;
}

bw_status_t bw_decode_band_range(const uint8_t *payload, size_t len, uint32_t b0, uint32_t b1,
                                 int32_t *samples, size_t samples_cap, int32_t *work,
                                 size_t work_cap, bw_header_t *hdr_out)
{
    (void)payload;
    (void)len;
    (void)b0;
    (void)b1;
    (void)samples;
    (void)samples_cap;
    (void)work;
    (void)work_cap;
    (void)hdr_out;
    return BW_ERR_NOT_BUILT;
}

#endif
