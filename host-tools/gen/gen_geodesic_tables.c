/* SPDX-License-Identifier: BSD-2-Clause */
#define _DEFAULT_SOURCE
/*
 * Prints firmware/codec/bw_geodesic_tables.c: the Bio-Haar weight tables
 * bw_geo_weight_coarse_q16 / bw_geo_weight_fine for base triangle 0's subtree (see bw_geodesic.h); with
 * --areas, firmware/codec/bw_geodesic_areas.c: the solid angles of that
 * subtree's triangles at levels 0..6 as Q31 fractions of the base triangle.
 *
 *   cc -std=c11 -O2 -I host-tools/lib -o /tmp/gen_geodesic_tables \
 *      host-tools/gen/gen_geodesic_tables.c host-tools/lib/geodesic.c -lm
 *   /tmp/gen_geodesic_tables > firmware/codec/bw_geodesic_tables.c
 *   /tmp/gen_geodesic_tables --areas > firmware/codec/bw_geodesic_areas.c
 *
 * The weights are checked rather than assert()ed so that the checks survive
 * -DNDEBUG; any failure exits non-zero without printing a table.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geodesic.h"

#define TABLE_LEVELS 6u   /* parents at levels 0..5, as BW_GEO_TABLE_LEVELS */
#define TABLE_PARENTS 1365u /* (4^6 - 1) / 3, as BW_GEO_PARENTS */
#define PER_LINE 4u
#define COARSE_LEVELS 3u /* as BW_GEO_COARSE_LEVELS: stored whole below this level */

/* Exact .5 ties would make the rounded value depend on the last bit of the
 * solid angles; refuse anything closer than this to a tie. */
#define TIE_MARGIN 1e-6

static uint16_t table[TABLE_PARENTS][3];

static double tri_area(const bwh_tri_t *t)
{
    return bwh_solid_angle(t->v[0], t->v[1], t->v[2]);
}

static int build(void)
{
    bwh_tri_t *par = malloc(bwh_grid_count(TABLE_LEVELS - 1) * sizeof *par);
    bwh_tri_t *kid = malloc(bwh_grid_count(TABLE_LEVELS) * sizeof *kid);
    int rc = 0;
    if (par == NULL || kid == NULL) {
        fprintf(stderr, "gen_geodesic_tables: out of memory\n");
        rc = -1;
        goto out;
    }
    for (unsigned j = 0; j < TABLE_LEVELS && rc == 0; j++) {
        if (bwh_grid_triangles(j, par) != 0 || bwh_grid_triangles(j + 1, kid) != 0) {
            fprintf(stderr, "gen_geodesic_tables: grid level %u failed\n", j);
            rc = -1;
            break;
        }
        uint32_t first = ((1u << (2u * j)) - 1u) / 3u;
        uint32_t n = 1u << (2u * j); /* parents in base 0 at level j */
        for (uint32_t p = 0; p < n; p++) {
            double ap = tri_area(&par[p]);
            uint32_t sum = 0, l[3];
            for (unsigned m = 1; m <= 3; m++) {
                double x = 65536.0 * tri_area(&kid[4 * p + m]) / ap;
                double f = x - floor(x);
                if (fabs(f - 0.5) < TIE_MARGIN) {
                    fprintf(stderr,
                            "gen_geodesic_tables: level %u parent %u child %u: "
                            "%.12f is too close to a rounding tie\n",
                            j, (unsigned)p, m, x);
                    rc = -1;
                }
                l[m - 1] = (uint32_t)floor(x + 0.5);
                sum += l[m - 1];
            }
            /* The centre child is the largest, so L0 must be positive and
             * exceed every corner weight. */
            if (sum >= 65536u || 65536u - sum <= l[0] || 65536u - sum <= l[1] ||
                65536u - sum <= l[2]) {
                fprintf(stderr,
                        "gen_geodesic_tables: level %u parent %u: L0 = 65536 - %u "
                        "is not the largest weight (%u %u %u)\n",
                        j, (unsigned)p, (unsigned)sum, (unsigned)l[0], (unsigned)l[1],
                        (unsigned)l[2]);
                rc = -1;
            }
            for (unsigned m = 0; m < 3; m++) {
                if (j >= COARSE_LEVELS && (l[m] > 16384u || 16384u - l[m] > 255u)) {
                    fprintf(stderr,
                            "gen_geodesic_tables: level %u parent %u: weight %u does not fit "
                            "the 8-bit form\n",
                            j, (unsigned)p, (unsigned)l[m]);
                    rc = -1;
                }
                table[first + p][m] = (uint16_t)l[m];
            }
        }
    }
out:
    free(par);
    free(kid);
    return rc;
}

