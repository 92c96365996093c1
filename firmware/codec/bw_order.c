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
    size_t b = pl->dims.bands, base = (size_t)bw_in_pos(pl, it->i) * pl->dims.n_out;
    it->prev = pl->stream || b == 1u ? NULL : it->vec;
    it->vec = it->x + (base + pos_out) * b;
    /* the parent: the vector at the position with this level's digit cleared
     * (coded before, at a coarser level) */
    it->par = level < 0 || pl->stream
                  ? NULL
                  : it->x + (base + (pos_out &
                                     ~(3u << (2u * (pl->dims.level_out - 1u - (unsigned)level))))) *
                                b;
    it->cls_dir = bw_level_cls(pl, level);
}

void bw_iter_init(bw_iter_t *it, const bw_plan_t *pl, int32_t *x)
{
    it->pl = pl;
    it->x = x;
    it->i = it->o = it->k = 0;
    it->leaf = 0;
    it->qi = it->q.n = 0;
    bw_walk_init(&it->w);
    it->vec = NULL;
    iter_vec(it);
}

void bw_iter_next_vec(bw_iter_t *it)
{
    it->k = 0;
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
