/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The coding order (docs/FORMAT.md, Body): incoming coefficients coarse to
 * fine, then the outgoing ones, coarse to fine or in the order a streaming
 * encoder completes them, then the spectral ones as stored; with the parent
 * and the previous vector each coefficient's contexts come from.
 */
#include "bw_internal.h"

void bw_walk_init(bw_walk_t *w)
{
    w->j = -1;
    w->p = 0;
    w->m = 1;
}

uint32_t bw_walk_next(bw_walk_t *w, unsigned L, int *level)
{
    uint32_t pos;
    *level = w->j;
    if (w->j < 0) {
        pos = w->p << (2u * L);
        if (++w->p == 4u) {
            w->j = 0;
            w->p = 0;
            w->m = 1;
        }
        return pos;
    }
    pos = (4u * w->p + w->m) << (2u * (L - (unsigned)w->j - 1u));
    if (++w->m == 4u) {
        w->m = 1;
        if (++w->p == 4u << (2u * (unsigned)w->j)) {
            w->p = 0;
            w->j++;
        }
    }
    return pos;
}

/* The outgoing vectors completed by leaf t of a level-L hemisphere, in order:
 * the details of every ancestor whose last leaf t is (lowest first), then
 * the scaling coefficient of the base triangle when t ends it. */
static void stream_leaf(unsigned L, uint32_t t, bw_stream_queue_t *q)
{
    q->n = 0;
    for (unsigned k = 1; k <= L && ((t + 1u) & ((1u << (2u * k)) - 1u)) == 0u; k++) {
        uint32_t p = t >> (2u * k);
        for (uint32_t m = 1; m <= 3u; m++) {
            q->pos[q->n] = (4u * p + m) << (2u * (k - 1u));
            q->level[q->n++] = (int8_t)(L - k);
        }
    }
    if (((t + 1u) & ((1u << (2u * L)) - 1u)) == 0u) {
        q->pos[q->n] = (t >> (2u * L)) << (2u * L);
        q->level[q->n++] = -1;
    }
}

/* The coarse-to-fine index of the outgoing coefficient at in-place position
 * t of a level-L hemisphere: child d (1..3) of parent P at level k - 1 is
 * 4^k + 3 P + d - 1 (its last non-zero child digit, at depth k); a scaling
 * coefficient is its base triangle's number. */
uint32_t bw_cf_index(uint32_t t, unsigned L)
{
    for (unsigned k = L; k >= 1u; k--) {
        uint32_t d = (t >> (2u * (L - k))) & 3u;
        if (d)
            return (1u << (2u * k)) + 3u * (t >> (2u * (L - k + 1u))) + d - 1u;
    }
    return t >> (2u * L);
}

static void iter_vec(bw_iter_t *it)
{
    const bw_plan_t *pl = it->pl;
    uint32_t pos_out = 0;
    int level = -1;
    if (bw_has_out(&pl->dims)) {
        if (pl->stream) {
            while (it->qi == it->q.n) {
                stream_leaf(pl->dims.level_out, it->leaf++, &it->q);
                it->qi = 0;
            }
            pos_out = it->q.pos[it->qi];
            level = it->q.level[it->qi++];
        } else {
            pos_out = bw_walk_next(&it->w, pl->dims.level_out, &level);
        }
    }
    /* the incoming block's place: once a block, or (where flash counts
     * more) every vector */
    size_t b = pl->dims.bands, base;
    if (BW_CFG_SPEED || BW_CFG_EMBED) {
        if (it->base_i != it->i) {
            it->base_i = it->i;
            it->base = (size_t)bw_in_pos(pl, it->i) * pl->dims.n_out;
        }
        base = it->base;
    } else {
        base = (size_t)bw_in_pos(pl, it->i) * pl->dims.n_out;
    }
    unsigned L = pl->dims.level_out;
    it->prev = pl->stream || b == 1u ? NULL : it->vec;
    it->vec = it->x + (base + pos_out) * b;
    /* the parent: the vector at the position with this level's digit cleared
     * (coded before, at a coarser level) */
    uint32_t par_pos = level < 0 ? 0u : pos_out & ~(3u << (2u * (L - 1u - (unsigned)level)));
    it->par = level < 0 || pl->stream ? NULL : it->x + (base + par_pos) * b;
    it->cls_dir = bw_level_cls(pl, level);
    if (BW_CFG_EMBED)
        it->lvl = level;
    /* no context from before the segment: the parent of a segment that
     * began in this block may lie before it */
    size_t first = (size_t)it->i * pl->dims.n_out;
    if (BW_CFG_SEGMENTS && it->par && it->seg0 > first && first + bw_cf_index(par_pos, L) < it->seg0)
        it->par = NULL;
    if (BW_CFG_SEGMENTS && it->vi == it->seg0)
        it->prev = NULL;
}

/* The iterator at the first vector of incoming block i. */
static void iter_start(bw_iter_t *it, const bw_plan_t *pl, int32_t *x, uint32_t i)
{
    it->pl = pl;
    it->x = x;
    it->i = i;
    it->o = it->k = 0;
    it->leaf = 0;
    it->qi = it->q.n = 0;
    bw_walk_init(&it->w);
    it->vec = NULL;
    it->vi = it->seg0 = (size_t)i * pl->dims.n_out;
    if (BW_CFG_SPEED || BW_CFG_EMBED)
        it->base_i = UINT32_MAX;
    if (i < pl->dims.n_in)
        iter_vec(it);
}

void bw_iter_init(bw_iter_t *it, const bw_plan_t *pl, int32_t *x) { iter_start(it, pl, x, 0u); }

void bw_iter_at(bw_iter_t *it, const bw_plan_t *pl, int32_t *x, size_t vi)
{
    /* the first vector of vi's block, then a step at a time to vi */
    iter_start(it, pl, x, (uint32_t)(vi / pl->dims.n_out));
    while (it->vi < vi)
        bw_iter_next_vec(it);
}

#if BW_CFG_EMBED
void bw_iter_seek(bw_iter_t *it, size_t vi)
{
    const bw_plan_t *pl = it->pl;
    size_t from = vi > it->seg0 ? vi - 1u : vi; /* the vector before: `prev` */
    uint32_t i = (uint32_t)(from / pl->dims.n_out), o = (uint32_t)(from % pl->dims.n_out);
    it->i = i;
    it->o = o;
    it->vi = from;
    it->k = 0;
    it->vec = NULL;
    /* the walk about to yield coarse-to-fine index o */
    if (o < 4u) {
        it->w.j = -1;
        it->w.p = o;
        it->w.m = 1u;
    } else {
        int j = bw_biohaar_coef_level(o);
        uint32_t r = o - (1u << (2u * (unsigned)(j + 1)));
        it->w.j = j;
        it->w.p = r / 3u;
        it->w.m = r % 3u + 1u;
    }
    iter_vec(it);
    if (from != vi)
        bw_iter_next_vec(it);
}
#endif

void bw_iter_segment(bw_iter_t *it)
{
    it->seg0 = it->vi;
    it->prev = NULL;
    it->par = NULL; /* coded before this vector, so before the segment */
}


void bw_iter_next_vec(bw_iter_t *it)
{
    it->k = 0;
    if (BW_CFG_SEGMENTS)
        it->vi++;
    if (++it->o == it->pl->dims.n_out) {
        it->o = 0;
        it->i++;
        it->leaf = 0;
        it->qi = it->q.n = 0;
        bw_walk_init(&it->w);
    }
    if (it->i < it->pl->dims.n_in)
        iter_vec(it);
}
