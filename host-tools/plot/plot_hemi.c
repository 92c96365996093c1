/* SPDX-License-Identifier: BSD-2-Clause */
/* The hemisphere of geodesic triangles in polar projection, and the colour
 * bar (plot.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bwh_error.h"
#include "geodesic.h"
#include "plot.h"

#define PI 3.14159265358979323846
#define TEXT 2

void plot_hemisphere_xy(int cx, int cy, int r, const double d[3], double *x, double *y)
{
    double z = d[2] > 1 ? 1 : d[2] < 0 ? 0 : d[2];
    double theta = acos(z), phi = atan2(d[1], d[0]);
    double rho = r * theta / (PI / 2);
    *x = cx + rho * cos(phi);
    *y = cy - rho * sin(phi); /* +y of the hemisphere upwards */
}

/* the colour map's position of value v */
static double position(double v, double lo, double hi, int log)
{
    if (log) {
        if (!(v > 0))
            return 0;
        return (log10(v) - log10(lo)) / (log10(hi) - log10(lo));
    }
    return (v - lo) / (hi - lo);
}

int plot_hemisphere(plot_canvas_t *c, int cx, int cy, int r, unsigned level,
                    const double *values, double lo, double hi, int log, int edges)
{
    /* the triangle of every pixel in the disc's box (-1: outside the disc) */
    int side = 2 * r + 1;
    long *tri = malloc((size_t)side * side * sizeof *tri);
    if (!tri)
        return bwh_fail("out of memory");
    for (int j = 0; j < side; j++)
        for (int i = 0; i < side; i++) {
            double dx = i - r, dy = r - j, rho = hypot(dx, dy);
            long t = -1;
            if (rho <= r) {
                double theta = rho / r * (PI / 2), phi = atan2(dy, dx);
                double d[3] = {sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)};
                t = bwh_grid_locate(level, d);
            }
            tri[(size_t)j * side + i] = t;
        }
    for (int j = 0; j < side; j++)
        for (int i = 0; i < side; i++) {
            long t = tri[(size_t)j * side + i];
            if (t < 0)
                continue;
            plot_rgb_t col = plot_colour_map(position(values[t], lo, hi, log));
            /* a triangle's edge: a neighbour in another triangle */
            if (edges && ((i + 1 < side && tri[(size_t)j * side + i + 1] >= 0 &&
                           tri[(size_t)j * side + i + 1] != t) ||
                          (j + 1 < side && tri[(size_t)(j + 1) * side + i] >= 0 &&
                           tri[(size_t)(j + 1) * side + i] != t))) {
                col.r = (uint8_t)(col.r * 0.55 + 255 * 0.45);
                col.g = (uint8_t)(col.g * 0.55 + 255 * 0.45);
                col.b = (uint8_t)(col.b * 0.55 + 255 * 0.45);
            }
            plot_blend(c, cx - r + i, cy - r + j, col, 1.0);
        }
    free(tri);
    /* rings every 30 degrees of zenith angle, the azimuths every 90 */
    for (int k = 1; k <= 3; k++) {
        double rr = r * k / 3.0;
        plot_circle(c, cx + 0.5, cy + 0.5, rr, k == 3 ? 1.5 : 1, k == 3 ? PLOT_BLACK : PLOT_WHITE);
        if (k == 3)
            continue; /* the rim is 90 degrees */
        char buf[24];
        snprintf(buf, sizeof buf, "theta %d\xb0", 30 * k);
        /* inside the ring, beside the line phi = 90 degrees */
        plot_text_halo(c, cx + 6, (int)(cy - rr) + 4, buf, TEXT, PLOT_LEFT);
    }
    for (int k = 0; k < 4; k++) {
        double a = k * PI / 2;
        plot_line(c, cx + 0.5, cy + 0.5, cx + 0.5 + r * cos(a), cy + 0.5 - r * sin(a), 1,
                  PLOT_WHITE, 4);
    }
    const int h = PLOT_TEXT_HEIGHT(TEXT);
    plot_text(c, cx + r + 8, cy - h / 2, "0\xb0", TEXT, PLOT_LEFT, PLOT_BLACK);
    plot_text(c, cx, cy - r - h - 8, "phi 90\xb0", TEXT, PLOT_CENTRE, PLOT_BLACK);
    plot_text(c, cx - r - 8, cy - h / 2, "180\xb0", TEXT, PLOT_RIGHT, PLOT_BLACK);
    plot_text(c, cx, cy + r + 8, "270\xb0", TEXT, PLOT_CENTRE, PLOT_BLACK);
    return 0;
}

void plot_colour_bar(plot_canvas_t *c, int x0, int y0, int x1, int y1, double lo, double hi,
                     int log, const char *label)
{
    for (int y = y0; y < y1; y++) {
        plot_rgb_t col = plot_colour_map((double)(y1 - 1 - y) / (y1 - 1 - y0));
        plot_rect(c, x0, y, x1, y + 1, col);
    }
    plot_line(c, x0, y0, x1, y0, 1, PLOT_BLACK, 0);
    plot_line(c, x0, y1, x1, y1, 1, PLOT_BLACK, 0);
    plot_line(c, x0, y0, x0, y1, 1, PLOT_BLACK, 0);
    plot_line(c, x1, y0, x1, y1, 1, PLOT_BLACK, 0);
    /* its ticks: an axes box of zero width on its right edge */
    plot_axes_t a = {x1, y0, x1, y1, 0, 1, lo, hi, 0, log};
    /* the numbers of a nice range that fall inside [lo, hi] */
    char buf[32];
    int widest = 0;
    for (int pass = 0; pass < 2; pass++) {
        double step = 0;
        int n = 0;
        double v[64];
        if (log) {
            for (int d = (int)floor(log10(lo)); d <= (int)ceil(log10(hi)) && n < 60; d++)
                for (int m = 1; m <= 9 && n < 60; m++) {
                    int decades = (int)ceil(log10(hi) - log10(lo));
                    if (m != 1 && !(decades <= 2 && (m == 2 || m == 5)) &&
                        !(decades <= 1 && (m == 3 || m == 7)))
                        continue;
                    v[n++] = m * pow(10.0, d);
                }
        } else {
            double span = hi - lo, raw = span / 6, p = pow(10.0, floor(log10(raw))), m = raw / p;
            step = (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
            for (double t = ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step && n < 60;
                 t += step)
                v[n++] = fabs(t) < 1e-12 * step ? 0.0 : t;
        }
        for (int k = 0; k < n; k++) {
            if (v[k] < lo - 1e-9 * fabs(lo) || v[k] > hi + 1e-9 * fabs(hi))
                continue;
            double y = plot_py(&a, v[k]);
            plot_number(buf, sizeof buf, v[k]);
            int w = plot_text_width(buf, TEXT);
            if (pass == 0) {
                widest = w > widest ? w : widest;
                continue;
            }
            plot_line(c, x1, y, x1 + 6, y, 1, PLOT_BLACK, 0);
            plot_text(c, x1 + 10, (int)lround(y) - PLOT_TEXT_HEIGHT(TEXT) / 2, buf, TEXT,
                      PLOT_LEFT, PLOT_BLACK);
        }
    }
    if (label)
        plot_text_up(c, x1 + 10 + widest + 14, (y0 + y1) / 2, label, TEXT, PLOT_BLACK);
}
