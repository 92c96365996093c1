/* SPDX-License-Identifier: BSD-2-Clause */
#include "bw_frame.h"

#include <string.h>

#include "bw_crc32.h"

size_t bw_frame_pack(uint8_t *out, uint8_t type, uint16_t seq, const uint8_t *data, uint16_t len)
{
    if (len > BW_FRAME_MAX_DATA)
        return 0;
    out[0] = BW_FRAME_SYNC0;
    out[1] = BW_FRAME_SYNC1;
    out[2] = type;
    out[3] = 0;
    bw_put_u16(out + 4, seq);
    bw_put_u16(out + 6, len);
    if (len)
        memcpy(out + BW_FRAME_HEADER, data, len);
    bw_put_u32(out + BW_FRAME_HEADER + len, bw_crc32(out + 2, BW_FRAME_HEADER - 2u + len));
    return BW_FRAME_OVERHEAD + len;
}

void bw_frame_rx_init(bw_frame_rx_t *rx)
{
    rx->have = 0;
    rx->dropped = 0;
    rx->bad_crc = 0;
}

/* Drops the first byte and shifts to the next possible sync. */
static void resync(bw_frame_rx_t *rx)
{
    size_t i = 1;
    while (i < rx->have && rx->buf[i] != BW_FRAME_SYNC0)
        i++;
    rx->dropped += (uint32_t)i;
    memmove(rx->buf, rx->buf + i, rx->have - i);
    rx->have -= i;
}

/* Takes a complete, valid frame off the front of the buffered bytes, if
 * there is one; drops what cannot start a frame on the way. */
static bool extract(bw_frame_rx_t *rx, bw_frame_t *out)
{
    for (;;) {
        if (rx->have >= 1 && rx->buf[0] != BW_FRAME_SYNC0) {
            resync(rx);
            continue;
        }
        if (rx->have >= 2 && rx->buf[1] != BW_FRAME_SYNC1) {
            resync(rx);
            continue;
        }
        if (rx->have < BW_FRAME_HEADER)
            return false;
        uint16_t len = bw_get_u16(rx->buf + 6);
        if (len > BW_FRAME_MAX_DATA || rx->buf[3] != 0) {
            resync(rx);
            continue;
        }
        size_t total = BW_FRAME_OVERHEAD + len;
        if (rx->have < total)
            return false;
        uint32_t crc = bw_get_u32(rx->buf + BW_FRAME_HEADER + len);
        if (bw_crc32(rx->buf + 2, BW_FRAME_HEADER - 2u + len) != crc) {
            rx->bad_crc++;
            resync(rx);
            continue;
        }
        out->type = rx->buf[2];
        out->flags = rx->buf[3];
        out->seq = bw_get_u16(rx->buf + 4);
        out->len = len;
        memcpy(out->data, rx->buf + BW_FRAME_HEADER, len);
        /* keep the bytes past this frame: after a resynchronisation they
         * may hold further frames */
        memmove(rx->buf, rx->buf + total, rx->have - total);
        rx->have -= total;
        return true;
    }
}

size_t bw_frame_rx_feed(bw_frame_rx_t *rx, const uint8_t *in, size_t len, bw_frame_t *out,
                        bool *got)
{
    *got = extract(rx, out);
    if (*got)
        return 0;
    for (size_t i = 0; i < len; i++) {
        rx->buf[rx->have++] = in[i];
        if (extract(rx, out)) {
            *got = true;
            return i + 1u;
        }
    }
    return len;
}

bool bw_frame_rx_byte(bw_frame_rx_t *rx, uint8_t byte, bw_frame_t *out)
{
    bool got;
    size_t used = bw_frame_rx_feed(rx, &byte, 1, out, &got);
    if (!got || used == 1)
        return got;
    /* a frame that was already buffered: the byte goes in behind it */
    rx->buf[rx->have++] = byte;
    return true;
}

size_t bw_job_pack(const bw_job_t *j, uint8_t *o)
{
    memset(o, 0, BW_JOB_SIZE);
    o[0] = j->shape;
    o[1] = j->level_out;
    o[2] = j->level_in;
    o[3] = j->mode;
    o[4] = j->basis;
    o[5] = j->flags;
    o[6] = j->effort;
    o[7] = j->coder;
    bw_put_u32(o + 8, j->n_in);
    bw_put_u32(o + 12, j->bands);
    bw_put_u32(o + 16, j->max_error);
    bw_put_u32(o + 20, j->byte_budget);
    bw_put_u32(o + 24, j->scale_bits);
    bw_put_u32(o + 28, j->offset_bits);
    for (size_t i = 0; i + 1 < sizeof j->source && j->source[i]; i++)
        o[32 + i] = (uint8_t)j->source[i];
    size_t n = j->ext && j->ext_len <= BW_JOB_EXT_MAX ? j->ext_len : 0u;
    if (n)
        memcpy(o + BW_JOB_SIZE, j->ext, n);
    return BW_JOB_SIZE + n;
}

bool bw_job_unpack(const uint8_t *in, size_t len, bw_job_t *j)
{
    if (len < BW_JOB_SIZE || len > BW_JOB_SIZE + BW_JOB_EXT_MAX || in[6] > BW_EFFORT_FAST ||
        in[7] > BW_CODER_AUTO)
        return false;
    memset(j, 0, sizeof *j);
    j->shape = in[0];
    j->level_out = in[1];
    j->level_in = in[2];
    j->mode = in[3];
    j->basis = in[4];
    j->flags = in[5];
    j->effort = in[6];
    j->coder = in[7];
    j->n_in = bw_get_u32(in + 8);
    j->bands = bw_get_u32(in + 12);
    j->max_error = bw_get_u32(in + 16);
    j->byte_budget = bw_get_u32(in + 20);
    j->scale_bits = bw_get_u32(in + 24);
    j->offset_bits = bw_get_u32(in + 28);
    if (len > BW_JOB_SIZE) {
        j->ext = in + BW_JOB_SIZE;
        j->ext_len = (uint32_t)(len - BW_JOB_SIZE);
    }
    size_t i = 0;
    for (; i < sizeof j->source - 1u; i++) {
        j->source[i] = (char)in[32 + i];
        if (!in[32 + i])
            break;
    }
    return i < sizeof j->source - 1u; /* NUL-terminated within the field */
}

