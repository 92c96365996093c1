/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * CSV, both ways. Lines "# key: value" before the table carry the metadata
 * (the keys of the metadata's JSON, each value in JSON); then a title row
 * and the rows, comma separated (a title with a comma or a quote in
 * double quotes).
 *
 *   spectra      wavelength_nm (or _um, wavenumber_cm-1, band), then one
 *                column per spectrum titled by its name; a row per band
 *   directional  [theta_in_deg, [phi_in_deg,]] theta_deg, phi_deg, then one
 *                column per band titled by its name or wavelength; a row per
 *                direction. Directions that are the grid's centres of a
 *                level, in grid order, are taken as they are; others are
 *                projected onto the grid (bwh_project.h), for each incidence.
 *
 * Values with at most 6 decimals and no exponent are read exactly, as
 * integers of 10^-k; others as float32. Written values are the shortest
 * decimals that read back as the same float32.
 */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "bwh_error.h"
#include "bwh_file.h"
#include "bwh_input.h"
#include "bwh_output.h"
#include "bwh_project.h"
#include "bwh_text.h"
#include "geodesic.h"

#define CSV_MAX_COLS 65536
#define RAD2DEG (180.0 / 3.14159265358979323846)

/* ---- writing ------------------------------------------------------------- */

typedef struct {
    char *b;
    size_t n, cap;
    int oom;
} obuf_t;

static void out(obuf_t *o, const char *s, size_t n)
{
    if (o->oom)
        return;
    if (o->n + n + 1 > o->cap) {
        size_t c = o->cap ? o->cap : 65536;
        while (c < o->n + n + 1)
            c *= 2;
        char *nb = realloc(o->b, c);
        if (!nb) {
            o->oom = 1;
            return;
        }
        o->b = nb;
        o->cap = c;
    }
    memcpy(o->b + o->n, s, n);
    o->n += n;
    o->b[o->n] = 0; /* the JSON of the '# key: value' lines is read as a string */
}

static void outs(obuf_t *o, const char *s) { out(o, s, strlen(s)); }

/* the shortest decimal that reads back as the float32 v */
static void float_text(float v, char *b, size_t cap)
{
    if (!isfinite(v)) {
        snprintf(b, cap, "%s", isnan(v) ? "nan" : v > 0 ? "inf" : "-inf");
        return;
    }
    for (int p = 1; p <= 9; p++) {
        snprintf(b, cap, "%.*g", p, (double)v);
        if (strtof(b, NULL) == v)
            return;
    }
}

static void title(obuf_t *o, const char *s)
{
    if (!strpbrk(s, ",\"\n\r")) {
        outs(o, s);
        return;
    }
    outs(o, "\"");
    for (; *s; s++)
        if (*s == '"')
            outs(o, "\"\"");
        else
            out(o, s, 1);
    outs(o, "\"");
}

/* "# key: value" lines from the metadata's JSON, one per key, without skip */
static int meta_lines(obuf_t *o, const bwh_meta_t *m, int shape, const char *const *skip)
{
    bwh_meta_t c;
    if (bwh_meta_copy(&c, m) != 0)
        return -1;
    for (const char *const *k = skip; *k; k++) {
        if (!strcmp(*k, "wavelengths"))
            bwh_meta_set_numbers(&c.wavelengths, NULL, 0);
        else if (!strcmp(*k, "spectrum_names"))
            bwh_meta_set_strings(&c.spectrum_names, NULL, 0);
    }
    char *j;
    int rc = bwh_meta_to_json_layout(&c, shape, &j);
    bwh_meta_free(&c);
    if (rc)
        return -1;
    /* the object's top-level members, one per line */
    const char *p = j + 1;
    int depth = 0, str = 0;
    const char *start = p;
    for (; *p; p++) {
        if (str) {
            if (*p == '\\')
                p++;
            else if (*p == '"')
                str = 0;
            continue;
        }
        if (*p == '"')
            str = 1;
        else if (*p == '[' || *p == '{')
            depth++;
        else if ((*p == ']' || *p == '}') && depth)
            depth--;
        else if ((*p == ',' || *p == '}') && !depth) {
            /* "key": value -> # key: value */
            const char *q = start;
            while (*q == ' ')
                q++;
            if (*q == '"') {
                const char *ke = strchr(q + 1, '"');
                outs(o, "# ");
                out(o, q + 1, (size_t)(ke - q - 1));
                outs(o, ":");
                out(o, ke + 2, (size_t)(p - ke - 2));
                outs(o, "\n");
            }
            start = p + 1;
        }
    }
    free(j);
    return 0;
}

int bwh_csv_write(const char *path, const bwh_decoded_t *d)
{
    const bw_dims_t *g = &d->dims;
    const bwh_meta_t *m = d->meta;
    bwh_meta_t none;
    bwh_meta_init(&none);
    if (!m)
        m = &none;
    obuf_t o = {0};
    size_t bands = g->bands;
    char b[64];
    if (g->shape == BW_SHAPE_SPECTRA) {
        static const char *const skip[] = {"wavelengths", "spectrum_names", NULL};
        if (meta_lines(&o, m, g->shape, skip))
            return -1;
        static const char *const wl_titles[] = {"wavelength_nm", "wavelength_um",
                                                "wavenumber_cm-1"};
        outs(&o, m->wavelengths.n ? wl_titles[m->wl_unit] : "band");
        for (size_t s = 0; s < g->n_in; s++) {
            outs(&o, ",");
            if (m->spectrum_names.n) {
                title(&o, m->spectrum_names.s[s]);
            } else {
                snprintf(b, sizeof b, "spectrum_%zu", s);
                outs(&o, b);
            }
        }
        outs(&o, "\n");
        for (size_t k = 0; k < bands; k++) {
            if (m->wavelengths.n)
                bwh_json_number(m->wavelengths.v[k], b, sizeof b);
            else
                snprintf(b, sizeof b, "%zu", k);
            outs(&o, b);
            for (size_t s = 0; s < g->n_in; s++) {
                float_text(d->values[s * bands + k], b, sizeof b);
                outs(&o, ",");
                outs(&o, b);
            }
            outs(&o, "\n");
        }
    } else {
        static const char *const skip[] = {NULL};
        if (meta_lines(&o, m, g->shape, skip))
            return -1;
        size_t n_out = g->n_out, n_in = g->shape == BW_SHAPE_REFLECTANCE ? 1 : g->n_in;
        double(*wo)[3] = malloc(n_out * sizeof *wo), (*wi)[3] = NULL;
        if (!wo || bwh_grid_centres(g->level_out, wo, NULL) != 0 ||
            (g->shape == BW_SHAPE_BRDF_FULL &&
             (!(wi = malloc(n_in * sizeof *wi)) || bwh_grid_centres(g->level_in, wi, NULL) != 0))) {
            free(wo);
            free(wi);
            free(o.b);
            return bwh_fail("out of memory");
        }
        if (g->shape == BW_SHAPE_BRDF_ISO)
            outs(&o, "theta_in_deg,");
        else if (g->shape == BW_SHAPE_BRDF_FULL)
            outs(&o, "theta_in_deg,phi_in_deg,");
        outs(&o, "theta_deg,phi_deg");
        for (size_t k = 0; k < bands; k++) {
            outs(&o, ",");
            if (m->band_names.n) {
                title(&o, m->band_names.s[k]);
            } else if (m->wavelengths.n) {
                bwh_json_number(m->wavelengths.v[k], b, sizeof b);
                outs(&o, b);
            } else {
                snprintf(b, sizeof b, "band_%zu", k);
                outs(&o, b);
            }
        }
        outs(&o, "\n");
        for (size_t i = 0; i < n_in; i++)
            for (size_t r = 0; r < n_out; r++) {
                double a[4];
                int na = 0;
                if (g->shape == BW_SHAPE_BRDF_ISO) {
                    double t = m->incidence.n ? m->incidence.v[i] : (i + 0.5) * 90.0 / (double)n_in;
                    a[na++] = m->incidence.n && m->inc_unit == BWH_ANGLE_RAD ? t * RAD2DEG : t;
                } else if (g->shape == BW_SHAPE_BRDF_FULL) {
                    a[na++] = acos(fmin(1.0, fmax(-1.0, wi[i][2]))) * RAD2DEG;
                    double p = atan2(wi[i][1], wi[i][0]) * RAD2DEG;
                    a[na++] = p < 0 ? p + 360.0 : p;
                }
                a[na++] = acos(fmin(1.0, fmax(-1.0, wo[r][2]))) * RAD2DEG;
                double p = atan2(wo[r][1], wo[r][0]) * RAD2DEG;
                a[na++] = p < 0 ? p + 360.0 : p;
                for (int k = 0; k < na; k++) {
                    if (a[k] >= 360.0)
                        a[k] = 0.0;
                    bwh_json_number(a[k] + 0.0, b, sizeof b);
                    if (k)
                        outs(&o, ",");
                    outs(&o, b);
                }
                for (size_t k = 0; k < bands; k++) {
                    float_text(d->values[(i * n_out + r) * bands + k], b, sizeof b);
                    outs(&o, ",");
                    outs(&o, b);
                }
                outs(&o, "\n");
            }
        free(wo);
        free(wi);
    }
    if (o.oom) {
        free(o.b);
        return bwh_fail("out of memory");
    }
    int rc = bwh_write_file(path, o.b, o.n);
    free(o.b);
    return rc;
}

/* ---- reading ------------------------------------------------------------- */

/* splits line at commas (quoted fields kept whole, quotes removed), in
 * place; the count, or -1 beyond cap */
static long split(char *line, char **f, size_t cap)
{
    size_t n = 0;
    char *p = line;
    for (;;) {
        if (n == cap)
            return -1;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '"') {
            char *w = ++p;
            f[n++] = w;
            while (*p) {
                if (*p == '"' && p[1] == '"') {
                    *w++ = '"';
                    p += 2;
                } else if (*p == '"') {
                    p++;
                    break;
                } else {
                    *w++ = *p++;
                }
            }
            char *rest = p;
            *w = 0;
            p = strchr(rest, ',');
            if (!p)
                return (long)n;
            p++;
            continue;
        }
        f[n++] = p;
        char *c = strchr(p, ',');
        if (!c) {
            bwh_trim(p);
            return (long)n;
        }
        *c = 0;
        bwh_trim(p);
        p = c + 1;
    }
}

