/* SPDX-License-Identifier: BSD-2-Clause */
/* The canvas, its shapes and the colour map (plot.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwh_error.h"
#include "plot.h"
#include "render_png.h"

#define PI 3.14159265358979323846

int plot_canvas_init(plot_canvas_t *c, unsigned w, unsigned h)
{
    c->w = w;
    c->h = h;
    c->rgb = malloc((size_t)w * h * 3);
    if (!c->rgb)
        return bwh_fail("out of memory");
    memset(c->rgb, 255, (size_t)w * h * 3);
    return 0;
}

void plot_canvas_free(plot_canvas_t *c)
{
    free(c->rgb);
    c->rgb = NULL;
}

int plot_canvas_png(const plot_canvas_t *c, const char *path)
{
    return render_png_write(path, c->rgb, c->w, c->h);
}

void plot_blend(plot_canvas_t *c, int x, int y, plot_rgb_t col, double alpha)
{
    if (x < 0 || y < 0 || x >= (int)c->w || y >= (int)c->h || !(alpha > 0.0))
        return;
    if (alpha > 1.0)
        alpha = 1.0;
    uint8_t *p = c->rgb + 3 * ((size_t)y * c->w + (size_t)x);
    const uint8_t to[3] = {col.r, col.g, col.b};
    for (int k = 0; k < 3; k++)
        p[k] = (uint8_t)lround(p[k] + alpha * ((double)to[k] - p[k]));
}

void plot_rect(plot_canvas_t *c, int x0, int y0, int x1, int y1, plot_rgb_t col)
{
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            plot_blend(c, x, y, col, 1.0);
}

/* one straight piece of a line, anti-aliased by the distance of each
 * pixel's centre from the segment */
static void segment(plot_canvas_t *c, double x0, double y0, double x1, double y1, double width,
                    plot_rgb_t col)
{
    double hw = 0.5 * width;
    int bx0 = (int)floor(fmin(x0, x1) - hw - 1), bx1 = (int)ceil(fmax(x0, x1) + hw + 1);
    int by0 = (int)floor(fmin(y0, y1) - hw - 1), by1 = (int)ceil(fmax(y0, y1) + hw + 1);
    double dx = x1 - x0, dy = y1 - y0, len2 = dx * dx + dy * dy;
    for (int y = by0 < 0 ? 0 : by0; y <= by1 && y < (int)c->h; y++)
        for (int x = bx0 < 0 ? 0 : bx0; x <= bx1 && x < (int)c->w; x++) {
            double px = x + 0.5 - x0, py = y + 0.5 - y0;
            double t = len2 > 0 ? (px * dx + py * dy) / len2 : 0.0;
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            double ex = px - t * dx, ey = py - t * dy;
            double d = sqrt(ex * ex + ey * ey);
            double cover = hw + 0.5 - d;
            if (cover > 0)
                plot_blend(c, x, y, col, cover);
        }
}

void plot_line(plot_canvas_t *c, double x0, double y0, double x1, double y1, double width,
               plot_rgb_t col, double dash)
{
    if (!isfinite(x0) || !isfinite(y0) || !isfinite(x1) || !isfinite(y1))
        return;
    double len = hypot(x1 - x0, y1 - y0);
    if (!(dash > 0) || len <= dash) {
        segment(c, x0, y0, x1, y1, width, col);
        return;
    }
    for (double s = 0; s < len; s += 2 * dash) {
        double e = s + dash < len ? s + dash : len;
        segment(c, x0 + (x1 - x0) * s / len, y0 + (y1 - y0) * s / len, x0 + (x1 - x0) * e / len,
                y0 + (y1 - y0) * e / len, width, col);
    }
}

void plot_circle(plot_canvas_t *c, double cx, double cy, double r, double width, plot_rgb_t col)
{
    int n = (int)(2 * PI * r / 3) + 16;
    for (int k = 0; k < n; k++) {
        double a0 = 2 * PI * k / n, a1 = 2 * PI * (k + 1) / n;
        segment(c, cx + r * cos(a0), cy + r * sin(a0), cx + r * cos(a1), cy + r * sin(a1), width,
                col);
    }
}

void plot_disc(plot_canvas_t *c, double cx, double cy, double r, plot_rgb_t col)
{
    for (int y = (int)floor(cy - r - 1); y <= (int)ceil(cy + r + 1); y++)
        for (int x = (int)floor(cx - r - 1); x <= (int)ceil(cx + r + 1); x++) {
            double d = hypot(x + 0.5 - cx, y + 0.5 - cy);
            plot_blend(c, x, y, col, r + 0.5 - d);
        }
}

plot_rgb_t plot_series_colour(unsigned k)
{
    /* Okabe and Ito's colours: blue, vermillion, bluish green, reddish
     * purple, orange, sky blue */
    static const plot_rgb_t set[] = {{0, 114, 178},  {213, 94, 0},    {0, 158, 115},
                                     {204, 121, 167}, {230, 159, 0}, {86, 180, 233}};
    return set[k % (sizeof set / sizeof *set)];
}

plot_rgb_t plot_colour_map(double t)
{
    /* viridis at nine points, linearly between them */
    static const uint8_t v[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                    {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                    {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
    if (!(t > 0))
        t = 0;
    if (t > 1)
        t = 1;
    double f = t * 8;
    int i = (int)f;
    if (i > 7)
        i = 7;
    f -= i;
    plot_rgb_t o;
    o.r = (uint8_t)lround(v[i][0] + f * (v[i + 1][0] - v[i][0]));
    o.g = (uint8_t)lround(v[i][1] + f * (v[i + 1][1] - v[i][1]));
    o.b = (uint8_t)lround(v[i][2] + f * (v[i + 1][2] - v[i][2]));
    return o;
}
