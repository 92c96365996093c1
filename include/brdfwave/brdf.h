/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Decoded BRDFs as functions, for renderers: the analytic Phong and Ward
 * models, evaluation of a decoded payload at any (wi, wo, lambda) with the
 * interpolants of the paper's sec. 4.5, and importance sampling from the
 * triangle hierarchy (what `brdfwave render` uses). The library's own
 * headers, installed beside this one.
 */
#ifndef BRDFWAVE_BRDF_H
#define BRDFWAVE_BRDF_H

#include "brdfwave.h"

#include "brdf_eval.h"
#include "brdf_models.h"
#include "bw_sample.h"
#include "bwh_interp.h"

#endif