/* a decimal without exponent: its digits after the point, else -1 */
static int decimals_of(const char *s)
{
    const char *p = s;
    if (*p == '-' || *p == '+')
        p++;
    int dig = 0, frac = -1;
    for (; *p; p++) {
        if (isdigit((unsigned char)*p)) {
            dig++;
            if (frac >= 0)
                frac++;
        } else if (*p == '.' && frac < 0) {
            frac = 0;
        } else {
            return -1;
        }
    }
    return dig ? (frac < 0 ? 0 : frac) : -1;
}

static int parse_num(const char *s, double *x)
{
    char *e;
    errno = 0;
    *x = strtod(s, &e);
    return e == s || *e || errno == ERANGE ? -1 : 0;
}

/* the grid level whose centres, in order, are the directions (theta, phi
 * in degrees) of n rows; -1 if none */
static int grid_level_of(const double *theta, const double *phi, size_t n)
{
    for (unsigned l = 0; l <= BW_MAX_LEVEL; l++) {
        if (bwh_grid_count(l) != n)
            continue;
        double(*c)[3] = malloc(n * sizeof *c);
        if (!c || bwh_grid_centres(l, c, NULL) != 0) {
            free(c);
            return -1;
        }
        size_t i;
        for (i = 0; i < n; i++) {
            double t = acos(fmin(1.0, fmax(-1.0, c[i][2]))) * RAD2DEG;
            double p = atan2(c[i][1], c[i][0]) * RAD2DEG;
            if (p < 0)
                p += 360.0;
            if (p >= 360.0)
                p = 0.0;
            double dp = fabs(p - phi[i]);
            if (fabs(t - theta[i]) > 1e-6 || (fmin(dp, 360.0 - dp) > 1e-6 && t > 1e-6))
                break;
        }
        free(c);
        return i == n ? (int)l : -1;
    }
    return -1;
}

