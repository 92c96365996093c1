/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * brdfwave codec core: what the core's modules share and callers do not see.
 *
 * The plan of one encode or decode (bw_plan_t, made by bw_plan_make from the
 * dims, the basis, the mode and the flags), the helpers every module reads it
 * with, and each module's functions for the others. The modules and their
 * jobs are listed in bw_codec.h.
 */
#ifndef BW_INTERNAL_H
#define BW_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bw_biohaar.h"
#include "bw_codec.h"
#include "bw_config.h"
#include "bw_fixed.h"
#include "bw_spectral.h"

#define BW_VERSION 6u     /* payloads without extension records */
#define BW_VERSION_EXT 7u /* with them (BW_FLAG_EXT)             */
#define BW_MAGIC0 'B'
#define BW_MAGIC1 'W'
#define BW_STEP_ONE_Q8 256u   /* a step of 1.0 (Q24.8): coefficients are kept exactly */
#define BW_VEC_THRESH_Q8 256u /* default vector threshold: one step (Q8)             */

/* ---- the plan (bw_plan.c) ------------------------------------------------ */

typedef struct {
    bw_dims_t dims;
    size_t n;
    unsigned basis;
    unsigned spec_levels;
    uint32_t prequant;      /* max-error prequantiser 2E + 1, else 1            */
    uint32_t step_q8;       /* base quantiser step, unsigned Q24.8               */
    uint32_t vec_thresh_q8; /* vector threshold in steps, Q8                     */
    uint32_t round_q8;      /* encoder: rounding offset of the quantiser, Q8     */
    uint32_t round_cut;     /* encoder: coefficient k of the v-th vector quantised
                             * takes round_q8 + 1 where k V + v < round_cut (V vectors) */
    bool mirror;            /* BW_FLAG_MIRROR */
    bool recip;             /* BW_FLAG_RECIPROCAL */
    bool stream;            /* coding order: streamed (post-order) instead of coarse-to-fine */
    uint32_t seg_vec;       /* vectors per segment (BW_EXT_SEGMENTS), 0: one body */
    uint8_t embed;          /* embedded segments (BW_EXT_EMBEDDED): 0 none, 1 + the form */
    bool bands;             /* band access (BW_EXT_BANDS) */
#if BW_CFG_CHUNK_STEPS
    uint32_t chunk_vec;     /* vectors per chunk (BW_EXT_CHUNK_STEPS), 0: one step */
    const int8_t *chunk_d;  /* [chunks] each chunk's step change (bw_chunk_step) */
#endif
#if BW_CFG_FAST_BUDGET && BW_CFG_CHUNK_STEPS
    struct bw_rate *rate;   /* encoder: quantises as the body codes (bw_budget.c), or NULL */
#endif
    int32_t *spec_cls;      /* [bands] context class of each spectral coefficient */
    int32_t *spec_gain;     /* [bands] its inverse gain, Q16                      */
    int32_t *tmp;           /* [bands] lifting scratch                           */
} bw_plan_t;

/* The prequantiser of a mode: 2E + 1 for MAX_ERROR, else 1. */
static inline uint32_t bw_prequant(unsigned mode, uint32_t max_error)
{
    return mode == BW_MODE_MAX_ERROR ? 2u * max_error + 1u : 1u;
}

/* The spectral decomposition depth of a basis: none for prediction. */
static inline unsigned bw_plan_spec_levels(unsigned basis, uint32_t bands)
{
    return basis == BW_BASIS_PRED ? 0u : bw_spec_levels(bands);
}

/* The one plan constructor (encoder, decoder, streaming encoder). mode and
 * param: MAX_ERROR and E, STEP or BYTES and the step (Q24.8), LOSSLESS and
 * anything; vec_thresh_q8 0 for the default; tables holds 2 * bands int32
 * for the spectral tables (spec_cls, spec_gain), tmp bands int32 of lifting
 * scratch (it may be tables: the scratch is used only while transforming,
 * the tables only while quantising and coding). */
void bw_plan_make(bw_plan_t *pl, const bw_dims_t *dims, unsigned basis, unsigned mode,
                  uint32_t param, unsigned flags, uint32_t vec_thresh_q8, int32_t *tables,
                  int32_t *tmp);
/* Fills the spectral tables (the class and the gain of each band). */
void bw_plan_tables(const bw_plan_t *pl);