static int emit(void)
{
    printf("/* SPDX-License-Identifier: BSD-2-Clause */\n"
           "/*\n"
           " * GENERATED FILE - DO NOT EDIT.\n"
           " * Written by host-tools/gen/gen_geodesic_tables.c. To regenerate, from the\n"
           " * repository root: make tables\n"
           " *\n"
           " * Bio-Haar weights {L1, L2, L3} in Q16 for base triangle 0's subtree,\n"
           " * L_m = round(65536 * a_m / a_parent) with a the spherical solid angles;\n"
           " * L0 = 65536 - (L1 + L2 + L3) is the largest. Levels 0..2 whole, levels\n"
           " * 3..4 as 16384 - L_m in a byte, level 5 as 16384 - L_m in a nibble for\n"
           " * the parents whose first non-zero digit is 1 (see bw_geodesic.h).\n"
           " */\n"
           "#include \"bw_geodesic.h\"\n"
           "\n"
           "const uint16_t bw_geo_weight_coarse_q16[BW_GEO_COARSE][3] = {\n");
    for (unsigned j = 0; j < TABLE_LEVELS; j++) {
        uint32_t first = ((1u << (2u * j)) - 1u) / 3u;
        uint32_t n = 1u << (2u * j);
        if (j == COARSE_LEVELS)
            printf("};\n\nconst uint8_t bw_geo_weight_fine[BW_GEO_FINE][3] = {\n");
        if (j == TABLE_LEVELS - 1u) {
            /* the finest level: only the parents whose first non-zero digit
             * is 1 (or that have none), in ascending order; every other
             * parent is the rotation of one of them that cycles the corner
             * digits 1 -> 2 -> 3, with the weights cycled alike (checked
             * here); two differences a byte, low nibble first */
            uint32_t nib[3u * 342u], cnt = 0;
            for (uint32_t p = 0; p < n; p++) {
                unsigned top = 0;
                for (unsigned k = 0; k < j; k++)
                    if ((p >> (2u * k)) & 3u)
                        top = k;
                unsigned first_digit = (p >> (2u * top)) & 3u;
                for (unsigned r = 1; r <= 2; r++) { /* the rotations of p */
                    uint32_t q = 0;
                    for (unsigned k = 0; k < j; k++) {
                        unsigned x = (p >> (2u * k)) & 3u;
                        q |= (uint32_t)(x ? (x - 1u + r) % 3u + 1u : 0u) << (2u * k);
                    }
                    for (unsigned m = 0; m < 3; m++)
                        if (table[first + q][(m + r) % 3u] != table[first + p][m]) {
                            fprintf(stderr, "gen_geodesic_tables: level %u parent %u is not "
                                            "symmetric\n", j, (unsigned)p);
                            return 1;
                        }
                }
                if (p && first_digit != 1u)
                    continue;
                for (unsigned m = 0; m < 3; m++) {
                    unsigned d = 16384u - table[first + p][m];
                    if (d > 15u) {
                        fprintf(stderr, "gen_geodesic_tables: level %u weight differs from "
                                        "16384 by more than 15\n", j);
                        return 1;
                    }
                    nib[cnt++] = d;
                }
            }
            if (cnt != 3u * 342u) {
                fprintf(stderr, "gen_geodesic_tables: %u stored parents at level %u\n",
                        (unsigned)(cnt / 3u), j);
                return 1;
            }
            printf("};\n\nconst uint8_t bw_geo_weight_finest[BW_GEO_FINEST_BYTES] = {\n");
            printf("    /* level %u: the 342 parents 0, 1, 4..7, 16..31, 64..127, 256..511 "
                   "(entries %u..), 3 nibbles each */\n", j, (unsigned)first);
            for (uint32_t i = 0; i < cnt; i += 2u) {
                unsigned lo = nib[i], hi = i + 1u < cnt ? nib[i + 1u] : 0u;
                printf("%s0x%02x,%s", i % 24u == 0 ? "    " : "", lo | (hi << 4),
                       (i + 2u) % 24u == 0 || i + 2u >= cnt ? "\n" : " ");
            }
            continue;
        }
        printf("    /* level %u: entries %u..%u */\n", j, (unsigned)first,
               (unsigned)(first + n - 1));
        for (uint32_t p = 0; p < n; p++) {
            const uint16_t *w = table[first + p];
            int last = (p + 1 == n) || ((p + 1) % PER_LINE == 0);
            if (j < COARSE_LEVELS)
                printf("%s{%5u,%5u,%5u},%s", (p % PER_LINE == 0) ? "    " : "", (unsigned)w[0],
                       (unsigned)w[1], (unsigned)w[2], last ? "\n" : " ");
            else
                printf("%s{%3u,%3u,%3u},%s", (p % PER_LINE == 0) ? "    " : "",
                       16384u - w[0], 16384u - w[1], 16384u - w[2], last ? "\n" : " ");
        }
    }
    printf("};\n");
    return 0;
}

