/* SPDX-License-Identifier: BSD-2-Clause */
/* Displayed intensity, image variance, sRGB (render_image.h). */
#include "render_image.h"

#include <math.h>
#include <stddef.h>

double render_displayed(const double *rgb, double exposure)
{
    double v = exposure * (rgb[0] + rgb[1] + rgb[2]) / 3.0;
    return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}

double render_image_variance(const double *img, unsigned w, unsigned h, double exposure)
{
    double total = 0.0;
    size_t n = 0;
    for (unsigned y = 1; y + 1 < h; y++)
        for (unsigned x = 1; x + 1 < w; x++) {
            double s = 0.0, s2 = 0.0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    double v =
                        render_displayed(img + 3 * ((size_t)(y + dy) * w + (x + dx)), exposure);
                    s += v;
                    s2 += v * v;
                }
            double mean = s / 9.0;
            total += s2 / 9.0 - mean * mean;
            n++;
        }
    return n ? total / (double)n : 0.0;
}

uint8_t render_srgb8(double v)
{
    v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
    v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
    return (uint8_t)lround(v * 255.0);
}