static inline uint32_t bw_tri_count(unsigned level) { return 4u << (2u * level); }
static inline bool bw_has_out(const bw_dims_t *d) { return d->shape != BW_SHAPE_SPECTRA; }
static inline bool bw_has_in(const bw_dims_t *d) { return d->shape == BW_SHAPE_BRDF_FULL; }

/* Coarse-to-fine incoming index -> in-place position. */
static inline uint32_t bw_in_pos(const bw_plan_t *pl, uint32_t i)
{
    return bw_has_in(&pl->dims) ? bw_biohaar_pos(i, pl->dims.level_in) : i;
}
/* Its inverse gain, Q16. */
static inline uint32_t bw_in_gain_q16(const bw_plan_t *pl, uint32_t i)
{
    return bw_has_in(&pl->dims)
               ? bw_biohaar_inv_gain_q16(pl->dims.level_in, bw_biohaar_coef_level(i))
               : 65536u;
}
/* Context class of an outgoing coefficient from its parent level j (-1 for
 * a scaling coefficient): 0 finest details, 1 next, 2 coarser. */
static inline unsigned bw_level_cls(const bw_plan_t *pl, int j)
{
    if (!bw_has_out(&pl->dims))
        return 2u;
    int fine = (int)pl->dims.level_out - 1;
    return j == fine ? 0u : (j == fine - 1 ? 1u : 2u);
}

/* spec_cls[k] packs the context class of spectral coefficient k (bits 0-1)
 * and 1 + the index of its spectral parent (above; 0: none). */
#define BW_SPEC_CLS(v) ((unsigned)(v) & 3u)
#define BW_SPEC_PAR(v) ((int32_t)((uint32_t)(v) >> 2) - 1)

/* The coder's context class of a coefficient (BW_CODER_CLASSES): its
 * spectral class (sc = spec_cls[k]) and its vector's direction class. */
static inline unsigned bw_coef_cls(int32_t sc, unsigned cls_dir)
{
    return BW_SPEC_CLS(sc) * 3u + cls_dir;
}

/* The parent of band k of vector v (sc = spec_cls[k]): band k of the parent
 * vector pv (coarse-to-fine order), else the spectral parent in v; NULL for
 * none. */
static inline const int32_t *bw_parent_of(const int32_t *pv, const int32_t *v, int32_t sc,
                                          uint32_t k)
{
    int32_t sp = BW_SPEC_PAR(sc);
    return pv ? pv + k : sp >= 0 ? v + sp : NULL;
}

/* ---- parameters (bw_params.c) -------------------------------------------- */

/* Who asks bw_params_check: the rules are the format's; the encoders offer
 * less (bw_encode: BW_BASIS_AUTO, and prediction only with
 * BW_CFG_ENCODE_PRED; the streaming encoder: no full BRDF, no BYTES, no
 * prediction, no symmetry flags). */
enum { BW_FOR_ENCODE, BW_FOR_STREAM, BW_FOR_PAYLOAD };

/* Whether shape, mode, basis, flags and the mode's parameter (MAX_ERROR: E;
 * STEP: the step, Q24.8) go together: BW_OK, else the status the encoders
 * return (the header parser turns any into BW_ERR_HEADER). */
bw_status_t bw_params_check(const bw_dims_t *d, unsigned mode, unsigned basis, unsigned flags,
                            uint32_t param, unsigned use);

/* Where prediction applies: sets of spectra, LOSSLESS or MAX_ERROR, not in
 * stream order. */
bool bw_pred_applies(const bw_dims_t *d, unsigned mode, unsigned flags);

/* ---- loads (bw_load.c) ----------------------------------------------------
 * Both check every sample against +-BW_SAMPLE_MAX and return BW_ERR_RANGE,
 * after loading all, when one lies outside. */

/* n samples into out, each prequantised: floor((x + E) / q) for q = 2E + 1
 * (1: none). */
bw_status_t bw_load_samples(int32_t *out, const int32_t *in, size_t n, uint32_t prequant);
/* The encoder's load of a plan into out; without a symmetry step
 * (BW_CFG_FAST_LOADS) for the Haar basis the first one or two spectral
 * levels in the same pass, for the 5/3 and 9/7 bases the first
 * (BW_CFG_FAST_SPECTRAL too), their number in *done. */
bw_status_t bw_load(const bw_plan_t *pl, int32_t *out, const int32_t *in, unsigned *done);
/* The streaming encoder's load of one spectrum of the plan's bands into out,
 * and for the 5/3 and 9/7 bases its first spectral level as bw_load does
 * (*done). */
bw_status_t bw_load_spectrum(const bw_plan_t *pl, int32_t *out, const int32_t *in,
                             unsigned *done);

