/* SPDX-License-Identifier: BSD-2-Clause */
/* CRC-32 (IEEE 802.3, reflected 0xEDB88320, init and final xor 0xFFFFFFFF):
 * the CRC of "123456789" is 0xCBF43926. */
#ifndef BW_CRC32_H
#define BW_CRC32_H

#include <stddef.h>
#include <stdint.h>

uint32_t bw_crc32_update(uint32_t crc, const uint8_t *p, size_t n);
static inline uint32_t bw_crc32(const uint8_t *p, size_t n) { return bw_crc32_update(0, p, n); }

#endif
