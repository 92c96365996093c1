/* SPDX-License-Identifier: BSD-2-Clause */
/* Little-endian fields of the wire formats (payload, link frames): explicit
 * byte shifts, never a struct written to the wire. */
#ifndef BW_LE_H
#define BW_LE_H

#include <stdint.h>

static inline void bw_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}
static inline void bw_put_u32(uint8_t *p, uint32_t v)
{
    bw_put_u16(p, (uint16_t)v);
    bw_put_u16(p + 2, (uint16_t)(v >> 16));
}
static inline uint16_t bw_get_u16(const uint8_t *p) { return (uint16_t)(p[0] | p[1] << 8); }
static inline uint32_t bw_get_u32(const uint8_t *p)
{
    return (uint32_t)bw_get_u16(p) | (uint32_t)bw_get_u16(p + 2) << 16;
}

#endif
