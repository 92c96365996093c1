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

/* A payload that arrived in part (docs/LINK.md, Incomplete payloads): the
 * device's id, the length and CRC-32 it announced for the whole payload,
 * and which of its parts (link chunks of 1024 bytes, I2C pages of 32) are
 * in; the parts not in read as zeros. */
typedef struct {
    uint32_t id, crc;
    size_t len;
    unsigned unit;    /* bytes a part */
    uint32_t parts;   /* ceil(len / unit) */
    uint8_t *have;    /* parts: 1 = in and checked */
    uint8_t *payload; /* len bytes */
} bwh_partial_t;

/* An empty record of a payload of len bytes in parts of unit bytes (none
 * in). 0, or -1 (bwh_last_error()). */
int bwh_partial_init(bwh_partial_t *p, uint32_t id, uint32_t crc, size_t len, unsigned unit);
void bwh_partial_free(bwh_partial_t *p);
/* Parts not in. */
uint32_t bwh_partial_missing(const bwh_partial_t *p);
/* Stores it in dir as payload-ID-CRC.part.bwv (the bytes, missing parts
 * zero: `brdfwave decode` decodes what its segments hold) and
 * payload-ID-CRC.part (a text record: id, length, crc, unit, the missing
 * parts), CRC the announced one in hex; each through a temporary file,
 * fsync and a rename that replaces an older record of it. The record's
 * name goes to path[cap]. 0, or -1. */
int bwh_partial_store(const char *dir, const bwh_partial_t *p, char *path, size_t cap);
/* Reads a record stored so (path: the .part or the .part.bwv file) and its
 * bytes. 0, or -1 with a clear error (missing, malformed, inconsistent). */
int bwh_partial_load(const char *path, bwh_partial_t *p);
/* Removes both files of a stored record (once the payload is whole). */
void bwh_partial_remove(const char *path);
/* Once a payload is whole and stored: removes the record of it that dir may
 * hold (the name bwh_partial_store gives it, from the id and the CRC-32 of
 * the payload's bytes). */
void bwh_partial_forget(const char *dir, uint32_t id, const uint8_t *payload, size_t len);

#ifdef __cplusplus
}
#endif

#endif
