/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * Pictures of measurements for `brdfwave plot`: an RGB canvas with
 * anti-aliased lines, a built-in 5 x 7 bitmap font, axes with ticks
 * (linear or logarithmic), a viridis-like colour map, the hemisphere of
 * geodesic triangles in polar projection, and the PNG writer of the
 * renderer (render_png.h).
 *
 * Coordinates are pixels, x to the right and y down, (0, 0) the top left
 * corner; a pixel's centre is at (x + 0.5, y + 0.5).
 */
#ifndef PLOT_H
#define PLOT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    uint8_t r, g, b;
} plot_rgb_t;

#define PLOT_BLACK ((plot_rgb_t){0, 0, 0})
#define PLOT_WHITE ((plot_rgb_t){255, 255, 255})
#define PLOT_GREY ((plot_rgb_t){128, 128, 128})
#define PLOT_LIGHT ((plot_rgb_t){225, 225, 225})

/* the colours of series 0, 1, 2, ... (a colour-blind safe set) */
plot_rgb_t plot_series_colour(unsigned k);

/* ---- the canvas ---------------------------------------------------------- */

typedef struct {
    unsigned w, h;
    uint8_t *rgb; /* h rows of w * 3 bytes */
} plot_canvas_t;

/* a white canvas; 0, or -1 (bwh_last_error()) */
int plot_canvas_init(plot_canvas_t *c, unsigned w, unsigned h);
void plot_canvas_free(plot_canvas_t *c);
/* writes the canvas as an 8-bit RGB PNG; 0, or -1 */
int plot_canvas_png(const plot_canvas_t *c, const char *path);

/* pixel (x, y) blended towards col by alpha 0..1 (outside: nothing) */
void plot_blend(plot_canvas_t *c, int x, int y, plot_rgb_t col, double alpha);
/* the pixels [x0, x1) x [y0, y1) */
void plot_rect(plot_canvas_t *c, int x0, int y0, int x1, int y1, plot_rgb_t col);
/* an anti-aliased line of the given width; dash > 0: dashes and gaps of
 * that length */
void plot_line(plot_canvas_t *c, double x0, double y0, double x1, double y1, double width,
               plot_rgb_t col, double dash);
/* a circle's outline (centre, radius) and a filled disc */
void plot_circle(plot_canvas_t *c, double cx, double cy, double r, double width, plot_rgb_t col);
void plot_disc(plot_canvas_t *c, double cx, double cy, double r, plot_rgb_t col);

/* ---- text ---------------------------------------------------------------- */

/* The font: printable ASCII and '\xb0' (degree), 5 x 7 pixels in cells of
 * 6 x 9, each pixel drawn as scale x scale. */
enum { PLOT_LEFT = 0, PLOT_CENTRE = 1, PLOT_RIGHT = 2 };
/* width in pixels of s at scale */
int plot_text_width(const char *s, int scale);
#define PLOT_TEXT_HEIGHT(scale) (7 * (scale))
/* s with its top at y, its left edge, centre or right edge at x (align) */
void plot_text(plot_canvas_t *c, int x, int y, const char *s, int scale, int align,
               plot_rgb_t col);
/* white text with a dark outline, readable on any colour */
void plot_text_halo(plot_canvas_t *c, int x, int y, const char *s, int scale, int align);
/* text turned 90 degrees counter-clockwise (reading upwards), its centre
 * at (x, y) */
void plot_text_up(plot_canvas_t *c, int x, int y, const char *s, int scale, plot_rgb_t col);

/* a number for a tick or a legend: the shortest of %g-like forms, with an
 * exponent as "1e-05" */
void plot_number(char *buf, size_t cap, double v);

/* ---- colour map ---------------------------------------------------------- */

/* t in [0, 1] (clamped) to a perceptually uniform map from dark violet
 * through blue and green to yellow */
plot_rgb_t plot_colour_map(double t);

/* ---- axes ---------------------------------------------------------------- */

typedef struct {
    int x0, y0, x1, y1;        /* the plotting area's pixels: [x0, x1) x [y0, y1) */
    double xmin, xmax, ymin, ymax;
    int xlog, ylog;            /* logarithmic axes (limits > 0) */
} plot_axes_t;

/* the axes' limits from data: [lo, hi] widened to nice tick values (log:
 * to decades); a constant range is widened around it */
void plot_nice_range(double *lo, double *hi, int log);

/* pixel of a data coordinate */
double plot_px(const plot_axes_t *a, double x);
double plot_py(const plot_axes_t *a, double y);

/* the frame, grid lines, ticks and their numbers, the axis labels and a
 * title above */
void plot_axes_draw(plot_canvas_t *c, const plot_axes_t *a, const char *xlabel,
                    const char *ylabel, const char *title);

/* a polyline through (x[i], y[i]) (points that are not finite, or not > 0
 * on a log axis, break it); marker > 0: a dot of that radius at each point.
 * Drawn inside the plotting area only. */
void plot_series(plot_canvas_t *c, const plot_axes_t *a, const double *x, const double *y,
                 size_t n, plot_rgb_t col, double width, double dash, double marker);

/* a legend of n entries in a corner of the plotting area: PLOT_TOP_RIGHT
 * or PLOT_BOTTOM_LEFT */
enum { PLOT_TOP_RIGHT = 0, PLOT_BOTTOM_LEFT = 1 };
void plot_legend(plot_canvas_t *c, const plot_axes_t *a, const char *const *names,
                 const plot_rgb_t *cols, const double *dashes, size_t n, int corner);

/* ---- the hemisphere ------------------------------------------------------ */

/* Values per triangle of a geodesic level (4 * 4^level of them, in grid
 * order) as a disc: polar projection of the hemisphere seen from above,
 * the normal at the centre (cx, cy), the zenith angle theta growing
 * linearly to 90 degrees at radius r, the azimuth phi counter-clockwise
 * from +x (to the right; +y upwards). Each pixel takes the colour of the
 * triangle holding its direction (bwh_grid_locate), value v at
 * (v - lo) / (hi - lo) of the colour map (log: of log v, values <= 0 as
 * lo); edges: the triangles' outlines. Rings at 30, 60 and 90 degrees and
 * the azimuths 0, 90, 180, 270 labelled. 0, or -1 (out of memory). */
int plot_hemisphere(plot_canvas_t *c, int cx, int cy, int r, unsigned level,
                    const double *values, double lo, double hi, int log, int edges);

/* a direction (unit vector, z >= 0) on that disc: its pixel */
void plot_hemisphere_xy(int cx, int cy, int r, const double d[3], double *x, double *y);

/* a vertical colour bar [x0, x1) x [y0, y1) for lo .. hi (log), with
 * ticks on its right and a label */
void plot_colour_bar(plot_canvas_t *c, int x0, int y0, int x1, int y1, double lo, double hi,
                     int log, const char *label);

#ifdef __cplusplus
}
#endif

#endif
