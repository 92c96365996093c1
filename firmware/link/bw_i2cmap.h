/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The co-processor's I2C register map (docs/I2C.md), shared by the register
 * window the boards serve (bw_i2cwin.c) and the host's I2C client
 * (host-tools/lib/bwh_i2c.c, which both acquirers run).
 * host-tools/python/brdfwave/i2cmap.py repeats these values; a test compares them.
 *
 * Registers are 16 bits, SMBus words (low byte first). Registers
 * BW_I2C_WINDOW_FIRST .. BW_I2C_WINDOW_LAST change with BW_I2C_PAGE.
 */
#ifndef BW_I2CMAP_H
#define BW_I2CMAP_H

#define BW_I2C_ADDR 0x42u

#define BW_I2C_MAGIC 0x00u
#define BW_I2C_VERSION 0x01u
#define BW_I2C_STATUS 0x02u
#define BW_I2C_ID_LO 0x03u
#define BW_I2C_ID_HI 0x04u
#define BW_I2C_LEN_LO 0x05u
#define BW_I2C_LEN_HI 0x06u
#define BW_I2C_PAGES 0x07u
#define BW_I2C_CRC_LO 0x08u
#define BW_I2C_CRC_HI 0x09u
#define BW_I2C_ERRCODE 0x0Au
#define BW_I2C_FAULT_LO 0x0Bu
#define BW_I2C_FAULT_HI 0x0Cu
#define BW_I2C_PAGE 0x10u
#define BW_I2C_PAGE_HI 0x11u
#define BW_I2C_RETRY 0x12u
#define BW_I2C_ACK_LO 0x13u
#define BW_I2C_ACK_HI 0x14u
#define BW_I2C_CMD 0x15u
#define BW_I2C_FRAMES 0x16u
#define BW_I2C_BLOCK 0x20u
#define BW_I2C_DATA 0x40u /* DATA0 .. DATA15 */
#define BW_I2C_PNUM 0x50u
#define BW_I2C_PLEN 0x51u
#define BW_I2C_PCRC_LO 0x52u
#define BW_I2C_PCRC_HI 0x53u
#define BW_I2C_WINDOW_FIRST 0x40u
#define BW_I2C_WINDOW_LAST 0x53u

#define BW_I2C_MAGIC_VALUE 0x5742u /* "BW" */
#define BW_I2C_MAP_VERSION 1u
#define BW_I2C_PAGE_SIZE 32u

#define BW_I2C_ST_READY 0x01u
#define BW_I2C_ST_ERROR 0x02u
#define BW_I2C_ST_FAULT 0x04u
#define BW_I2C_ST_LOST 0x08u
#define BW_I2C_ST_NAK 0x10u

#define BW_I2C_CMD_ACK 0x01u
#define BW_I2C_CMD_CLEAR 0x02u

#endif