/* ---- transforms (bw_transform.c), symmetry (bw_symmetry.c), prediction
 * (bw_predict.c) ------------------------------------------------------------ */

/* done: the first spectral levels already applied (bw_load). */
void bw_transform_fwd(const bw_plan_t *pl, int32_t *x, unsigned done);
void bw_transform_inv(const bw_plan_t *pl, int32_t *x);
/* The direction index of the mirror image (x, -y, z) of direction o of a
 * level (docs/FORMAT.md, Transform). */
uint32_t bw_mirror_index(uint32_t o, unsigned level);
/* The mirror and reciprocity steps of the plan's flags; forward, BW_ERR_RANGE
 * if a difference leaves +-BW_SAMPLE_MAX. */
bw_status_t bw_symmetry(const bw_plan_t *pl, int32_t *x, bool forward);
/* Prediction instead of the prequantiser and the transforms, in place:
 * forward, range-checked samples -> coded errors (rows: 2 * bands int32 for
 * the decoded spectra); back, coded errors -> decoded samples (rows unused). */
void bw_predict(const bw_plan_t *pl, int32_t *x, int32_t *rows, bool forward);

/* ---- quantiser (bw_quant.c) ---------------------------------------------- */

/* The spectral subbands of a vector, Mallat order: subband 0 the
 * approximation, then the details from coarse to fine; band i holds the
 * elements [lo[i], lo[i + 1]), its synthesis gain's inverse gain_q16[i]. */
typedef struct {
    unsigned count;
    uint32_t lo[BW_SPEC_MAX_LEVELS + 2u];
    uq16_t gain_q16[BW_SPEC_MAX_LEVELS + 1u];
} spec_bands_t;
void bw_spec_bands(const bw_plan_t *pl, spec_bands_t *sb);

/* Every coefficient of the plan, forward (thresholds, then the dead-zone
 * quantiser with the plan's rounding offsets) or back. */
void bw_quantise(const bw_plan_t *pl, int32_t *x, bool forward);
/* The block of coarse-to-fine incoming index i back (the inverse
 * quantiser of its coefficients alone). */
void bw_dequant_block(const bw_plan_t *pl, int32_t *x, uint32_t i);
/* One outgoing vector of parent level j (-1: scaling) forward, as
 * bw_quantise does where there is no incoming transform (the streaming
 * encoder's shapes; no rounding offsets). */
void bw_quant_vector(const bw_plan_t *pl, int32_t *v, int j);
/* The histogram of the coefficients' magnitudes against their steps, for a
 * byte budget's estimate: hist[0] counts the zeros; a coefficient c whose
 * step is st at a base step of 1 (Q8 256) counts in bin
 * 4 log2(256 |c| / st) + BW_HIST_ZERO_BIN - 32 (quarter octaves, rounded
 * down; the last bin takes everything above), so that the base step
 * 2^(t / 4) codes it as non-zero about from bin BW_HIST_ZERO_BIN + t on. */
#define BW_HIST_BINS 128u
#define BW_HIST_ZERO_BIN 16u
void bw_quant_hist(const bw_plan_t *pl, const int32_t *x, uint32_t *hist);
/* s 2^(t / 32) for t >= 0, floor(s 2^e m / 2^15) for t = 32 e + f,
 * m = round(2^15 2^(f / 32)), f = 0..31 (the steps of a byte budget's
 * search, the chunks' steps), when s 2^e < 2^47. */
static inline uint64_t bw_oct32(uint32_t s, unsigned t)
{
    static const uint16_t frac_q15[32] = {
        32768, 33486, 34219, 34968, 35734, 36516, 37316, 38133, 38968, 39821, 40693,
        41584, 42495, 43425, 44376, 45348, 46341, 47356, 48393, 49452, 50535, 51642,
        52773, 53928, 55109, 56316, 57549, 58809, 60097, 61413, 62757, 64132,
    };
    return ((uint64_t)s << (t / 32u)) * frac_q15[t % 32u] >> 15;
}
#if BW_CFG_CHUNK_STEPS
/* The record BW_EXT_CHUNK_STEPS of payload p (its header h read): K, the
 * vectors per chunk, and *steps its chunks' step changes; 0 without it. */
uint32_t bw_chunk_steps(const uint8_t *p, const bw_header_t *h, const int8_t **steps);
#endif
/* The step of a chunk whose step change is d, -128..127
 * (BW_EXT_CHUNK_STEPS): step_q8 2^(d / 32) as bw_oct32 (floor(step_q8 2^e
 * m / 2^15), e = floor(d / 32) < 0 included) within BW_STEP_ONE_Q8 + 1 ..
 * 2^32 - 1 (docs/FORMAT.md, Chunk steps). */
