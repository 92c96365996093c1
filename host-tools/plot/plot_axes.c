/* SPDX-License-Identifier: BSD-2-Clause */
/* Axes, ticks, series and legends (plot.h). */
#include <math.h>
#include <stdio.h>

#include "plot.h"

#define TEXT 2 /* the scale of every number and label */

/* the tick step for about n ticks over span: 1, 2 or 5 times a power of ten */
static double nice_step(double span, int n)
{
    double raw = span / n, p = pow(10.0, floor(log10(raw))), m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

void plot_nice_range(double *lo, double *hi, int log)
{
    if (log) {
        if (!(*lo > 0))
            *lo = *hi > 0 ? *hi / 10 : 1;
        if (!(*hi > *lo))
            *hi = *lo * 10;
        *lo = pow(10.0, floor(log10(*lo) + 1e-9));
        *hi = pow(10.0, ceil(log10(*hi) - 1e-9));
        if (*hi <= *lo)
            *hi = *lo * 10;
        return;
    }
    if (!(*hi > *lo)) {
        double d = *lo != 0 ? fabs(*lo) * 0.1 : 1;
        *lo -= d;
        *hi += d;
    }
    double s = nice_step(*hi - *lo, 5);
    *lo = floor(*lo / s + 1e-9) * s;
    *hi = ceil(*hi / s - 1e-9) * s;
}

static double frac(double v, double lo, double hi, int log)
{
    return log ? (log10(v) - log10(lo)) / (log10(hi) - log10(lo)) : (v - lo) / (hi - lo);
}

double plot_px(const plot_axes_t *a, double x)
{
    return a->x0 + frac(x, a->xmin, a->xmax, a->xlog) * (a->x1 - a->x0);
}

double plot_py(const plot_axes_t *a, double y)
{
    return a->y1 - frac(y, a->ymin, a->ymax, a->ylog) * (a->y1 - a->y0);
}

/* the ticks of one axis: calls tick(value, major) for each in [lo, hi] */
typedef struct {
    double v[64];
    int major[64];
    int n;
} ticks_t;

static void ticks(double lo, double hi, int log, ticks_t *t)
{
    t->n = 0;
    if (log) {
        int d0 = (int)floor(log10(lo) + 1e-9), d1 = (int)ceil(log10(hi) - 1e-9);
        int decades = d1 - d0, every = decades > 12 ? (decades + 5) / 6 : 1;
        for (int d = d0; d <= d1 && t->n < 60; d++) {
            for (int m = 1; m <= 9; m++) {
                double v = m * pow(10.0, d);
                if (v < lo * (1 - 1e-9) || v > hi * (1 + 1e-9))
                    continue;
                int major = m == 1 && (d - d0) % every == 0;
                /* over few decades 2 and 5 are numbered too */
                if ((decades <= 2 && (m == 2 || m == 5)) || (decades <= 1 && (m == 3 || m == 7)))
                    major = 2;
                if (m == 1 || decades <= 6) {
                    t->v[t->n] = v;
                    t->major[t->n++] = major;
                }
            }
        }
        return;
    }
    double s = nice_step(hi - lo, 5);
    for (double v = ceil(lo / s - 1e-9) * s; v <= hi + 1e-9 * s && t->n < 60; v += s) {
        t->v[t->n] = fabs(v) < 1e-12 * s ? 0.0 : v;
        t->major[t->n++] = 1;
    }
}

void plot_axes_draw(plot_canvas_t *c, const plot_axes_t *a, const char *xlabel,
                    const char *ylabel, const char *title)
{
    ticks_t tx, ty;
    ticks(a->xmin, a->xmax, a->xlog, &tx);
    ticks(a->ymin, a->ymax, a->ylog, &ty);
    char buf[32];
    int widest = 0;
    /* grid lines first, under everything */
    for (int k = 0; k < tx.n; k++) {
        double x = plot_px(a, tx.v[k]);
        plot_line(c, x, a->y0, x, a->y1, 1, tx.major[k] ? PLOT_LIGHT : (plot_rgb_t){240, 240, 240},
                  0);
    }
    for (int k = 0; k < ty.n; k++) {
        double y = plot_py(a, ty.v[k]);
        plot_line(c, a->x0, y, a->x1, y, 1, ty.major[k] ? PLOT_LIGHT : (plot_rgb_t){240, 240, 240},
                  0);
    }
    for (int k = 0; k < tx.n; k++) {
        double x = plot_px(a, tx.v[k]);
        plot_line(c, x, a->y1, x, a->y1 + (tx.major[k] ? 6 : 3), 1, PLOT_BLACK, 0);
        if (tx.major[k]) {
            plot_number(buf, sizeof buf, tx.v[k]);
            plot_text(c, (int)lround(x), a->y1 + 10, buf, TEXT, PLOT_CENTRE, PLOT_BLACK);
        }
    }
    for (int k = 0; k < ty.n; k++) {
        double y = plot_py(a, ty.v[k]);
        plot_line(c, a->x0 - (ty.major[k] ? 6 : 3), y, a->x0, y, 1, PLOT_BLACK, 0);
        if (ty.major[k]) {
            plot_number(buf, sizeof buf, ty.v[k]);
            int w = plot_text_width(buf, TEXT);
            widest = w > widest ? w : widest;
            plot_text(c, a->x0 - 10, (int)lround(y) - PLOT_TEXT_HEIGHT(TEXT) / 2, buf, TEXT,
                      PLOT_RIGHT, PLOT_BLACK);
        }
    }
    /* the frame */
    plot_line(c, a->x0, a->y0, a->x1, a->y0, 1.5, PLOT_BLACK, 0);
    plot_line(c, a->x0, a->y1, a->x1, a->y1, 1.5, PLOT_BLACK, 0);
    plot_line(c, a->x0, a->y0, a->x0, a->y1, 1.5, PLOT_BLACK, 0);
    plot_line(c, a->x1, a->y0, a->x1, a->y1, 1.5, PLOT_BLACK, 0);
    if (xlabel)
        plot_text(c, (a->x0 + a->x1) / 2, a->y1 + 10 + PLOT_TEXT_HEIGHT(TEXT) + 12, xlabel, TEXT,
                  PLOT_CENTRE, PLOT_BLACK);
    if (ylabel)
        plot_text_up(c, a->x0 - 10 - widest - 12 - PLOT_TEXT_HEIGHT(TEXT) / 2, (a->y0 + a->y1) / 2,
                     ylabel, TEXT, PLOT_BLACK);
    if (title)
        plot_text(c, (a->x0 + a->x1) / 2, a->y0 - PLOT_TEXT_HEIGHT(TEXT) - 10, title, TEXT,
                  PLOT_CENTRE, PLOT_BLACK);
}

static int usable(const plot_axes_t *a, double x, double y)
{
    return isfinite(x) && isfinite(y) && (!a->xlog || x > 0) && (!a->ylog || y > 0);
}

/* the segment p0 p1 cut to the plotting area (Liang-Barsky); 0 if none */
static int clip(const plot_axes_t *a, double *x0, double *y0, double *x1, double *y1)
{
    double t0 = 0, t1 = 1, dx = *x1 - *x0, dy = *y1 - *y0;
    double p[4] = {-dx, dx, -dy, dy};
    double q[4] = {*x0 - a->x0, a->x1 - *x0, *y0 - a->y0, a->y1 - *y0};
    for (int k = 0; k < 4; k++) {
        if (p[k] == 0) {
            if (q[k] < 0)
                return 0;
            continue;
        }
        double t = q[k] / p[k];
        if (p[k] < 0 && t > t0)
            t0 = t;
        if (p[k] > 0 && t < t1)
            t1 = t;
    }
    if (t0 > t1)
        return 0;
    double ax = *x0, ay = *y0;
    *x0 = ax + t0 * dx;
    *y0 = ay + t0 * dy;
    *x1 = ax + t1 * dx;
    *y1 = ay + t1 * dy;
    return 1;
}

void plot_series(plot_canvas_t *c, const plot_axes_t *a, const double *x, const double *y,
                 size_t n, plot_rgb_t col, double width, double dash, double marker)
{
    for (size_t i = 0; i + 1 < n; i++) {
        if (!usable(a, x[i], y[i]) || !usable(a, x[i + 1], y[i + 1]))
            continue;
        double x0 = plot_px(a, x[i]), y0 = plot_py(a, y[i]);
        double x1 = plot_px(a, x[i + 1]), y1 = plot_py(a, y[i + 1]);
        if (clip(a, &x0, &y0, &x1, &y1))
            plot_line(c, x0, y0, x1, y1, width, col, dash);
    }
    if (marker > 0)
        for (size_t i = 0; i < n; i++) {
            if (!usable(a, x[i], y[i]))
                continue;
            double px = plot_px(a, x[i]), py = plot_py(a, y[i]);
            if (px >= a->x0 - 0.5 && px <= a->x1 + 0.5 && py >= a->y0 - 0.5 && py <= a->y1 + 0.5)
                plot_disc(c, px, py, marker, col);
        }
}

void plot_legend(plot_canvas_t *c, const plot_axes_t *a, const char *const *names,
                 const plot_rgb_t *cols, const double *dashes, size_t n, int corner)
{
    int w = 0, line = PLOT_TEXT_HEIGHT(TEXT) + 8;
    for (size_t k = 0; k < n; k++) {
        int tw = plot_text_width(names[k], TEXT);
        w = tw > w ? tw : w;
    }
    int x1 = a->x1 - 8, x0 = x1 - w - 52, y0 = a->y0 + 8, y1 = y0 + (int)n * line + 8;
    if (corner == PLOT_BOTTOM_LEFT) {
        x0 = a->x0 + 8;
        x1 = x0 + w + 52;
        y1 = a->y1 - 8;
        y0 = y1 - (int)n * line - 8;
    }
    plot_rect(c, x0, y0, x1, y1, PLOT_WHITE);
    plot_line(c, x0, y0, x1, y0, 1, PLOT_GREY, 0);
    plot_line(c, x0, y1, x1, y1, 1, PLOT_GREY, 0);
    plot_line(c, x0, y0, x0, y1, 1, PLOT_GREY, 0);
    plot_line(c, x1, y0, x1, y1, 1, PLOT_GREY, 0);
    for (size_t k = 0; k < n; k++) {
        int y = y0 + 8 + (int)k * line;
        double ym = y + PLOT_TEXT_HEIGHT(TEXT) / 2.0;
        plot_line(c, x0 + 8, ym, x0 + 40, ym, 2.5, cols[k], dashes ? dashes[k] : 0);
        plot_text(c, x0 + 46, y, names[k], TEXT, PLOT_LEFT, PLOT_BLACK);
    }
}
