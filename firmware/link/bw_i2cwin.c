/* SPDX-License-Identifier: BSD-2-Clause */
/* The I2C register window of docs/I2C.md (bw_i2cwin.h). */
#include "bw_i2cwin.h"

#include "bw_crc32.h"
#include "bw_frame.h"

enum { T_IDLE, T_WRITE, T_READ };

static void tell_ready(bw_i2cwin_t *w)
{
    if (w->ops && w->ops->ready)
        w->ops->ready(w->ops->ctx, w->offered);
}

static void to_app(bw_i2cwin_t *w, const uint8_t *bytes, size_t n)
{
    if (w->ops && w->ops->to_app)
        w->ops->to_app(w->ops->ctx, bytes, n);
}

void bw_i2cwin_init(bw_i2cwin_t *w, const bw_i2cwin_ops_t *ops)
{
    *w = (bw_i2cwin_t){0};
    w->ops = ops;
    w->state = T_IDLE;
}

/* ---- the device side ------------------------------------------------------ */

static void set_offered(bw_i2cwin_t *w, uint8_t offered)
{
    if (w->offered != offered) {
        w->offered = offered;
        tell_ready(w);
    }
}

void bw_i2cwin_offer(bw_i2cwin_t *w, uint32_t id, const uint8_t *payload, uint32_t len,
                     uint32_t crc)
{
    if (len > BW_I2CWIN_MAX_LEN) {
        w->lost = 1;
        len = 0;
    }
    if (len == 0 || payload == 0) {
        set_offered(w, 0);
        return;
    }
    w->payload = payload;
    w->id = id;
    w->len = len;
    w->crc = crc;
    set_offered(w, 1);
}

void bw_i2cwin_job_failed(bw_i2cwin_t *w, int32_t status)
{
    w->error = 1;
    w->errcode = (uint16_t)status;
}

void bw_i2cwin_set_fault(bw_i2cwin_t *w, uint32_t code)
{
    w->fault = code;
    w->fault_valid = 1;
}

void bw_i2cwin_lost(bw_i2cwin_t *w) { w->lost = 1; }

/* ---- registers --------------------------------------------------------------- */

static uint32_t pages_of(const bw_i2cwin_t *w)
{
    return (w->len + BW_I2C_PAGE_SIZE - 1u) / BW_I2C_PAGE_SIZE;
}

/* bytes of the selected page in the payload, 0 when none is selected */
static uint32_t page_len(const bw_i2cwin_t *w)
{
    if (!w->offered || w->page == 0 || w->page > pages_of(w))
        return 0;
    uint32_t off = (uint32_t)(w->page - 1u) * BW_I2C_PAGE_SIZE;
    return w->len - off < BW_I2C_PAGE_SIZE ? w->len - off : BW_I2C_PAGE_SIZE;
}

static const uint8_t *page_data(const bw_i2cwin_t *w)
{
    return w->payload + (uint32_t)(w->page - 1u) * BW_I2C_PAGE_SIZE;
}

/* byte i of the selected page; 0xFF past its end */
static uint8_t page_byte(const bw_i2cwin_t *w, uint32_t i)
{
    return i < page_len(w) ? page_data(w)[i] : 0xFFu;
}

static uint8_t status_byte(const bw_i2cwin_t *w)
{
    return (uint8_t)((w->offered ? BW_I2C_ST_READY : 0u) | (w->error ? BW_I2C_ST_ERROR : 0u) |
                     (w->fault_valid ? BW_I2C_ST_FAULT : 0u) | (w->lost ? BW_I2C_ST_LOST : 0u) |
                     (w->nak ? BW_I2C_ST_NAK : 0u));
}

