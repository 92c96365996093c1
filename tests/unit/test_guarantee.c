/* SPDX-License-Identifier: BSD-2-Clause */
/* The guarantees of float input, held on every sample: lossless bit for bit,
 * the absolute bound E, the relative bound R (with and without a floor F),
 * and both at once, on random and adversarial values (extreme magnitudes,
 * spikes, constants, zeros, signs, subnormals, -0.0, NaN and infinities),
 * odd band counts, every geodesic level, every basis and both coders. Each
 * decode is checked here in double against the rule, independently of the
 * library's own check, and the payload's recorded guarantee must say the
 * same. A refusal must leave a message; only non-finite values under a lossy
 * mode and an absolute bound below float32's resolution may be refused. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "bw_config.h"
#include "bwh_decode.h"
#include "bwh_encode.h"
#include "bwh_error.h"
#include "bwh_guarantee.h"
#include "bwh_shape.h"
#include "bwh_values.h"
#include "test_rng.h"

enum { GEN_LOGNORMAL, GEN_SIGNED_ZEROS, GEN_SPIKES, GEN_CONSTANT, GEN_ZEROS, GEN_SMOOTH,
       GEN_EXTREME, GEN_HUGE_POSITIVE, GEN_ODD_BITS, GEN_COUNT };
static const char *const gen_names[] = {"lognormal", "signed with zeros", "spikes", "constant",
                                        "zeros", "smooth", "extreme", "huge positive",
                                        "odd bits"};

typedef struct {
    int kind; /* bwh_guarantee_kind_t */
    double E, R, F;
} rule_t;

static const rule_t rules[] = {
    {BWH_GUARANTEE_EXACT, 0, 0, 0},
    {BWH_GUARANTEE_ABSOLUTE, 1e-3, 0, 0},
    {BWH_GUARANTEE_RELATIVE, 0, 1e-2, 0},
    {BWH_GUARANTEE_RELATIVE, 0, 1e-4, 0},
    {BWH_GUARANTEE_RELATIVE, 0, 1e-3, 1e-3},
    {BWH_GUARANTEE_BOTH, 5e-3, 1e-2, 0},
    {BWH_GUARANTEE_BOTH, 1e-4, 1e-3, 1e-6},
};
#define N_RULES (sizeof rules / sizeof rules[0])

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static unsigned n_checked, n_refused;

static float gen_value(int gen, size_t i, size_t n)
{
    double u = test_uniform(&rng), t = (double)i / (double)(n ? n : 1);
    switch (gen) {
    case GEN_LOGNORMAL:
        return (float)exp(-9.0 + 12.0 * u);
    case GEN_SIGNED_ZEROS:
        if (u < 0.15)
            return 0.0f;
        return (float)((u < 0.55 ? -1 : 1) * exp(-6.0 + 8.0 * test_uniform(&rng)));
    case GEN_SPIKES:
        return (float)(0.02 + 0.01 * sin(40 * t) + (u < 0.03 ? 500.0 * test_uniform(&rng) : 0.0));
    case GEN_CONSTANT:
        return 0.3718f;
    case GEN_ZEROS:
        return 0.0f;
    case GEN_SMOOTH:
        return (float)(0.05 + 0.9 * pow(sin(3.1 * t) * sin(3.1 * t), 8.0));
    case GEN_HUGE_POSITIVE:
        return u < 0.3 ? nextafterf(FLT_MAX, 0.0f) : u < 0.5 ? FLT_MAX : (float)(u * 1e38);
    case GEN_EXTREME: {
        static const float ex[] = {FLT_MAX / 4, -FLT_MAX / 4, FLT_MIN, -FLT_MIN, 1e-42f, -1e-45f,
                                   1e30f, -1e-30f, 1.0f, 0.0f};
        return u < 0.5 ? ex[i % (sizeof ex / sizeof ex[0])] : (float)(u * 1e3);
    }
    default: { /* any bit pattern but non-finite ones, and -0.0 */
        uint32_t b = (uint32_t)(test_uniform(&rng) * 4294967296.0);
        if ((b & 0x7F800000u) == 0x7F800000u)
            b ^= 0x40000000u;
        return i % 17 == 3 ? -0.0f : bwh_bits_to_float(b);
    }
    }
}

/* the rule's bound for input x, in double */
static double bound_of(const rule_t *r, double x)
{
    double rel = fmax(r->R * fabs(x), r->F);
    switch (r->kind) {
    case BWH_GUARANTEE_ABSOLUTE:
        return r->E;
    case BWH_GUARANTEE_RELATIVE:
        return rel;
    case BWH_GUARANTEE_BOTH:
        return fmin(r->E, rel);
    default:
        return 0;
    }
}