static void dir_of(double theta_deg, double phi_deg, double d[3])
{
    double t = theta_deg / RAD2DEG, p = phi_deg / RAD2DEG;
    d[0] = sin(t) * cos(p);
    d[1] = sin(t) * sin(p);
    d[2] = cos(t);
}

int bwh_read_csv(const char *path, const bwh_read_opts_t *o, bwh_measure_t *m)
{
    bwh_measure_init(m);
    bwh_text_t t;
    if (bwh_text_open(&t, path) != 0)
        return -1;
    char *line, **f = malloc(CSV_MAX_COLS * sizeof *f);
    double *num = NULL;
    char *json = NULL;
    size_t jn = 0;
    int rc = -1;
    obuf_t js = {0};
    if (!f) {
        bwh_fail("out of memory");
        goto out;
    }
    outs(&js, "{");
    /* metadata lines, then the titles */
    while ((line = bwh_text_line(&t))) {
        if (line[0] == '#') {
            static const char *const keys[] = {
                "shape", "quantity", "unit", "sample_type", "wavelength_unit", "wavelengths",
                "fwhm", "band_names", "incidence_unit", "incidence", "instrument", "serial",
                "time", "location", "spectrum_names", "spectrum_times", "spectrum_locations",
                "missing", "fields", NULL};
            char *c = strchr(line, ':');
            if (!c)
                continue;
            *c = 0;
            char *k = bwh_trim(line + 1);
            int known = 0;
            for (int i = 0; keys[i] && !known; i++)
                known = !strcmp(k, keys[i]);
            if (known) { /* other comments are the file's own */
                if (jn++)
                    outs(&js, ", ");
                outs(&js, "\"");
                outs(&js, k);
                outs(&js, "\": ");
                outs(&js, c + 1);
            }
            continue;
        }
        if (*bwh_trim(line))
            break;
    }
    outs(&js, "}");
    if (!line) {
        bwh_fail("%s: no title row: an empty CSV file", path);
        goto out;
    }
    int layout = -1;
    if (js.oom || bwh_meta_from_json_layout(js.b, &m->meta, &layout) != 0) {
        bwh_fail("%s: the '# key: value' lines: %s", path, bwh_last_error());
        goto out;
    }
    long nc = split(line, f, CSV_MAX_COLS);
    if (nc < 2) {
        bwh_fail("%s:%u: %s", path, t.line,
                 nc < 0 ? "more than 65536 columns" : "a title row of at least 2 columns");
        goto out;
    }
    char **titles = malloc((size_t)nc * sizeof *titles);
    if (!titles) {
        bwh_fail("out of memory");
        goto out;
    }
    for (long i = 0; i < nc; i++)
        titles[i] = f[i];
    /* which layout */
    int angles = 0, spectra = 0;
    static const char *const dirs[] = {"theta_in_deg", "phi_in_deg", "theta_deg", "phi_deg"};
    int has[4] = {0, 0, 0, 0};
    for (long i = 0; i < nc && i < 4; i++)
        for (int k = 0; k < 4; k++)
            if (!strcasecmp(titles[i], dirs[k]) && i == angles) {
                has[k] = 1;
                angles++;
            }
    int wl_unit = -1;
    if (!angles) {
        if (!strncasecmp(titles[0], "wavelength", 10) || !strcasecmp(titles[0], "band") ||
            !strncasecmp(titles[0], "wavenumber", 10)) {
            spectra = 1;
            const char *u = strrchr(titles[0], '_');
            wl_unit = !strcasecmp(titles[0], "band") ? -1
                      : u ? bwh_wl_unit_from_name(u + 1) : BWH_WL_NM;
            if (wl_unit < 0 && strcasecmp(titles[0], "band") &&
                !strncasecmp(titles[0], "wavenumber", 10))
                wl_unit = BWH_WL_WAVENUMBER;
            if (wl_unit < 0 && strcasecmp(titles[0], "band"))
                wl_unit = BWH_WL_NM;
        } else {
            free(titles);
            bwh_fail("%s:%u: the first title is neither a wavelength column (wavelength_nm, "
                     "wavelength_um, wavenumber_cm-1, band) nor an angle column (theta_in_deg, "
                     "theta_deg)",
                     path, t.line);
            goto out;
        }
    } else if (!has[2] || !has[3] || (has[1] && !has[0]) || nc <= angles) {
        free(titles);
        bwh_fail("%s:%u: directional data needs theta_deg and phi_deg (after theta_in_deg and "
                 "phi_in_deg, if any) and at least one value column",
                 path, t.line);
        goto out;
    }
    /* the rows: numbers, every one of them */
    size_t cols = (size_t)nc, rows = 0, cap = 0;
    int max_dec = 0, exact = 1;
    unsigned title_line = t.line;
    while ((line = bwh_text_line(&t))) {
        if (!*bwh_trim(line) || line[0] == '#')
            continue;
        long k = split(line, f, CSV_MAX_COLS);
        if (k != nc) {
            free(titles);
            bwh_fail("%s:%u: %ld columns, the titles have %ld%s", path, t.line, k, nc,
                     t.last_cut ? " (the file is cut short)" : "");
            goto out;
        }
        if (rows == cap) {
            cap = cap ? cap * 2 : 1024;
            double *nn = cap * cols <= BW_MAX_SAMPLES ? realloc(num, cap * cols * sizeof *nn) : NULL;
            if (!nn) {
                free(titles);
                bwh_fail("%s: too many values (out of memory)", path);
                goto out;
            }
            num = nn;
        }
        for (size_t c = 0; c < cols; c++) {
            if (parse_num(f[c], &num[rows * cols + c]) != 0 || !isfinite(num[rows * cols + c])) {
                bwh_fail("%s:%u: column %zu ('%s') is not a finite number: '%s'%s", path, t.line,
                         c + 1, titles[c], f[c], t.last_cut ? " (the file is cut short)" : "");
                free(titles);
                goto out;
            }
            if (c >= (size_t)(spectra ? 1 : angles)) {
                int dd = decimals_of(f[c]);
                if (dd < 0 || dd > 6)
                    exact = 0;
                else if (dd > max_dec)
                    max_dec = dd;
            }
        }
        rows++;
    }
    if (!rows) {
        free(titles);
        bwh_fail("%s:%u: no rows after the titles", path, title_line);
        goto out;
    }
    size_t first = spectra ? 1 : (size_t)angles, nv = cols - first;
    double sc = pow(10.0, -max_dec);
    for (size_t r = 0; exact && r < rows; r++)
        for (size_t c = first; c < cols; c++)
            if (fabs(nearbyint(num[r * cols + c] / sc)) > BW_SAMPLE_MAX)
                exact = 0;
    int st_given = (m->meta.present & BWH_M_SAMPLE_TYPE) != 0;
    if (spectra) {
        /* [spectrum][band]: the table transposed */
        size_t n = nv * rows;
        if (exact)
            m->ints = malloc(n * sizeof *m->ints);
        else
            m->values = malloc(n * sizeof *m->values);
        double *wl = malloc(rows * sizeof *wl);
        if ((!m->ints && !m->values) || !wl) {
            free(wl);
            free(titles);
            bwh_fail("out of memory");
            goto out;
        }
        for (size_t r = 0; r < rows; r++) {
            wl[r] = num[r * cols];
            for (size_t s = 0; s < nv; s++) {
                double x = num[r * cols + 1 + s];
                if (exact)
                    m->ints[s * rows + r] = (int32_t)nearbyint(x / sc);
                else
                    m->values[s * rows + r] = (float)x;
            }
        }
        int bad = 0;
        if (wl_unit >= 0) {
            m->meta.wl_unit = wl_unit;
            bad = bwh_meta_set_numbers(&m->meta.wavelengths, wl, rows);
        }
        free(wl);
        /* titles spectrum_0, spectrum_1, ... are bwh_csv_write's for
         * spectra without names */
        int unnamed = 1;
        for (size_t s = 0; s < nv && unnamed; s++) {
            char b[32];
            snprintf(b, sizeof b, "spectrum_%zu", s);
            unnamed = !strcmp(titles[1 + s], b);
        }
        if (!bad && !m->meta.spectrum_names.n && !unnamed)
            bad = bwh_meta_set_strings(&m->meta.spectrum_names, (const char *const *)titles + 1, nv);
        if (bad) {
            free(titles);
            goto out;
        }
        m->shape = BW_SHAPE_SPECTRA;
        m->n_in = (uint32_t)nv;
        m->bands = (uint32_t)rows;
        m->count = n;
    } else {
        /* groups of rows with the same incidence, in order */
        int iso = has[0] && !has[1], full = has[1];
        size_t groups = 0, *start = malloc((rows + 1) * sizeof *start);
        double *inc = malloc(rows * sizeof *inc);
        if (!start || !inc) {
            free(start);
            free(inc);
            free(titles);
            bwh_fail("out of memory");
            goto out;
        }
        for (size_t r = 0; r < rows; r++) {
            double ti = has[0] ? num[r * cols] : 0, pi = full ? num[r * cols + 1] : 0;
            if (!r || ti != num[(r - 1) * cols] || (full && pi != num[(r - 1) * cols + 1])) {
                for (size_t g = 0; g < groups && iso; g++)
                    if (inc[g] == ti) {
                        free(start);
                        free(inc);
                        free(titles);
                        bwh_fail("%s:%u: the rows of incidence %g come in two runs: keep each "
                                 "incidence's rows together",
                                 path, title_line + (unsigned)r + 1, ti);
                        goto out;
                    }
                inc[groups] = ti;
                start[groups++] = r;
            }
        }
        start[groups] = rows;
        size_t a0 = (size_t)(has[0] + has[1]);
        /* the outgoing directions: the grid's, or projected onto it */
        int level = -1;
        size_t per = start[1] - start[0];
        int on_grid = 1;
        double *th = malloc(rows * sizeof *th), *ph = malloc(rows * sizeof *ph);
        for (size_t g = 0; th && ph && g < groups; g++) {
            size_t n = start[g + 1] - start[g];
            for (size_t r = 0; r < n; r++) {
                th[r] = num[(start[g] + r) * cols + a0];
                ph[r] = num[(start[g] + r) * cols + a0 + 1];
            }
            int l = n == per ? grid_level_of(th, ph, n) : -1;
            if (l < 0 || (level >= 0 && l != level))
                on_grid = 0;
            level = l;
        }
        if (!th || !ph) {
            free(th);
            free(ph);
            free(start);
            free(inc);
            free(titles);
            bwh_fail("out of memory");
            goto out;
        }
        if (full && !on_grid) {
            free(th);
            free(ph);
            free(start);
            free(inc);
            free(titles);
            bwh_fail("%s: a full BRDF's outgoing directions must be a grid level's centres in "
                     "grid order (theta_deg, phi_deg as 'brdfwave grid' gives them)",
                     path);
            goto out;
        }
        unsigned lo = on_grid ? (unsigned)level : (o->level >= 0 ? (unsigned)o->level : 4u);
        size_t n_out = bwh_grid_count(lo), n_in = groups;
        if (!has[0] && groups != 1) {
            free(th);
            free(ph);
            free(start);
            free(inc);
            free(titles);
            bwh_fail("%s: directions repeat without an incidence column", path);
            goto out;
        }
        if (on_grid && exact) {
            m->ints = malloc(n_in * n_out * nv * sizeof *m->ints);
        } else {
            exact = 0;
            m->values = malloc(n_in * n_out * nv * sizeof *m->values);
        }
        int bad = !m->ints && !m->values;
        for (size_t g = 0; !bad && g < groups; g++) {
            size_t n = start[g + 1] - start[g];
            if (on_grid) {
                for (size_t r = 0; r < n; r++)
                    for (size_t k = 0; k < nv; k++) {
                        double x = num[(start[g] + r) * cols + first + k];
                        size_t idx = (g * n_out + r) * nv + k;
                        if (exact)
                            m->ints[idx] = (int32_t)nearbyint(x / sc);
                        else
                            m->values[idx] = (float)x;
                    }
                continue;
            }
            double(*dir)[3] = malloc(n * sizeof *dir), *val = malloc(n * nv * sizeof *val),
                   *res = malloc(n_out * nv * sizeof *res);
            bad = !dir || !val || !res;
            for (size_t r = 0; !bad && r < n; r++) {
                dir_of(num[(start[g] + r) * cols + a0], num[(start[g] + r) * cols + a0 + 1], dir[r]);
                for (size_t k = 0; k < nv; k++)
                    val[r * nv + k] = num[(start[g] + r) * cols + first + k];
            }
            if (!bad && bwh_project(dir, val, n, nv, lo, res) != 0) {
                bwh_fail("%s: incidence %g: %s", path, inc[g], bwh_last_error());
                bad = 2;
            }
            for (size_t i = 0; !bad && i < n_out * nv; i++)
                m->values[g * n_out * nv + i] = (float)res[i];
            free(dir);
            free(val);
            free(res);
        }
        free(th);
        free(ph);
        free(start);
        if (bad) {
            free(inc);
            free(titles);
            if (bad == 1)
                bwh_fail("out of memory");
            goto out;
        }
        m->shape = full ? BW_SHAPE_BRDF_FULL : iso ? BW_SHAPE_BRDF_ISO : BW_SHAPE_REFLECTANCE;
        m->level_out = lo;
        m->n_in = (uint32_t)n_in;
        m->bands = (uint32_t)nv;
        m->count = n_in * n_out * nv;
        if (full) {
            int li = -1;
            for (unsigned l = 0; l <= BW_MAX_LEVEL; l++)
                if (bwh_grid_count(l) == n_in)
                    li = (int)l;
            if (li < 0) {
                free(inc);
                free(titles);
                bwh_fail("%s: %zu incoming directions is not a geodesic level's 4*4^L", path,
                         n_in);
                goto out;
            }
            m->level_in = (unsigned)li;
        }
        /* incidence angles: the column's, unless the metadata has them */
        if (iso && !m->meta.incidence.n) {
            m->meta.inc_unit = BWH_ANGLE_DEG;
            if (bwh_meta_set_numbers(&m->meta.incidence, inc, n_in)) {
                free(inc);
                free(titles);
                goto out;
            }
        }
        free(inc);
        /* band titles: numbers are wavelengths, others names */
        double *wl = malloc(nv * sizeof *wl);
        int numeric = wl != NULL;
        for (size_t k = 0; numeric && k < nv; k++)
            numeric = parse_num(titles[first + k], &wl[k]) == 0;
        int names = !numeric && nv > 1 ? 1 : !numeric && strcasecmp(titles[first], "value");
        if (numeric && !m->meta.wavelengths.n)
            bad = bwh_meta_set_numbers(&m->meta.wavelengths, wl, nv);
        else if (names && !m->meta.band_names.n)
            bad = bwh_meta_set_strings(&m->meta.band_names, (const char *const *)titles + first,
                                       nv);
        free(wl);
        if (bad) {
            free(titles);
            goto out;
        }
    }
    free(titles);
    if (exact)
        m->scale = sc;
    if (!st_given) {
        m->meta.sample_type = BWH_ST_F32;
        m->meta.present |= BWH_M_SAMPLE_TYPE;
    }
    if (layout >= 0 && layout != m->shape && !(layout == BW_SHAPE_BRDF_ISO && m->shape == BW_SHAPE_REFLECTANCE)) {
        bwh_fail("%s: the metadata says shape %d, the table holds %d", path, layout, m->shape);
        goto out;
    }
    rc = 0;
out:
    free(js.b);
    free(json);
    free(f);
    free(num);
    bwh_text_close(&t);
    if (rc)
        bwh_measure_free(m);
    return rc;
}
