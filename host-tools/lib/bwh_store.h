/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Storing received payloads: what `brdfwave receive`, `brdfwave acquire`
 * and the Python acquisition service do once a payload has been checked and
 * before they acknowledge it.
 */
#ifndef BWH_STORE_H
#define BWH_STORE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Stores a received payload in dir as payload-ID-CRC.bwv (ID the device's
 * payload id, CRC the payload's CRC-32 field in hex: a device that counts ids from 1 again
 * after a reboot cannot collide with what is stored), through a temporary
 * file, fsync and a link that never replaces an existing file; the name
 * goes to path[cap]. 0 when stored, 1 when that very payload was stored
 * before (a repeat whose acknowledgement was lost), -1 on failure. */
int bwh_store_payload(const char *dir, uint32_t id, const uint8_t *p, size_t n, char *path,
                      size_t cap);

#ifdef __cplusplus
}
#endif

#endif
