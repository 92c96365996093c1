/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * What an image shows and how noisy it is: the displayed intensity, the image
 * variance of sec. 6.2 (per interior pixel the variance of the displayed
 * intensity over the 3 x 3 block of the pixel and its 8 neighbours, averaged
 * over the image), and sRGB encoding.
 */
#ifndef RENDER_IMAGE_H
#define RENDER_IMAGE_H

#include <stdint.h>

/* exposure * the mean of R, G, B, clamped to [0, 1] */
double render_displayed(const double *rgb, double exposure);

/* img: w * h pixels of R, G, B */
double render_image_variance(const double *img, unsigned w, unsigned h, double exposure);

/* a linear value in [0, 1] (clamped) as an 8-bit sRGB code */
uint8_t render_srgb8(double v);

#endif