static int all_finite(const float *x, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

/* Encodes x under rule r, decodes, and checks every sample and the record.
 * may_refuse: the encoder may refuse these values under this rule. */
static void check_case(const bw_dims_t *d, const float *x, const rule_t *r, unsigned basis,
                       unsigned flags, int may_refuse, const char *what)
{
    size_t n = bw_dims_samples(d);
    bwh_encode_opts_t o;
    memset(&o, 0, sizeof o);
    o.basis = basis;
    o.flags = flags;
    o.mode = r->kind == BWH_GUARANTEE_EXACT      ? BW_MODE_LOSSLESS
             : r->kind == BWH_GUARANTEE_RELATIVE ? BW_MODE_LOSSLESS
                                                 : BW_MODE_MAX_ERROR;
    o.max_error = r->E;
    o.max_rel_error = r->R;
    o.rel_floor = r->F;
    uint8_t *p = NULL;
    size_t len = 0;
    if (bwh_encode_f32(d, x, &o, &p, &len) != 0) {
        if (!may_refuse || !*bwh_last_error())
            fail_msg("%s: refused: %s", what, bwh_last_error());
        assert_null(p);
        n_refused++;
        return;
    }
    bw_header_t h;
    float *v = NULL;
    if (bwh_decode(p, len, &h, NULL, &v) != 0)
        fail_msg("%s: decode: %s", what, bwh_last_error());
    for (size_t i = 0; i < n; i++) {
        if (r->kind == BWH_GUARANTEE_EXACT) {
            if (bwh_float_to_bits(v[i]) != bwh_float_to_bits(x[i]))
                fail_msg("%s: sample %zu: 0x%08x decoded as 0x%08x", what, i,
                         (unsigned)bwh_float_to_bits(x[i]), (unsigned)bwh_float_to_bits(v[i]));
        } else {
            double e = fabs((double)v[i] - (double)x[i]), b = bound_of(r, x[i]);
            if (!(e <= b))
                fail_msg("%s: sample %zu: %.9g decoded as %.9g, error %.3g > bound %.3g", what, i,
                         (double)x[i], (double)v[i], e, b);
        }
    }
    /* what the payload promises is what was asked */
    bwh_guarantee_t g;
    assert_int_equal(bwh_guarantee_read(p, len, &g), 0);
    assert_int_equal(g.kind, r->kind);
    if (r->kind == BWH_GUARANTEE_ABSOLUTE || r->kind == BWH_GUARANTEE_BOTH)
        assert_true(g.max_error == r->E);
    if (r->kind == BWH_GUARANTEE_RELATIVE || r->kind == BWH_GUARANTEE_BOTH) {
        assert_true(g.max_rel_error == r->R);
        assert_true(g.rel_floor == r->F);
    }
    assert_int_equal(bwh_guarantee_check(&g, x, v, n, NULL), 0);
    free(v);
    free(p);
    n_checked++;
}

static int dims_of(int level, int level_in, uint32_t incoming, uint32_t bands, size_t count,
                   bw_dims_t *d)
{
    bwh_shape_t s = {level, level_in, incoming, bands};
    return bwh_shape_dims(&s, count, d);
}

/* every rule, every generator, on one shape with one basis and coder */
static void sweep(const bw_dims_t *d, unsigned basis, unsigned flags, const char *shape)
{
    size_t n = bw_dims_samples(d);
    float *x = malloc(n * sizeof *x);
    assert_non_null(x);
    char what[200];
    for (int gen = 0; gen < GEN_COUNT; gen++) {
        for (size_t i = 0; i < n; i++)
            x[i] = gen_value(gen, i, n);
        for (size_t k = 0; k < N_RULES; k++) {
            const rule_t *r = &rules[k];
            if (basis == BW_BASIS_PRED && (flags & BW_FLAG_STREAM_ORDER))
                continue;
            /* an absolute bound finer than float32 resolves at the
             * largest value (1e38: 2^103 apart) is refused; a relative one
             * whose grid would span more than the core's 2^25 steps is
             * coded exactly, and so met */
            int may_refuse = r->kind == BWH_GUARANTEE_ABSOLUTE &&
                             (gen == GEN_EXTREME || gen == GEN_HUGE_POSITIVE ||
                              gen == GEN_ODD_BITS);
            snprintf(what, sizeof what, "%s, %s values, rule %zu, basis %u, %s", shape,
                     gen_names[gen], k, basis, flags & BW_FLAG_RICE ? "rice" : "range");
            check_case(d, x, r, basis, flags, may_refuse, what);
        }
    }
    free(x);
}

static void every_basis_and_coder_on_odd_spectra_never_breaks_a_guarantee(void **state)
{
    (void)state;
    static const uint32_t bands[] = {1, 3, 7, 33, 65};
    static const unsigned bases[] = {BW_BASIS_HAAR, BW_BASIS_53, BW_BASIS_97, BW_BASIS_PRED,
                                     BW_BASIS_AUTO};
    for (size_t b = 0; b < sizeof bands / sizeof bands[0]; b++) {
        bw_dims_t d;
        assert_int_equal(dims_of(-1, -1, 0, bands[b], (size_t)bands[b] * (b % 2 ? 5 : 4), &d), 0);
        for (size_t k = 0; k < sizeof bases / sizeof bases[0]; k++)
            for (unsigned rice = 0; rice < 2; rice++) {
                /* the device's build of the core encodes no prediction */
                if (bases[k] == BW_BASIS_PRED && !BW_CFG_ENCODE_PRED)
                    continue;
                char shape[64];
                snprintf(shape, sizeof shape, "%u spectra x %u bands", d.n_in, d.bands);
                sweep(&d, bases[k], rice ? BW_FLAG_RICE : 0u, shape);
            }
    }
}

static void every_level_and_directional_shape_never_breaks_a_guarantee(void **state)
{
    (void)state;
    for (int level = 0; level <= 6; level++) {
        bw_dims_t d;
        uint32_t bands = level >= 5 ? 1u : 3u;
        size_t n = (size_t)4 << (2 * level);
        assert_int_equal(dims_of(level, -1, 0, bands, n * bands, &d), 0);
        char shape[64];
        snprintf(shape, sizeof shape, "reflectance level %d", level);
        sweep(&d, level % 3 == 0 ? BW_BASIS_AUTO : (unsigned)(level % 3),
              level % 2 ? BW_FLAG_RICE : 0u, shape);
    }
    bw_dims_t d;
    assert_int_equal(dims_of(2, -1, 3, 5, 3 * 64 * 5, &d), 0);
    sweep(&d, BW_BASIS_53, 0, "isotropic BRDF level 2");
    sweep(&d, BW_BASIS_97, BW_FLAG_RICE | BW_FLAG_STREAM_ORDER, "streamed BRDF level 2");
    assert_int_equal(dims_of(1, 1, 0, 2, 16 * 16 * 2, &d), 0);
    sweep(&d, BW_BASIS_AUTO, 0, "full BRDF level 1");
    sweep(&d, BW_BASIS_HAAR, BW_FLAG_RICE, "full BRDF level 1");
}

static void non_finite_values_come_back_bit_for_bit_or_are_refused(void **state)
{
    (void)state;
    bw_dims_t d;
    assert_int_equal(dims_of(-1, -1, 0, 9, 9 * 4, &d), 0);
    float x[36];
    for (size_t i = 0; i < 36; i++)
        x[i] = (float)(0.25 + 0.01 * (double)i);
    x[0] = NAN;
    x[5] = INFINITY;
    x[13] = -INFINITY;
    x[21] = bwh_bits_to_float(0xFFA00001u); /* a signalling NaN with a payload */
    x[30] = -0.0f;
    assert_false(all_finite(x, 36));
    unsigned before = n_refused;
    for (size_t k = 0; k < N_RULES; k++)
        check_case(&d, x, &rules[k], BW_BASIS_AUTO, 0, rules[k].kind != BWH_GUARANTEE_EXACT,
                   "non-finite values");
    /* lossless must take them; every lossy rule must refuse them */
    assert_int_equal(n_refused - before, N_RULES - 1);
}

static void a_decode_that_moves_one_value_past_its_bound_is_caught(void **state)
{
    (void)state;
    float x[8] = {1.0f, -2.0f, 0.0f, 1e-3f, 100.0f, 7.0f, -0.5f, 3.0f}, v[8];
    for (size_t k = 1; k < N_RULES; k++) {
        bwh_guarantee_t g = {rules[k].kind, 1, 4, rules[k].E, rules[k].R, rules[k].F};
        for (size_t j = 0; j < 8; j++) {
            memcpy(v, x, sizeof v);
            double b = bound_of(&rules[k], x[j]);
            v[j] = nextafterf((float)((double)x[j] + b), INFINITY);
            while (fabs((double)v[j] - (double)x[j]) <= b)
                v[j] = nextafterf(v[j], INFINITY);
            assert_int_equal(bwh_guarantee_check(&g, x, v, 8, NULL), 1);
        }
    }
    bwh_guarantee_t exact = {BWH_GUARANTEE_EXACT, 0, 0, 0, 0, 0};
    memcpy(v, x, sizeof v);
    v[2] = -0.0f;
    assert_int_equal(bwh_guarantee_check(&exact, x, v, 8, NULL), 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_decode_that_moves_one_value_past_its_bound_is_caught),
        cmocka_unit_test(non_finite_values_come_back_bit_for_bit_or_are_refused),
        cmocka_unit_test(every_basis_and_coder_on_odd_spectra_never_breaks_a_guarantee),
        cmocka_unit_test(every_level_and_directional_shape_never_breaks_a_guarantee),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    printf("guarantee cases checked: %u, refused: %u\n", n_checked, n_refused);
    return rc;
}