uint32_t bw_chunk_step(uint32_t step_q8, int d);

/* log2(v) in Q16, v >= 1: the leading bit's place, and log2(1 + f) for the
 * fraction f below it from 17 points (Q16) interpolated, within 2^-10 */
static inline uint32_t bw_log2_q16(uint32_t v)
{
    static const uint16_t t[17] = {0,     5732,  11136, 16248, 21098, 25711, 30109, 34312, 38336,
                                   42196, 45904, 49472, 52911, 56229, 59434, 62534, 65535};
    unsigned e = bw_bitlen(v) - 1u;
    uint32_t m = v << (31u - e); /* 1.f in Q31 */
    uint32_t i = (m >> 27) & 15u, f = (m >> 11) & 0xFFFFu;
    return (e << 16) + t[i] + (((t[i + 1u] - t[i]) * f) >> 16);
}

/* ---- coding order (bw_order.c) ------------------------------------------- */

/* The outgoing coefficients in coarse-to-fine order (the order of
 * bw_biohaar_pos) without a division per step: the next one is child m of
 * parent p at level j (j = -1: the scaling coefficient of base p). */
typedef struct {
    int j;
    uint32_t p, m;
} bw_walk_t;

void bw_walk_init(bw_walk_t *w);
/* The in-place position of the current coefficient of a level-L hemisphere
 * and its parent level (-1: scaling); steps to the next. */
uint32_t bw_walk_next(bw_walk_t *w, unsigned L, int *level);

/* A byte budget met in one encode (BW_EFFORT_FAST; bw_budget.c, rate):
 * the quantiser runs ahead of the coder a chunk at a time, each chunk at
 * its own step (BW_EXT_CHUNK_STEPS). */
#define BW_RATE (BW_CFG_FAST_BUDGET && BW_CFG_CHUNK_STEPS)
#if BW_RATE
/* The outgoing vectors in coding order, one incoming block after another,
 * for a quantiser that runs ahead of the coder (bw_quant_ahead). */
typedef struct {
    uint32_t i, o; /* the next vector: the o-th of incoming block i (coarse to fine) */
    bw_walk_t w;
    bool dropped; /* block i fell below the vector threshold */
} bw_qwalk_t;
void bw_qwalk_init(bw_qwalk_t *qw);
/* Quantises the next nvec vectors of the walk forward at the plan's step
 * as it is at the call, as bw_quantise does (its thresholds; no rounding
 * offset). */
void bw_quant_ahead(const bw_plan_t *pl, bw_qwalk_t *qw, int32_t *x, uint32_t nvec);
/* An estimate of the bits of every chunk of chunk_vec vectors in coding
 * order at the base step 2^(t4 / 4), in est[] (whole bits): a coefficient
 * c of step st whose x = 4 log2(|c| / st) - t4 (quarter octaves, as
 * bw_quant_hist's bins) is 0 or more costs a0_q6 / 64 + x a1_q6 / 64 bits;
 * the others nothing. */
void bw_quant_est(const bw_plan_t *pl, const int32_t *x, uint32_t chunk_vec, int t4,
                  uint32_t a0_q6, uint32_t a1_q6, uint32_t *est);

/* The rate: the coder asks for the vectors it is about to code
 * (bw_strip_coder.c, rate_need), and the rate quantises them a chunk at a
 * time, each chunk's step from the bits coded so far against the estimate. */
#define BW_RATE_CHUNKS 64u
struct bw_rate {
    bw_plan_t *pl;
    int32_t *x;
    bw_qwalk_t qw;
    uint32_t step_q8;   /* the header's step */
    uint32_t ahead;     /* vectors quantised and not yet coded */
    uint32_t chunk;     /* the next chunk */
    uint32_t chunks;
    int32_t gamma_q8;   /* octaves of bits per octave of step (the estimate's), Q8 */
    uint64_t aim;       /* body bits aimed at */
    uint64_t est_left;  /* estimated bits of the chunks not yet quantised, at the step */
    uint64_t est_done;  /* of those quantised, at their steps */
    uint64_t bits_seen, est_seen; /* bits and est_done at the chunk before */
    uint64_t b_sum, e_sum;        /* their bits and estimates, the estimate's own first */
    uint32_t est[BW_RATE_CHUNKS];
    int8_t d[BW_RATE_CHUNKS]; /* each chunk's step change (the record's) */
};
/* Quantises the next chunks (at least v vectors) after the bits coded so far. */
void bw_rate_chunk(struct bw_rate *r, uint64_t bits, uint32_t v);
#endif

