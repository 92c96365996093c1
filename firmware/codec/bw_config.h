/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * brdfwave codec core: build switches.
 *
 * Each switch is 0 or 1 and may be set on the compiler's command line
 * (-DBW_CFG_...=0). The defaults do not depend on the optimisation level:
 * -O2 and -Os builds with the same switches write the same bytes.
 *
 * Encoder features: they change which payload an encoder writes.
 *
 *   switch                    default  what
 *   BW_CFG_ENCODE_PRED        1        bw_encode offers prediction (BW_BASIS_PRED):
 *                                      as a basis of its own, and among those
 *                                      BW_BASIS_AUTO tries on sets of spectra
 *                                      coded exactly or within a bound
 *   BW_CFG_BUDGET_FILL_HALF   1        the byte budget's last search: where a
 *                                      rounding offset of 1/8 of a step still
 *                                      leaves the budget short, offsets up to 1/2
 *   BW_CFG_FAST_BASIS         1        BW_EFFORT_FAST: BW_BASIS_AUTO chooses on
 *                                      parts of the measurement (0.9 KiB of
 *                                      flash); 0: it chooses as BW_EFFORT_BEST
 *                                      (every basis on the whole), the same
 *                                      payload or a smaller one
 *   BW_CFG_FAST_BUDGET        1        BW_EFFORT_FAST: a byte budget estimates
 *                                      its step and corrects it by the size of
 *                                      each encode (bw_budget.c); 0: it
 *                                      searches as BW_EFFORT_BEST
 *   BW_CFG_BANDS              1        sets of spectra with band access
 *                                      (BW_EXT_BANDS): encoder, decoders and
 *                                      bw_decode_band_range; 0: the encoder
 *                                      refuses it as not built, the decoders
 *                                      as an extension they do not know
 *   BW_CFG_SEGMENTS           1        bodies in segments (BW_EXT_SEGMENTS):
 *                                      bw_encode splits a body so when asked
 *                                      (bw_params_t.segment_vectors), the
 *                                      decoder decodes them; 0: both refuse
 *                                      them (BW_ERR_NOT_BUILT), as a build
 *                                      without BW_CFG_CODER_MS its payloads
 *
 *   BW_CFG_EMBED              1        embedded segments (BW_EXT_EMBEDDED,
 *                                      bw_params_t.progressive, bw_embed.c):
 *                                      bit-plane order, a prefix decodes to an
 *                                      approximation and a byte budget is a
 *                                      cut; needs BW_CFG_SEGMENTS; 0: both
 *                                      sides refuse them (BW_ERR_NOT_BUILT)
 *
 *   BW_CFG_CHUNK_STEPS        1        a step per chunk of vectors
 *                                      (BW_EXT_CHUNK_STEPS): with
 *                                      BW_CFG_FAST_BUDGET, BW_EFFORT_FAST meets
 *                                      a byte budget in one encode, steering
 *                                      the step chunk by chunk as it codes; the
 *                                      decoder decodes them; 0: the byte budget
 *                                      corrects its step encode by encode, and
 *                                      the decoder refuses them (BW_ERR_NOT_BUILT)
 *
 * Decoder features:
 *
 *   BW_CFG_SALVAGE            1        bw_decode_salvage decodes what a damaged
 *                                      or cut segmented payload still holds; 0:
 *                                      only whole payloads (as bw_decode_ctx)
 *
 * Coders:
 *
 *   BW_CFG_CODER_MS           1        the multi-symbol range coder (flag MS,
 *                                      format 7) both ways; 0 leaves it out of
 *                                      encoder and decoder (1.5 KiB of flash):
 *                                      such a build refuses an MS request or
 *                                      payload with BW_ERR_NOT_BUILT
 *   BW_CFG_CODER_TAB          as MS    the static-table coder (flags RICE and
 *                                      MS, format 7) both ways; 0 leaves it
 *                                      out (BW_ERR_NOT_BUILT as for MS)
 *
 * Apart from that the decoder has no switch: every build decodes every
 * payload the format allows, prediction included, whatever its encoder
 * leaves out.
 *
 * Text:
 *
 *   BW_CFG_STATUS_TEXT        1        bw_strerror gives each status's sentence;
 *                                      0: "status" for every one (a device sends
 *                                      the numbers, LINK.md ERROR, and the host
 *                                      turns them into text: 0.6 KiB of flash)
 *
 * Code forms: the same bytes, more flash for fewer instructions. Each
 * defaults to BW_CFG_SPEED (default 1), so one switch picks the small forms.
 *
 *   switch                    what the fast form does
 *   BW_CFG_FAST_LOADS         the load checks the sample range with one OR a
 *                             sample and runs the first one or two Haar levels,
 *                             or the first 5/3 or 9/7 level (with
 *                             BW_CFG_FAST_SPECTRAL), as it loads
 *   BW_CFG_FAST_QUANT         the quantiser's rounding offsets without a choice
 *                             per element, one band level by level, a vector's
 *                             energy past the values below the step
 *   BW_CFG_FAST_SPECTRAL      Haar, 5/3 and 9/7 levels in one pass over the
 *                             samples, 9/7's products one SMMULR each on a
 *                             core with the DSP extension
 *   BW_CFG_FAST_RICE          the Rice writer held in registers, whole strips
 *                             with a fixed count, the coarse-to-fine order as
 *                             loops
 *   BW_CFG_FAST_STRIPS        the range coders' strip code built once for each
 *                             direction (else one copy codes and decodes), the
 *                             coarse-to-fine order as loops, the multi-symbol
 *                             encoder's strips straight from the vectors
 *   BW_CFG_FAST_PREDICT       prediction's weight steps in 32 bits where the
 *                             values allow it, encoder and decoder loops
 *                             built apart
 *   BW_CFG_CRC_SLICE4         CRC-32 four bytes a step (4 KiB of tables, else
 *                             a 64-byte nibble table)
 *   BW_CFG_UNROLL             hot loops unrolled 8 times, small helpers inline,
 *                             the Bio-Haar levels built once per direction
 *
 * Builds in this repository and their bytes:
 *   the host library and CLI, the emulated board's firmware (make TARGET=qemu,
 *   -O2), the device benchmark's image: the defaults;
 *   the MCU build (make TARGET=mcu, -Os with link-time optimisation), the
 *   freestanding 16 KiB check, the sanitizer's first pass, the benchmark's
 *   -Os stack figures: the switches of mk/core-device.mk, BW_CFG_SPEED=0,
 *   BW_CFG_ENCODE_PRED=0, BW_CFG_BUDGET_FILL_HALF=0, BW_CFG_FAST_BASIS=0,
 *   BW_CFG_FAST_BUDGET=0, BW_CFG_SEGMENTS=0, BW_CFG_SALVAGE=0,
 *   BW_CFG_STATUS_TEXT=0 and BW_CFG_CODER_MS=0, which
 *   keep encoder, decoder and streaming encoder within 16 KiB of flash.
 *
 * Two builds write byte-identical payloads for the same input and options
 * exactly when their encoder features match; the code forms never matter.
 * A build without BW_CFG_ENCODE_PRED differs only where BW_BASIS_AUTO would
 * have chosen prediction (sets of spectra, LOSSLESS or MAX_ERROR) and refuses
 * BW_BASIS_PRED; one without BW_CFG_BUDGET_FILL_HALF only in BYTES payloads
 * whose search reaches that last step; one without BW_CFG_FAST_BASIS only
 * in BW_EFFORT_FAST encodes with BW_BASIS_AUTO; one without
 * BW_CFG_FAST_BUDGET only in BW_EFFORT_FAST byte budgets. A host that must reproduce a device's
 * payload byte for byte builds its library with the device's encoder features
 * (make EXTRA_CFLAGS="-DBW_CFG_ENCODE_PRED=0 -DBW_CFG_BUDGET_FILL_HALF=0"), or
 * asks the device for options that use neither (an explicit transform basis,
 * a mode other than BYTES). Every payload decodes alike in every build.
 */
