/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * The words for the payload header's fields and the encoder's choices, both
 * ways: what `brdfwave info` prints and what `brdfwave encode` and the
 * Python package take.
 */
#ifndef BWH_NAMES_H
#define BWH_NAMES_H

#ifdef __cplusplus
extern "C" {
#endif

/* "spectra", "reflectance", "brdf-iso", "brdf-full"; "?" out of range */
const char *bwh_shape_name(unsigned shape);
/* "lossless", "max-error", "bytes", "step"; "?" out of range */
const char *bwh_mode_name(unsigned mode);

/* "haar", "53", "97", "pred" (a header's basis); "?" out of range */
const char *bwh_basis_name(unsigned basis);
/* the encoder's basis for a name: those four, or "auto" (BW_BASIS_AUTO);
 * -1 for any other */
int bwh_basis_from_name(const char *name);

/* "none", "mirror", "reciprocal" or "both": a header's symmetry flags */
const char *bwh_symmetry_name(unsigned flags);
/* the encoder's flags for --symmetry NAME: "auto" 0 (every one that
 * applies is tried), "mirror", "reciprocal", "both" and "none" the header
 * flags with BWH_NO_MIRROR; -1 for any other name */
int bwh_symmetry_from_name(const char *name);

/* "range" or "rice" (BW_FLAG_RICE) */
const char *bwh_coder_name(unsigned flags);
/* the header flag of a coder name: "range" 0, "rice" BW_FLAG_RICE; -1 */
int bwh_coder_from_name(const char *name);

#ifdef __cplusplus
}
#endif

#endif