/* The outgoing vectors a streaming encoder completes with one leaf: at most
 * 3 details per level and a scaling vector. */
#define BW_STREAM_QUEUE (3u * BW_MAX_LEVEL + 1u)

typedef struct {
    uint32_t pos[BW_STREAM_QUEUE];
    int8_t level[BW_STREAM_QUEUE];
    unsigned n;
} bw_stream_queue_t;

/* Walks the coefficients in coding order: incoming (coarse to fine), then
 * outgoing, then spectral (Mallat order as stored). The outgoing order is
 * coarse to fine, or with the plan's `stream` the order in which a
 * streaming encoder completes them (post-order, docs/FORMAT.md). */
typedef struct {
    const bw_plan_t *pl;
    int32_t *x;
    uint32_t i, o, k; /* incoming, outgoing vector (in coding order), band */
    int32_t *vec;
    size_t base;         /* the incoming block's first vector in place ...  */
    uint32_t base_i;     /* ... of block base_i (BW_CFG_SPEED, BW_CFG_EMBED) */
    const int32_t *par;  /* coarse-to-fine order: the parent vector, or NULL */
    const int32_t *prev; /* the previous vector (coarse-to-fine, bands > 1), or NULL */
    unsigned cls_dir;
    int lvl;          /* the outgoing coefficient's parent level (-1: scaling; BW_CFG_EMBED) */
    size_t vi, seg0; /* the vector's index in coding order; its segment's first */
    uint32_t leaf; /* stream order: next leaf, queue of completed vectors */
    unsigned qi;
    bw_stream_queue_t q;
    bw_walk_t w; /* coarse-to-fine order */
} bw_iter_t;

void bw_iter_init(bw_iter_t *it, const bw_plan_t *pl, int32_t *x);
/* Moves to the next vector in coding order. */
void bw_iter_next_vec(bw_iter_t *it);
/* The iterator at vector vi of the coding order (from its block's first). */
void bw_iter_at(bw_iter_t *it, const bw_plan_t *pl, int32_t *x, size_t vi);
/* The iterator at vector vi of its segment (coarse-to-fine order), at once. */
void bw_iter_seek(bw_iter_t *it, size_t vi);
/* The coarse-to-fine index of the coefficient at in-place position t of a
 * level-L hemisphere (bw_biohaar_pos's inverse). */
uint32_t bw_cf_index(uint32_t t, unsigned L);
/* A segment begins at the current vector: from here on no context comes
 * from a vector before it (no previous vector for this one, no parent coded
 * before it). */
void bw_iter_segment(bw_iter_t *it);

/* ---- segments ------------------------------------------------------------ */

/* The number of segments of a plan: ceil(vectors / seg_vec), 1 without. */
static inline uint32_t bw_plan_segments(const bw_plan_t *pl)
{
    uint32_t nv = pl->dims.n_in * pl->dims.n_out;
    return pl->seg_vec ? (nv - 1u) / pl->seg_vec + 1u : 1u;
}
/* The segment table at the body's start: per segment its length and its
 * CRC-32 (4 bytes each, little-endian), then the CRC-32 of the payload
 * from its first byte to there. */
#define BW_SEG_ENTRY 8u
static inline size_t bw_segment_table_size(uint32_t segs) { return BW_SEGMENT_TABLE_SIZE(segs); }

/* Embedded segments (bw_embed.c): the n coefficients from iterator start
 * coded bit plane by bit plane into out[cap] (NULL: counted), the coder's
 * state in the work area after the plan's tables (BW_WORK_BOUND); with
 * truncate the coding stops before it passes cap (a byte budget), else
 * *over says it did not fit; its models in m's storage. Returns the
 * bytes. */
size_t bw_embed_encode(const bw_iter_t *start, size_t n, uint8_t *out, size_t cap, bool truncate,
                       bw_models_t *m, bool *over);
/* Decodes one into the n coefficients from start: a whole segment (in[len])
 * to where its encoder stopped, a cut one (cut) to where its bytes end.
 * *inexact: the coefficients are not all the encoder's. BW_ERR_CORRUPT for
 * a malformed start. Its models in m's storage. */
bw_status_t bw_embed_decode(const bw_iter_t *start, size_t n, const uint8_t *in, size_t len,
                            bool cut, bw_models_t *m, bool *inexact);