#define AREA_LEVELS 7u  /* levels 0..6, as BW_GEO_AREA_LEVELS */

/* Solid angle / solid angle of base 0 (pi/2), rounded to Q31. */
static int emit_areas(void)
{
    bwh_tri_t *t = malloc(bwh_grid_count(AREA_LEVELS - 1) * sizeof *t);
    if (!t) {
        fprintf(stderr, "gen_geodesic_tables: out of memory\n");
        return -1;
    }
    printf("/* SPDX-License-Identifier: BSD-2-Clause */\n"
           "/*\n"
           " * GENERATED FILE - DO NOT EDIT.\n"
           " * Written by host-tools/gen/gen_geodesic_tables.c --areas (see that file).\n"
           " *\n"
           " * Solid angle of each triangle of base 0's subtree, levels 0..6, as an\n"
           " * unsigned Q31 fraction of the base triangle's pi/2 sr:\n"
           " * round(2^31 * a / (pi/2)). Triangle p (0 <= p < 4^j) of level j is entry\n"
           " * (4^j - 1)/3 + p.\n"
           " */\n"
           "#include \"bw_geodesic.h\"\n"
           "\n"
           "const uint32_t bw_geo_area_q31[BW_GEO_AREAS] = {\n");
    for (unsigned j = 0; j < AREA_LEVELS; j++) {
        if (bwh_grid_triangles(j, t) != 0) {
            free(t);
            return -1;
        }
        uint32_t n = 1u << (2u * j);
        printf("    /* level %u */\n", j);
        for (uint32_t p = 0; p < n; p++) {
            double q = 2147483648.0 * tri_area(&t[p]) / (M_PI / 2);
            printf("%s%10lu,%s", p % 6 == 0 ? "    " : "", (unsigned long)floor(q + 0.5),
                   (p + 1 == n || (p + 1) % 6 == 0) ? "\n" : " ");
        }
    }
    printf("};\n");
    free(t);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 2 && !strcmp(argv[1], "--areas"))
        return emit_areas() != 0;
    if (argc != 1) {
        fprintf(stderr, "usage: gen_geodesic_tables [--areas]\n");
        return 2;
    }
    if (build() != 0 || emit() != 0)
        return 1;
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "gen_geodesic_tables: write error\n");
        return 1;
    }
    return 0;
}
