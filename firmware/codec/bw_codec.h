/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * brdfwave codec core: public interface.
 *
 * Freestanding C11. The core uses only <stdint.h>, <stddef.h>, <stdbool.h> and
 * <string.h>; it never allocates. Every buffer belongs to the caller and has a
 * compile-time worst-case size given by a BW_..._BOUND() macro (and a function
 * of the same name for run-time use).
 *
 * Data model
 * ----------
 * A measurement is an array of integer samples laid out row-major as
 * [incoming][outgoing][band]:
 *
 *   shape            n_in                 n_out          transforms
 *   SPECTRA          number of spectra    1              spectral
 *   REFLECTANCE      1                    4*4^level_out  Bio-Haar(out), spectral
 *   BRDF_ISO         any N (incoming)     4*4^level_out  Bio-Haar(out), spectral
 *   BRDF_FULL        4*4^level_in         4*4^level_out  Bio-Haar(in), Bio-Haar(out),
 *                                                        spectral
 *
 * Directions are in the codec's geodesic triangle order (bw_geodesic.h).
 * Monochromatic data is bands = 1 (the spectral transform is then the
 * identity).
 *
 * Modules (firmware/codec/), one job each
 * ---------------------------------------
 *   bw_codec.h         this interface; bw_internal.h, what the modules share
 *   bw_config.h        build switches: encoder features and code forms
 *   bw_dims.c          dimensions and the worst-case sizes (the BOUNDs)
 *   bw_params.c        which shapes, modes, bases and flags go together
 *   bw_plan.c          the plan of one encode or decode, its spectral tables
 *   bw_load.c          samples in: range check, prequantiser, fused Haar levels
 *   bw_symmetry.c      the mirror and reciprocity steps
 *   bw_transform.c     the transform driver over the two kernels below
 *   bw_spectral.c      integer lifting on the spectral axis (Haar, 5/3, 9/7)
 *   bw_biohaar.c       Bio-Haar lifting on the geodesic hemisphere
 *   bw_geodesic_*.c    its weight and area tables (generated)
 *   bw_predict.c       prediction, in place of the prequantiser and transforms
 *   bw_quant.c         thresholds and the dead-zone quantiser, with formats
 *   bw_order.c         the coding order of the coefficients
 *   bw_strip_coder.c   strips of 32, encoder and decoder side by side
 *                      (bw_strip_coder.h; the state's types in bw_coder.h)
 *   bw_rc.c            the adaptive binary range coder
 *   bw_rice.c          the Rice strip coder (BW_FLAG_RICE)
 *   bw_tab.c           the static-table coder (BW_FLAG_RICE | BW_FLAG_MS)
 *   bw_embed.c         embedded segments, bit plane by bit plane
 *                      (BW_EXT_EMBEDDED, bw_params_t.progressive)
 *   bw_bands.c         band access: spectra predicted along the bands and
 *                      coded by columns (BW_EXT_BANDS, bw_decode_band_range)
 *   bw_header.c        the payload's header and its CRC
 *   bw_encode.c        bw_encode: one pass, the choice of basis, self-check
 *   bw_budget.c        the byte budget's searches (BW_MODE_BYTES)
 *   bw_decode.c        bw_decode, bw_decode_salvage (segments), the partial
 *                      decodes (bw_decode_incoming, bw_decode_rows,
 *                      bw_decode_level)
 *   bw_salvage.c       what a decode in part rebuilt (bw_salvage_mask)
 *   bw_stream.c        the streaming encoder (bw_stream_*)
 *   bw_crc32.c         CRC-32
 *   bw_error.c         status messages
 *   bw_strip.c         the paper's sparse strip arrays (not used by the codec)
 */
#ifndef BW_CODEC_H
#define BW_CODEC_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "bw_coder.h"
#include "bw_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- limits ------------------------------------------------------------ */

#define BW_MAX_LEVEL 6u            /* geodesic levels 0..6: 4..16384 triangles */
#define BW_MAX_BANDS 65535u        /* bands per spectrum (u16 in the header)    */
#define BW_MAX_SAMPLES (1u << 28)  /* n_in * n_out * bands                      */
#define BW_MAX_N_IN (1u << 24)
/* Samples are signed integers with |x| <= BW_SAMPLE_MAX; transform
 * coefficients then stay well inside int32 (bw_spectral.c, bw_biohaar.c). */
#define BW_SAMPLE_MAX ((1 << 24) - 1)
#define BW_STRIP 32u               /* elements per strip (paper: B_s = 32)      */

/* ---- shapes, bases, modes --------------------------------------------- */

typedef enum {
    BW_SHAPE_SPECTRA = 0,
    BW_SHAPE_REFLECTANCE = 1,
    BW_SHAPE_BRDF_ISO = 2,
    BW_SHAPE_BRDF_FULL = 3
} bw_shape_t;

typedef enum {
    BW_BASIS_HAAR = 0, /* S-transform                         */
    BW_BASIS_53 = 1,   /* LeGall 5/3, reversible               */
    BW_BASIS_97 = 2,   /* integer-lifted CDF 9/7               */
    BW_BASIS_COUNT = 3, /* the transform bases above                 */
    /* Prediction instead of a transform (SPECTRA, LOSSLESS and MAX_ERROR
     * only): each sample is predicted from the decoded samples before it
     * in its spectrum and in the previous one, and the prediction error
     * quantised in the loop. Every decoder decodes it; an encoder built
     * without BW_CFG_ENCODE_PRED (bw_config.h) does not offer it. */
    BW_BASIS_PRED = 3,
    /* Encoder option: choose the basis (bw_effort_t says how) */
    BW_BASIS_AUTO = 255
} bw_basis_t;

typedef enum {
    BW_MODE_LOSSLESS = 0,  /* integer samples decode bit-exactly              */
    BW_MODE_MAX_ERROR = 1, /* every sample within max_error of the input      */
    BW_MODE_BYTES = 2,     /* payload <= byte_budget, best quality that fits  */
    BW_MODE_STEP = 3       /* fixed quantiser step (used by BYTES's search)   */
} bw_mode_t;

typedef struct {
    uint8_t shape;     /* bw_shape_t                                  */
    uint8_t level_out; /* outgoing geodesic level (0..6), 0 for SPECTRA */
    uint8_t level_in;  /* incoming level, BRDF_FULL only               */
    uint32_t n_in;     /* see table above                              */
    uint32_t n_out;
    uint32_t bands;
} bw_dims_t;

/* How much an encode may spend on its choices (bw_params_t.effort). */
typedef enum {
    /* BW_BASIS_AUTO codes the measurement with every basis and keeps the
     * smallest payload; a byte budget searches the finest step that fits,
     * coding the measurement once per try */
    BW_EFFORT_BEST = 0,
    /* for a device, where every try costs an encode: BW_BASIS_AUTO takes
     * parts of the measurement (an eighth of it), ranks the transform bases
     * by the bits of an order-0 coding of their coefficients there, subband
     * by subband (no coding), codes the parts with the first of them and
     * with prediction where that applies, then the whole once with the
     * basis that coded them smallest (for a byte budget, the exact
     * coefficients of half as much ranked); a byte
     * budget is met in one encode that steers a step per chunk of vectors
     * as it codes (BW_EXT_CHUNK_STEPS) where the body allows it; else, or
     * where that one does not land within 1 % under the budget, the step is
     * estimated from the coefficients and corrected by the size of each
     * encode until one lands (one to four encodes; then the search from the
     * steps they tried, to the first payload within 1 % under) */
    BW_EFFORT_FAST = 1
} bw_effort_t;

/* Which entropy coder codes the body (bw_params_t.coder). */
typedef enum {
    /* the one the flags name: BW_FLAG_RICE, BW_FLAG_MS, both (the static
     * tables), or neither (the binary range coder, the smallest payloads) */
    BW_CODER_BY_FLAGS = 0,
    /* the encoder chooses, for a device that must keep up with its sensor
     * (the flags then name no coder): Rice strips for prediction errors
     * whose bit lengths average at least 7/8 and whose Rice payload stays
     * within 248/256 of an order-0 coding of them (errors close to
     * geometric: there Rice strips come within about 2 % of the range
     * coder's bytes in a fraction of its instructions; the statistics from
     * every fourth error of a large measurement); for a set of spectra
     * transformed, coded in one body without a byte budget's rate ahead of
     * the coder, the static tables (BW_CFG_CODER_TAB); else the
     * multi-symbol range coder (the binary one in a core built without it,
     * BW_CFG_CODER_MS 0); the payload's flags name the coder chosen */
    BW_CODER_AUTO = 1
} bw_coder_choice_t;

typedef struct {
    uint8_t mode;          /* bw_mode_t                                     */
    uint8_t basis;         /* bw_basis_t, or BW_BASIS_AUTO                  */
    uint8_t effort;        /* bw_effort_t; 0 (BEST) in a zeroed struct     */
    uint8_t coder;         /* bw_coder_choice_t; 0 (BY_FLAGS) when zeroed   */
    uint32_t max_error;    /* MAX_ERROR: bound in sample units              */
    uint32_t byte_budget;  /* BYTES: upper bound on the payload size        */
    uint32_t step_q8;      /* STEP: quantiser step, Q24.8                   */
    uint32_t vec_thresh_q8; /* vector threshold in steps, Q8 (0: default 1.0) */
    /* Opaque to the core: copied into the header for the host's benefit
     * (IEEE-754 binary32 bit patterns of the sample scale and offset, so that
     * float value = offset + scale * integer sample). */
    uint32_t scale_bits;
    uint32_t offset_bits;
    uint8_t flags;         /* BW_FLAG_*, recorded for the host            */
    /* Extension records written after the header (docs/FORMAT.md,
     * Extensions): ext_len bytes of records, each type, varint length, data,
     * made by the caller (the host's metadata, a device's fixed block) and
     * checked by the encoder (BW_ERR_ARG if malformed). None when ext_len is
     * 0. A payload with records is version 7; one without stays version 6,
     * which every decoder since that version reads. The payload grows by
     * ext_len + BW_EXT_OVERHEAD at most: add that to BW_PAYLOAD_BOUND. */
    const uint8_t *ext;
    uint32_t ext_len;
    /* Segments (docs/FORMAT.md, Segments): 0 codes one body; n > 0 splits
     * the body into independently decodable segments of n vectors each (a
     * vector: the bands of one incoming x outgoing coefficient, in coding
     * order; the last segment may hold fewer), each with its length and
     * CRC-32, so that a damaged or missing segment costs its own
     * coefficients only (bw_decode_salvage). A payload with segments is
     * version 7 and BW_SEGMENT_OVERHEAD(s) bytes larger at most: add that
     * to BW_PAYLOAD_BOUND. Not for the streaming encoder. */
    uint32_t segment_vectors;
    /* Embedded segments (docs/FORMAT.md, Embedded segments): nonzero codes
     * each segment bit plane by bit plane (a body in one piece becomes one
     * segment), so that any prefix of a segment decodes to an approximation
     * of all its coefficients; with BW_MODE_BYTES the payload is then the
     * exact coding cut at the budget (no search). Transform bases only, not
     * in stream order. */
    uint32_t progressive;
    /* Band access (docs/FORMAT.md, Band access): nonzero codes a set of
     * spectra (LOSSLESS or MAX_ERROR, basis BW_BASIS_PRED or AUTO, no
     * segments, the flags naming no coder) so that any band or range of
     * bands decodes from the few columns of errors it depends on
     * (bw_decode_band_range), at a cost that follows the bands asked for.
     * A payload with it is version 7 and BW_BANDS_OVERHEAD bytes larger at
     * most (its codes' tables): add that to BW_PAYLOAD_BOUND. */
    uint32_t band_access;
} bw_params_t;

/* Header flags.
 * DECIMAL_SCALE (opaque to the core): the scale is exactly 10^-k; the host
 *   divides by 10^k instead of multiplying by the float.
 * STREAM_ORDER: outgoing coefficients are coded in the order a streaming
 *   encoder completes them (bw_stream_*), not coarse to fine; any encoder
 *   may choose it, and a streaming encoder's payload is byte-identical to
 *   bw_encode's with this flag. Not for BRDF_FULL.
 * RICE: the body is coded with the adaptive Rice strip coder (bw_rice.h)
 *   instead of the range coder: a few times fewer instructions per sample
 *   on a small core, a few percent more bytes. */
#define BW_FLAG_DECIMAL_SCALE 0x01u
#define BW_FLAG_STREAM_ORDER 0x02u
#define BW_FLAG_RICE 0x04u
/* LOG_VALUE (opaque to the core): samples code the logarithm of positive
 *   values, value = exp(offset + scale * sample); a uniform error in the
 *   samples is then a uniform relative error in the values. */
#define BW_FLAG_LOG_VALUE 0x08u
/* MIRROR: before the transform, every sample of the half y < 0 of the
 *   outgoing hemisphere (base triangles 2 and 3) becomes its difference from
 *   the sample at the mirror direction (x, -y, z) (for a full BRDF, with the
 *   incoming direction mirrored too). An isotropic BRDF whose incidence
 *   plane is the x-z plane, and an anisotropic one whose axes are x and y,
 *   is symmetric so: that half then codes almost nothing. Not for SPECTRA
 *   and not offered by the streaming encoder (the partner of a direction
 *   may arrive after it); the differences must stay within +-BW_SAMPLE_MAX
 *   (after the max-error prequantiser), else BW_ERR_RANGE. */
#define BW_FLAG_MIRROR 0x10u
/* Reciprocity, f(wi, wo) = f(wo, wi): for a full BRDF whose incoming and
 *   outgoing grids are the same level, each sample whose reciprocal partner
 *   (the sample with the two directions swapped, or that sample's mirror
 *   image in the half MIRROR codes as differences) comes first in
 *   [incoming][outgoing] order is coded as the difference from it: a
 *   reciprocal BRDF then codes about half its samples. Only for
 *   BW_SHAPE_BRDF_FULL with level_in == level_out; the differences must stay
 *   within +-BW_SAMPLE_MAX, else BW_ERR_RANGE. */
#define BW_FLAG_RECIPROCAL 0x20u
/* MS: the body is coded with the multi-symbol range coder: an element's
 *   bit length as one adaptive symbol in place of the valid bit and the
 *   5-bit tree (fewer instructions per sample). Version 7. RICE | MS: the
 *   body is coded with static tables sent ahead of it (BW_CFG_CODER_TAB,
 *   docs/FORMAT.md, Body with TAB: fewer instructions still on sets of
 *   spectra; not for the streaming encoder nor embedded segments). */
#define BW_FLAG_MS 0x80u
#define BW_FLAGS_KNOWN 0xBFu
/* EXT (set by the encoder when params.ext_len > 0, version 7): extension
 *   records follow the header's fields. */
#define BW_FLAG_EXT 0x40u

/* ---- sizes -------------------------------------------------------------- */

#define BW_HEADER_FIXED 7u /* magic, version, packed fields          */
#define BW_HEADER_MAX 27u  /* with the longest varints, scale, offset */
#define BW_TRAILER_SIZE 4u  /* CRC-32 */

/* Worst case payload size for n samples: 9 bytes per sample for the strip
 * coder (bw_strip_coder.c), plus the strip presence flags, the coder flush
 * and the header and trailer. An encode that needs more returns
 * BW_ERR_OUTPUT_FULL and writes nothing past out_cap. */
#define BW_PAYLOAD_BOUND(n) \
    ((size_t)BW_HEADER_MAX + BW_TRAILER_SIZE + 16u + (size_t)(n) * 9u + ((size_t)(n) / BW_STRIP + 1u))

/* Work area for the encoder and decoder, in int32 elements: the coefficient
 * array, one spectral line of scratch and the spectral tables, and a bit per
 * coefficient and per strip of 32 (the embedded coder's significance), in
 * n / 16 + 8 words. */
#define BW_WORK_BOUND(n, bands) \
    ((size_t)(n) + ((size_t)(n) >> 4) + 2u * (size_t)(bands) + 24u)

/* What band access (bw_params_t.band_access) may add to the bound: its
 * record and the code tables of up to 18 levels. */
#define BW_BANDS_OVERHEAD 640u

size_t bw_payload_bound(size_t n);
size_t bw_work_bound(size_t n, size_t bands);

/* ---- dims helpers ------------------------------------------------------- */

/* Fills dims for a shape; returns BW_OK or an error if the combination is
 * out of range. n_in is used for SPECTRA and BRDF_ISO only. */
bw_status_t bw_dims_make(bw_dims_t *dims, bw_shape_t shape, unsigned level_out, unsigned level_in,
                         uint32_t n_in, uint32_t bands);
bw_status_t bw_dims_check(const bw_dims_t *dims);
size_t bw_dims_samples(const bw_dims_t *dims);

/* ---- coder context ------------------------------------------------------ */

/*
 * The state of one encode or decode: the strip coder with the range coder's
 * adaptive models, sizeof(bw_ctx_t) bytes (BW_CTX_SIZE on a 32-bit core), a
 * size fixed at compile time. The caller owns it (a static, say) and lends
 * it to one call at a time; every call initialises what it uses, so it
 * needs no init of its own and holds nothing between calls.
 *
 * With it the encoder and the decoder keep their stack small: see
 * BW_CTX_STACK_MAX. bw_encode, bw_decode and bw_decode_unchecked are the
 * same calls with a bw_ctx_t on their stack: sizeof(bw_ctx_t) more, for
 * hosts.
 */
typedef struct {
    union {
        bw_strip_enc_t enc; /* bw_encode_ctx */
        bw_models_t models; /* bw_decode_ctx: the range decoder's models */
    };
    /* bw_encode_ctx's byte budget with BW_EFFORT_FAST: the coefficients'
     * histogram, then the state of its one encode (bw_budget.c) */
    uint64_t budget[64];
} bw_ctx_t;

/* The most stack, in bytes, that bw_encode_ctx (its deepest chain: the
 * byte-budget search, then the self-check's decode) or bw_decode_ctx takes
 * on the Cortex-M4 (-O2), interrupt frames not included; tests/target
 * measures every golden case on the emulated board against it. */
#define BW_CTX_STACK_MAX 2048u

/* ---- encoder ------------------------------------------------------------ */

/*
 * Encodes samples[n] (n = bw_dims_samples(dims)) into out[out_cap].
 * work must hold bw_work_bound(n, bands) int32 elements; samples are not
 * modified. verify (may be NULL) is a second work area of the same size: when
 * given, the encoder decodes its own payload and checks the mode's guarantee
 * (bit-exact, or every sample within max_error) before returning; in BYTES
 * mode with BW_BASIS_AUTO it also ranks the bases by decoded squared error
 * (without it, by quantiser step).
 * On success *out_len is the payload size.
 */
bw_status_t bw_encode_ctx(bw_ctx_t *ctx, const bw_dims_t *dims, const bw_params_t *params,
                          const int32_t *samples, int32_t *work, int32_t *verify, uint8_t *out,
                          size_t out_cap, size_t *out_len);
/* The same with the context on the stack. */
bw_status_t bw_encode(const bw_dims_t *dims, const bw_params_t *params, const int32_t *samples,
                      int32_t *work, int32_t *verify, uint8_t *out, size_t out_cap,
                      size_t *out_len);

/* ---- decoder ------------------------------------------------------------ */

typedef struct {
    uint8_t version;
    /* record BW_EXT_BANDS: 1, the body codes spectra for band access */
    uint8_t band_access;
    bw_dims_t dims;
    uint8_t basis;
    uint8_t spectral_levels;
    uint8_t mode;
    uint8_t flags;
    uint32_t prequant;   /* samples were divided by this before coding (>= 1) */
    uint32_t step_q8;    /* quantiser step of the coefficients, Q24.8          */
    uint32_t max_error;  /* the bound the encoder guaranteed (MAX_ERROR), else 0 */
    uint32_t scale_bits;
    uint32_t offset_bits;
    uint32_t payload_len; /* total bytes, header to CRC inclusive */
    uint32_t header_len;
    uint32_t body_len;
    uint32_t crc;
    /* the extension records (version 7): their offset in the payload and
     * their length, 0 and 0 when there are none (bw_ext_next walks them) */
    uint32_t ext_off;
    uint32_t ext_len;
    /* record BW_EXT_SEGMENTS: vectors per segment, and the segments'
     * count; 0 and 1 for a body in one piece */
    uint32_t segment_vectors;
    uint32_t segments;
    /* record BW_EXT_EMBEDDED: 0 none, else 1 + its form (1: the first,
     * without groups of strips; 2: with them; 3: with the incoming parent
     * block as a neighbour too; 4: and each pass split, significance
     * first; 5: in three parts, refinement second) */
    uint32_t embedded;
} bw_header_t;

/* ---- extension records ------------------------------------------------- */

/* A record's type says whether a decoder may skip it: types 0x80 and above
 * are ancillary (information a decoder need not understand); types below
 * 0x80 are critical (they change what the samples mean or how they decode),
 * and a decoder refuses a payload with a critical type it does not know
 * (BW_ERR_EXTENSION). A payload with BW_EXT_FLOAT_EXACT ends in a tail of
 * the host's between the body and the CRC: bw_header_t.body_len leaves it
 * out, and it is payload_len - 4 - header_len - body_len bytes long. */
#define BW_EXT_ANCILLARY 0x80u
/* Critical types every decoder knows. The core decodes the samples as usual
 * (for BW_EXT_FLOAT_EXACT without the tail it sets apart at the body's end);
 * the host maps them to values (host-tools/lib, docs/FORMAT.md): a reader
 * that turns samples into values itself must apply them. */
#define BW_EXT_FLOAT_EXACT 0x01u /* float32 values bit for bit: bit planes, exceptions;
                                  * its first field, a varint, is the tail's length */
#define BW_EXT_LOG_MAP 0x02u     /* samples to values through a signed log-linear map */
#define BW_EXT_SEGMENTS 0x03u    /* the body is split into segments (the core's) */
#define BW_EXT_EMBEDDED 0x04u    /* the segments are coded bit plane by bit plane */
#define BW_EXT_CHUNK_STEPS 0x05u /* a quantiser step per chunk of vectors (the core's) */
#define BW_EXT_BANDS 0x06u       /* spectra coded for band access (the core's) */
#define BW_EXT_METADATA 0x81u  /* the measurement's axes and context (host-tools) */
#define BW_EXT_GUARANTEE 0x82u /* the bound the encoder guarantees, in value units */
#define BW_EXT_MAX (1u << 20)  /* bytes of records at most */
#define BW_EXT_OVERHEAD 3u     /* the records' length field, as a varint */

/* Walks the records of area[len] (a header's ext_off / ext_len): the record
 * at *pos, its type, data and length; *pos moves to the next. false at the
 * end or on a malformed record. */
bool bw_ext_next(const uint8_t *area, size_t len, size_t *pos, uint8_t *type,
                 const uint8_t **data, uint32_t *data_len);

/* Parses and validates the header and the CRC of payload[len]. */
bw_status_t bw_header_read(const uint8_t *payload, size_t len, bw_header_t *hdr);

/* Parses and validates the header of payload[len] without the CRC check;
 * the body is what lies between the header and the last 4 bytes. */
bw_status_t bw_header_parse_fields(const uint8_t *payload, size_t len, bw_header_t *hdr);
/* The same for a payload that may be cut (bw_decode_salvage): a tail
 * (record 0x01) longer than what follows the header is cut to what is
 * there (the segment table, whose CRC vouches for the header, says where
 * the body ends). In a core built without BW_CFG_SALVAGE, the same as
 * bw_header_parse_fields. */
bw_status_t bw_header_parse_cut(const uint8_t *payload, size_t len, bw_header_t *hdr);

/* Decodes a payload into samples[n]; work holds bw_work_bound(n, bands) int32.
 * samples may be the same array as work. */
bw_status_t bw_decode_ctx(bw_ctx_t *ctx, const uint8_t *payload, size_t len, int32_t *samples,
                          size_t samples_cap, int32_t *work, size_t work_cap,
                          bw_header_t *hdr_out);
/* The same with the context on the stack. */
bw_status_t bw_decode(const uint8_t *payload, size_t len, int32_t *samples, size_t samples_cap,
                      int32_t *work, size_t work_cap, bw_header_t *hdr_out);

/* The most bytes segments add to a payload of s segments: the record, the
 * table (a length and a CRC-32 per segment, one CRC-32 for the header and
 * the table) and each segment's coder flush. */
#define BW_SEGMENT_OVERHEAD(s) ((size_t)16u + (size_t)(s) * 14u)
/* The segment table at the start of a segmented body: per segment its
 * length and CRC-32, then the CRC-32 of the payload from its first byte to
 * the table's last 4 bytes (the header and the table: whoever changes the
 * header, as the host adding records, writes it again). */
#define BW_SEGMENT_TABLE_SIZE(s) ((size_t)(s) * 8u + 4u)

/*
 * Decodes what a segmented payload still holds when parts of it are damaged
 * or missing (a cut payload, bytes lost or changed on the way): every
 * segment that lies whole within payload[len] and matches its CRC-32 is
 * decoded, the coefficients of the others are taken as zero, and the
 * samples are rebuilt from what is there (the coarser levels of a lost
 * segment's region). The header and the segment table must be intact (their
 * own CRC-32). Returns BW_OK for a whole payload (as bw_decode_ctx),
 * BW_ERR_INCOMPLETE when segments were lost (the samples hold the rest),
 * else bw_decode_ctx's error (a payload without segments that is not whole:
 * BW_ERR_CRC or BW_ERR_TRUNCATED). seg_ok (may be NULL): per segment 1
 * decoded, 0 lost, for the first seg_cap segments (hdr_out->segments in
 * all). vec_lost (may be NULL): n_in * n_out bytes, the coefficient vectors
 * in their place in the work array ([incoming][outgoing], in-place
 * transform positions), 1 where a vector's coefficients were lost, else 0.
 */
bw_status_t bw_decode_salvage(bw_ctx_t *ctx, const uint8_t *payload, size_t len,
                              int32_t *samples, size_t samples_cap, int32_t *work,
                              size_t work_cap, bw_header_t *hdr_out, uint8_t *seg_ok,
                              size_t seg_cap, uint8_t *vec_lost);

/*
 * Decodes one incoming direction of a BRDF (shapes BRDF_ISO and BRDF_FULL:
 * row `in` of the samples' layout [incoming][outgoing][band]) or one
 * spectrum of a set of spectra (row `in`): n_out * bands samples into
 * samples, the same as that row of bw_decode_ctx's. Only what the row
 * depends on is decoded: the segments that hold its coefficients (a body
 * in one piece up to the last of them) and, for a full BRDF, the incoming
 * blocks on its path down the tree (with the mirror, the mirrored row's
 * too), then the inverse steps of those blocks alone; in segments, the
 * CRCs checked are the table's and those of the segments read (BW_ERR_CRC),
 * not the whole payload's. work: as for bw_decode_ctx (the coefficients
 * have their places in it). BW_ERR_ARG for
 * a reflectance (no incoming axis), a row out of range, or a full BRDF with
 * the reciprocity step (every row depends on every other: decode it all).
 */
bw_status_t bw_decode_incoming(bw_ctx_t *ctx, const uint8_t *payload, size_t len, uint32_t in,
                               int32_t *samples, size_t samples_cap, int32_t *work,
                               size_t work_cap, bw_header_t *hdr_out);

/*
 * Decodes the incoming directions (rows) marked non-zero in rows[n_in] of
 * a BRDF, or the spectra so marked of a set of spectra (a region of the
 * incoming hemisphere, any set of rows): each marked row's n_out * bands
 * samples, in ascending row order, into samples, the same as those rows of
 * bw_decode_ctx's. Only what the rows depend on is decoded, once: the
 * segments that hold their incoming blocks (a body in one piece up to the
 * last of them) and, for a full BRDF, the inverse steps of the parents
 * above them (with the mirror, above the mirrored rows' partners too); the
 * CRCs checked as bw_decode_incoming's; spectra coded by prediction from
 * their segment's first. work: as for bw_decode_ctx. BW_ERR_ARG for a
 * reflectance, or a full BRDF with the reciprocity step; BW_ERR_WORK when
 * samples_cap is less than the marked rows' samples.
 */
bw_status_t bw_decode_rows(bw_ctx_t *ctx, const uint8_t *payload, size_t len, const uint8_t *rows,
                           int32_t *samples, size_t samples_cap, int32_t *work, size_t work_cap,
                           bw_header_t *hdr_out);

/*
 * Decodes a directional measurement (a reflectance, a BRDF) at a coarser
 * outgoing level (level of detail): n_in * 4 4^level * bands samples in
 * the layout of a measurement of that level, each the Bio-Haar scaling
 * value of its triangle (the area-weighted mean of the samples below it, up
 * to the lifting's rounding): exactly the whole decode's samples taken up
 * the tree to that level, or with the mirror step (whose differences are
 * taken at the finest level) within a few units. Only the coefficients of the
 * levels above are decoded (in segments, only the segments that hold them:
 * the first of a reflectance's) and inverted. level 0..level_out;
 * BW_ERR_ARG without an outgoing hemisphere, or with the reciprocity step.
 */
bw_status_t bw_decode_level(bw_ctx_t *ctx, const uint8_t *payload, size_t len, unsigned level,
                            int32_t *samples, size_t samples_cap, int32_t *work, size_t work_cap,
                            bw_header_t *hdr_out);

/*
 * The same at a coarser level of both hemispheres of a full BRDF: outgoing
 * level `level` and incoming level `level_in` (BW_LEVEL_OWN: the payload's
 * own), n_in = 4 4^level_in (a full BRDF; other shapes keep their n_in and
 * take BW_LEVEL_OWN or 0) times 4 4^level * bands samples in the layout of
 * a full BRDF of those levels. Only the coefficients of the levels above
 * on both sides are decoded: the first 4 4^level_in incoming blocks (in
 * segments, the segments that hold them), each to its first 4 4^level
 * vectors. Each value is the scaling value of its pair of triangles,
 * within a few units of the whole decode taken up both trees (the
 * lifting's roundings, incoming and outgoing, in the decoder's order).
 */
#define BW_LEVEL_OWN 0xFFu
bw_status_t bw_decode_lod(bw_ctx_t *ctx, const uint8_t *payload, size_t len, unsigned level,
                          unsigned level_in, int32_t *samples, size_t samples_cap, int32_t *work,
                          size_t work_cap, bw_header_t *hdr_out);

/* Bands b0 .. b1 - 1 of every spectrum of a payload with band access
 * (BW_EXT_BANDS; else BW_ERR_ARG) into samples[n_in][b1 - b0]: only the
 * columns of errors those bands depend on are decoded (at each prediction
 * level about one per band, and two), and only the CRC-32s of the tables
 * (which cover the header) and of the groups of columns read are checked,
 * not the whole payload's. The samples equal those of the whole decode.
 * work holds bw_band_range_work(n_in, b1 - b0) int32. */
size_t bw_band_range_work(uint32_t n_in, uint32_t bands);
/* The bytes of such a payload's tables after its header, before their
 * CRC-32, which covers the header and them (a writer that changes the
 * header's records rewrites it), or 0 if they do not fit the body. */
size_t bw_bands_tables(const bw_header_t *h, const uint8_t *payload);
bw_status_t bw_decode_band_range(const uint8_t *payload, size_t len, uint32_t b0, uint32_t b1,
                                 int32_t *samples, size_t samples_cap, int32_t *work,
                                 size_t work_cap, bw_header_t *hdr_out);

/* What bw_decode_salvage rebuilt, per direction pair (every band alike):
 * exact (as the whole payload decodes), approximate (rebuilt from the
 * coarser levels that were kept, without finer details that were lost), or
 * missing (its coarsest level was lost: the samples there are not to be
 * used). */
#define BW_SAMPLE_EXACT 0u
#define BW_SAMPLE_APPROX 1u
#define BW_SAMPLE_MISSING 2u
/* mask[n_in * n_out] in the samples' layout ([incoming][outgoing]) from the
 * lost vectors bw_decode_salvage reported; tmp: n_in * n_out int32 of
 * scratch. */
void bw_salvage_mask(const bw_header_t *h, const uint8_t *vec_lost, uint8_t *mask,
                     int32_t *tmp);

/* ---- streaming encoder ------------------------------------------------ */

/*
 * Encodes spectra as they arrive, in scan order ([incoming][outgoing], the
 * grid order of the directions), with RAM that does not grow with the number
 * of directions (nor with segments, bw_params_t.segment_vectors: their table
 * is kept in the output): each spectrum is transformed on arrival, and the Bio-Haar
 * lifting runs up the triangle tree as soon as four siblings are complete,
 * its coefficients going straight to the strip coder. The payload is
 * byte-identical to bw_encode's with BW_FLAG_STREAM_ORDER and the same
 * parameters. Modes LOSSLESS, MAX_ERROR and STEP with an explicit basis;
 * shapes SPECTRA, REFLECTANCE and BRDF_ISO.
 *
 * RAM: the context (sizeof(bw_stream_t), mostly the coder's models) plus
 * BW_STREAM_MEM_BOUND(level_out, bands) int32 of caller memory (pending
 * sibling vectors of each level and per-band tables), plus the output.
 */
#define BW_STREAM_MEM_BOUND(level, bands) ((size_t)(4u * ((level) + 1u) + 3u) * (size_t)(bands))

typedef struct {
    bw_dims_t dims;
    bw_params_t params; /* with BW_FLAG_STREAM_ORDER */
    int32_t *mem;       /* the caller's: spectral tables, lifting scratch, pending vectors */
    uint8_t pend_n[BW_MAX_LEVEL + 1u];
    uint32_t leaf; /* the next spectrum's leaf */
    size_t pushed;
    uint8_t *out;
    size_t cap;
    bw_status_t err;
    /* segments (params.segment_vectors): the vectors coded, the segment
     * being coded and where it begins in the body, the header's length */
    size_t emitted, seg_at, hl;
    uint32_t seg;
    bw_strip_enc_t se;
} bw_stream_t;

size_t bw_stream_mem_bound(unsigned level, size_t bands);
bw_status_t bw_stream_init(bw_stream_t *s, const bw_dims_t *dims, const bw_params_t *params,
                           int32_t *mem, size_t mem_len, uint8_t *out, size_t out_cap);
/* One spectrum of dims->bands samples (not kept). */
bw_status_t bw_stream_push(bw_stream_t *s, const int32_t *spectrum);
/* After the last spectrum: writes header and CRC; *out_len = payload size. */
bw_status_t bw_stream_finish(bw_stream_t *s, size_t *out_len);

/* As bw_decode, but without the length and CRC checks: for tests that feed the
 * body parser corrupted data which a CRC would otherwise catch. */
bw_status_t bw_decode_unchecked(const uint8_t *payload, size_t len, int32_t *samples,
                                size_t samples_cap, int32_t *work, size_t work_cap);

#ifdef __cplusplus
}
#endif

#endif /* BW_CODEC_H */