static void limits_put(uint8_t *o, const bw_limits_t *lim)
{
    bw_put_u32(o, lim->max_samples);
    bw_put_u32(o + 4, lim->max_bands);
    bw_put_u32(o + 8, lim->stream_bands);
    bw_put_u32(o + 12, lim->payload_cap);
    o[16] = lim->stream_level;
}

static void limits_get(const uint8_t *in, bw_limits_t *lim)
{
    lim->max_samples = bw_get_u32(in);
    lim->max_bands = bw_get_u32(in + 4);
    lim->stream_bands = bw_get_u32(in + 8);
    lim->payload_cap = bw_get_u32(in + 12);
    lim->stream_level = in[16];
}

size_t bw_error_pack(int32_t status, const bw_limits_t *lim, uint8_t *o)
{
    bw_put_u32(o, (uint32_t)status);
    limits_put(o + 4, lim);
    return BW_ERROR_SIZE;
}

bool bw_error_unpack(const uint8_t *in, size_t len, int32_t *status, bw_limits_t *lim)
{
    memset(lim, 0, sizeof *lim);
    if (len < 4)
        return false;
    *status = (int32_t)bw_get_u32(in);
    if (len >= BW_ERROR_SIZE)
        limits_get(in + 4, lim);
    return true;
}

size_t bw_hello_pack(const bw_limits_t *lim, uint8_t *o)
{
    o[0] = BW_LINK_VERSION;
    limits_put(o + 1, lim);
    return BW_HELLO_SIZE;
}

bool bw_hello_unpack(const uint8_t *in, size_t len, uint8_t *version, bw_limits_t *lim)
{
    memset(lim, 0, sizeof *lim);
    if (len < BW_HELLO_SIZE)
        return false;
    *version = in[0];
    limits_get(in + 1, lim);
    return true;
}

bw_status_t bw_limits_admit(const bw_limits_t *lim, const bw_dims_t *d, const bw_params_t *p,
                            bool *streamed)
{
    /* embedded segments need coarse-to-fine order: the encoder refuses
     * stream order with them, and so does the streaming path */
    if (p->progressive && (p->flags & BW_FLAG_STREAM_ORDER)) {
        *streamed = false;
        return BW_ERR_ARG;
    }
    *streamed = (p->flags & BW_FLAG_STREAM_ORDER) && p->mode != BW_MODE_BYTES &&
                p->basis < BW_BASIS_COUNT && d->shape != BW_SHAPE_BRDF_FULL &&
                d->bands <= lim->stream_bands && d->level_out <= lim->stream_level;
    if (*streamed)
        return BW_OK;
    if (d->bands > lim->max_bands || bw_dims_samples(d) > lim->max_samples)
        return BW_ERR_WORK;
    return BW_OK;
}

void bw_job_make(bw_job_t *j, const bw_dims_t *d, const bw_params_t *p)
{
    memset(j, 0, sizeof *j);
    j->shape = d->shape;
    j->level_out = d->level_out;
    j->level_in = d->level_in;
    j->n_in = d->n_in;
    j->bands = d->bands;
    j->mode = p->mode;
    j->basis = p->basis;
    j->flags = p->flags;
    j->effort = p->effort;
    j->coder = p->coder;
    j->max_error = p->max_error;
    j->byte_budget = p->byte_budget;
    j->scale_bits = p->scale_bits;
    j->offset_bits = p->offset_bits;
    j->ext = p->ext;
    j->ext_len = p->ext_len;
}

void bw_job_params(const bw_job_t *j, bw_params_t *p)
{
    memset(p, 0, sizeof *p);
    p->mode = j->mode;
    p->basis = j->basis;
    p->flags = j->flags;
    p->effort = j->effort;
    p->coder = j->coder;
    p->max_error = j->max_error;
    p->byte_budget = j->byte_budget;
    p->scale_bits = j->scale_bits;
    p->offset_bits = j->offset_bits;
    p->ext = j->ext;
    p->ext_len = j->ext_len;
    /* segments travel as the job's first record, BW_EXT_SEGMENTS with V (a
     * varint), embedded segments as a BW_EXT_EMBEDDED record without data
     * right after it: the encoder writes those records itself (a device
     * that predates segments refuses the job: a critical record it does
     * not know; one that predates embedded segments refuses a record 0x04
     * among the payload's records) */
    const uint8_t *e = j->ext;
    if (j->ext_len >= 3u && e[0] == BW_EXT_SEGMENTS && e[1] >= 1u && e[1] <= 5u &&
        2u + (uint32_t)e[1] <= j->ext_len) {
        uint32_t v = 0, used = 2u + e[1];
        for (unsigned k = 0; k < e[1]; k++)
            v |= (uint32_t)(e[2 + k] & 0x7Fu) << (7u * k);
        p->segment_vectors = v;
        if (j->ext_len >= used + 2u && e[used] == BW_EXT_EMBEDDED && e[used + 1u] == 0u) {
            p->progressive = 1u;
            used += 2u;
        }
        p->ext = j->ext_len > used ? e + used : NULL;
        p->ext_len = j->ext_len - used;
    }
}