/* The next coefficient, its class and where its contexts come from: the
 * parent (directional, else spectral) and the same band of the previous
 * vector (NULL: none). */
static inline int32_t *bw_iter_next(bw_iter_t *it, uint8_t *cls, const int32_t **par,
                                    const int32_t **prv)
{
    uint32_t k = it->k;
    int32_t *p = it->vec + k, sc = it->pl->spec_cls[k];
    *par = bw_parent_of(it->par, it->vec, sc, k);
    *prv = it->prev ? it->prev + k : NULL;
    *cls = (uint8_t)bw_coef_cls(sc, it->cls_dir);
    if (++it->k == it->pl->dims.bands)
        bw_iter_next_vec(it);
    return p;
}

/* ---- header (bw_header.c) ------------------------------------------------- */

/* Writes the header of the plan at out (NULL: only counts); returns its
 * length (at most BW_HEADER_MAX). */
size_t bw_header_write(uint8_t *out, const bw_plan_t *pl, const bw_params_t *pa, unsigned mode);

/* ---- band access (bw_bands.c) -------------------------------------------- */

/* A set of spectra with band access (BW_EXT_BANDS) from the plan pl (dims,
 * basis BW_BASIS_PRED, pl->bands) of LOSSLESS or MAX_ERROR: work holds
 * bw_work_bound(n, bands). */
bw_status_t bw_bands_encode(const bw_plan_t *pl, const bw_params_t *pa, const int32_t *x,
                            int32_t *work, uint8_t *out, size_t out_cap, size_t *out_len);
/* The whole of such a payload (its header read) into x[n]: the tables'
 * CRC and every group's checked. */
bw_status_t bw_bands_decode(const bw_header_t *h, const uint8_t *p, int32_t *x);

/* Extension records well formed, of known critical types only, without a
 * tail (an encoder codes none), at most BW_EXT_MAX bytes. */
bool bw_ext_valid(const uint8_t *area, size_t len);

/* ---- encoder (bw_encode.c) and its byte-budget search (bw_budget.c) ------- */

/* One encode at the plan's settings: load, transform, quantise, code; the
 * header records `mode`. out NULL: only counts (*len the payload size). */
bw_status_t bw_encode_pass(bw_plan_t *pl, const bw_params_t *pa, unsigned mode,
                           const int32_t *samples, int32_t *work, bw_ctx_t *ctx, uint8_t *out,
                           size_t cap, size_t *len);
/* Its two halves: the coefficients in work (load, symmetry, transform or
 * prediction) and the plan's tables; then code the coefficients (quantised
 * by the caller) with the header and the CRC, *len the size even when it
 * does not fit cap (BW_ERR_OUTPUT_FULL). */
bw_status_t bw_encode_prepare(bw_plan_t *pl, const int32_t *samples, int32_t *work);
/* BW_CODER_AUTO's coder where it takes no Rice strips (bw_encode_code):
 * the multi-symbol one, or the binary one in a core built without it. */
#define BW_AUTO_CODER (BW_CFG_CODER_MS ? BW_FLAG_MS : 0u)
/* A coder choice the encoders take: BY_FLAGS, or AUTO with no coder flag. */
static inline bool bw_coder_choice_ok(const bw_params_t *pa)
{
    return pa->coder == BW_CODER_BY_FLAGS ||
           (pa->coder == BW_CODER_AUTO && !(pa->flags & (BW_FLAG_RICE | BW_FLAG_MS)));
}
bw_status_t bw_encode_code(const bw_plan_t *pl, const bw_params_t *pa, unsigned mode,
                           int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap, size_t *len);
/* BYTES: the payload of at most min(byte_budget, cap) bytes with the finest
 * quantiser the plan's basis reaches; BW_ERR_BUDGET if none fits. */
bw_status_t bw_budget_encode(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                             int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap,
                             size_t *len);
/* The same with BW_EFFORT_FAST: one encode that steers the step of each
 * chunk of vectors as it codes (BW_EXT_CHUNK_STEPS) where the body allows
 * it; else, or where that one misses, the step estimated from the
 * coefficients, corrected by the size of each encode, until one lands
 * within 1 % under the budget (else the search above, from the steps those
 * encodes tried). */
bw_status_t bw_budget_encode_fast(bw_plan_t *pl, const bw_params_t *pa, const int32_t *samples,
                                  int32_t *work, bw_ctx_t *ctx, uint8_t *out, size_t cap,
                                  size_t *len);

#endif