#ifndef BW_CONFIG_H
#define BW_CONFIG_H

#ifndef BW_CFG_ENCODE_PRED
#define BW_CFG_ENCODE_PRED 1
#endif
#ifndef BW_CFG_BUDGET_FILL_HALF
#define BW_CFG_BUDGET_FILL_HALF 1
#endif

#ifndef BW_CFG_FAST_BASIS
#define BW_CFG_FAST_BASIS 1
#endif
#ifndef BW_CFG_FAST_BUDGET
#define BW_CFG_FAST_BUDGET 1
#endif

#ifndef BW_CFG_SEGMENTS
#define BW_CFG_SEGMENTS 1
#endif
#ifndef BW_CFG_SALVAGE
#define BW_CFG_SALVAGE 1
#endif
#ifndef BW_CFG_CHUNK_STEPS
#define BW_CFG_CHUNK_STEPS 1
#endif
#ifndef BW_CFG_EMBED
#define BW_CFG_EMBED BW_CFG_SEGMENTS
#endif

#ifndef BW_CFG_BANDS
#define BW_CFG_BANDS 1
#endif

#ifndef BW_CFG_STATUS_TEXT
#define BW_CFG_STATUS_TEXT 1
#endif

#ifndef BW_CFG_CODER_MS
#define BW_CFG_CODER_MS 1
#endif

#ifndef BW_CFG_CODER_TAB
#define BW_CFG_CODER_TAB BW_CFG_CODER_MS
#endif

#ifndef BW_CFG_SPEED
#define BW_CFG_SPEED 1
#endif
#ifndef BW_CFG_FAST_LOADS
#define BW_CFG_FAST_LOADS BW_CFG_SPEED
#endif
#ifndef BW_CFG_FAST_QUANT
#define BW_CFG_FAST_QUANT BW_CFG_SPEED
#endif
#ifndef BW_CFG_FAST_SPECTRAL
#define BW_CFG_FAST_SPECTRAL BW_CFG_SPEED
#endif
#ifndef BW_CFG_FAST_RICE
#define BW_CFG_FAST_RICE BW_CFG_SPEED
#endif
#ifndef BW_CFG_FAST_STRIPS
#define BW_CFG_FAST_STRIPS BW_CFG_SPEED
#endif
#ifndef BW_CFG_FAST_PREDICT
#define BW_CFG_FAST_PREDICT BW_CFG_SPEED
#endif
#ifndef BW_CFG_CRC_SLICE4
#define BW_CFG_CRC_SLICE4 BW_CFG_SPEED
#endif
#ifndef BW_CFG_UNROLL
#define BW_CFG_UNROLL BW_CFG_SPEED
#endif

#endif