uint16_t bw_i2cwin_register(const bw_i2cwin_t *w, uint32_t r)
{
    uint32_t v = 0, fault = w->fault_valid ? w->fault : 0u;
    int ready = w->offered;
    if (r >= BW_I2C_DATA && r < BW_I2C_DATA + BW_I2C_PAGE_SIZE / 2u) {
        uint32_t i = 2u * (uint32_t)(r - BW_I2C_DATA);
        return page_len(w) ? (uint16_t)(page_byte(w, i) | page_byte(w, i + 1u) << 8) : 0u;
    }
    switch (r) {
    case BW_I2C_MAGIC: v = BW_I2C_MAGIC_VALUE; break;
    case BW_I2C_VERSION: v = BW_I2C_PAGE_SIZE << 8 | BW_I2C_MAP_VERSION; break;
    case BW_I2C_STATUS: v = status_byte(w); break;
    case BW_I2C_ID_LO: v = ready ? w->id : 0u; break;
    case BW_I2C_ID_HI: v = ready ? w->id >> 16 : 0u; break;
    case BW_I2C_LEN_LO: v = ready ? w->len : 0u; break;
    case BW_I2C_LEN_HI: v = ready ? w->len >> 16 : 0u; break;
    case BW_I2C_PAGES: v = ready ? pages_of(w) : 0u; break;
    case BW_I2C_CRC_LO: v = ready ? w->crc : 0u; break;
    case BW_I2C_CRC_HI: v = ready ? w->crc >> 16 : 0u; break;
    case BW_I2C_ERRCODE: v = w->errcode; break;
    case BW_I2C_FAULT_LO: v = fault; break;
    case BW_I2C_FAULT_HI: v = fault >> 16; break;
    case BW_I2C_PAGE: v = w->page; break;
    case BW_I2C_PAGE_HI: v = w->page_hi; break;
    case BW_I2C_RETRY: v = 0; break; /* the page in RAM is intact: answered at once */
    case BW_I2C_ACK_LO: v = w->ack_lo; break;
    case BW_I2C_ACK_HI: v = w->ack_hi; break;
    case BW_I2C_CMD: v = 0; break; /* commands complete inside the write */
    case BW_I2C_PNUM: v = page_len(w) ? w->page : 0u; break;
    case BW_I2C_PLEN: v = page_len(w); break;
    case BW_I2C_PCRC_LO:
    case BW_I2C_PCRC_HI: {
        uint32_t n = page_len(w), c = n ? bw_crc32(page_data(w), n) : 0u;
        v = r == BW_I2C_PCRC_LO ? c : c >> 16;
        break;
    }
    default: break;
    }
    return (uint16_t)v;
}

static void command(bw_i2cwin_t *w, uint8_t c)
{
    if (c == BW_I2C_CMD_ACK) {
        uint32_t id = (uint32_t)w->ack_hi << 16 | w->ack_lo;
        if (w->offered && id == w->id) {
            uint8_t d[4], f[BW_FRAME_OVERHEAD + 4u];
            bw_put_u32(d, id);
            set_offered(w, 0);
            to_app(w, f, bw_frame_pack(f, BW_FT_ACK, 0, d, 4));
        } else {
            w->nak = 1;
        }
    } else if (c == BW_I2C_CMD_CLEAR) {
        w->error = 0;
        w->lost = 0;
        w->nak = 0;
        w->fault_valid = 0;
    }
}

/* ---- the bus side ------------------------------------------------------------ */

/* end of a transfer (STOP or repeated START): a register write is applied */
static void end_transfer(bw_i2cwin_t *w)
{
    if (w->state == T_WRITE && !w->first && w->index > 0u) {
        uint8_t lo = w->wbuf[0];
        uint16_t word = (uint16_t)(lo | (w->index > 1u ? w->wbuf[1] << 8 : 0));
        switch (w->reg) {
        case BW_I2C_PAGE: w->page = (uint16_t)(w->page_hi << 8 | lo); break;
        case BW_I2C_PAGE_HI: w->page_hi = lo; break;
        case BW_I2C_RETRY: break; /* nothing to refresh: the page is in RAM */
        case BW_I2C_ACK_LO: w->ack_lo = word; break;
        case BW_I2C_ACK_HI: w->ack_hi = word; break;
        case BW_I2C_CMD: command(w, lo); break;
        default: break;
        }
    }
    w->state = T_IDLE;
}

void bw_i2cwin_addressed(bw_i2cwin_t *w, int host_reads)
{
    end_transfer(w);
    w->state = host_reads ? T_READ : T_WRITE;
    w->first = !host_reads;
    w->index = 0;
}

void bw_i2cwin_received(bw_i2cwin_t *w, uint8_t b)
{
    if (w->state != T_WRITE)
        return;
    if (w->first) {
        w->reg = b;
        w->first = 0;
        w->index = 0;
        return;
    }
    if (w->reg == BW_I2C_FRAMES)
        to_app(w, &b, 1);
    else if (w->index < 2u)
        w->wbuf[w->index] = b;
    w->index++;
}

uint8_t bw_i2cwin_transmit(bw_i2cwin_t *w)
{
    uint32_t i = w->index++;
    if (w->state != T_READ)
        return 0xFFu;
    if (w->reg == BW_I2C_BLOCK)
        return i == 0 ? (uint8_t)page_len(w) : page_byte(w, i - 1u);
    uint16_t v = bw_i2cwin_register(w, w->reg + i / 2u);
    return (uint8_t)(i & 1u ? v >> 8 : v);
}

void bw_i2cwin_stop(bw_i2cwin_t *w) { end_transfer(w); }

void bw_i2cwin_bus_error(bw_i2cwin_t *w)
{
    w->lost = 1;
    w->state = T_IDLE;
}
