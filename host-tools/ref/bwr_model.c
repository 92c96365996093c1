/* SPDX-License-Identifier: BSD-2-Clause */
/* The objects of sec. 4.2 on top of the generic transforms. */
#include "bwr_model.h"

#include <stdlib.h>
#include <string.h>

static bwr_shape_t shape0(bwr_kind_t k)
{
    bwr_shape_t s;
    memset(&s, 0, sizeof s);
    s.kind = k;
    s.n_in = 1;
    s.level_in = -1;
    s.level_out = -1;
    s.bands = 1;
    s.spec_levels = -1;
    s.spec_ext = BWR_EXT_PERIODIZATION;
    s.in_basis = NULL;
    s.in_levels = -1;
    return s;
}

bwr_shape_t bwr_shape_spectra(size_t count, size_t bands, const bwr_filter_t *basis)
{
    bwr_shape_t s = shape0(BWR_SPECTRUM);
    s.n_in = count;
    s.bands = bands;
    s.basis = basis;
    return s;
}

bwr_shape_t bwr_shape_reflectance(unsigned level)
{
    bwr_shape_t s = shape0(BWR_REFLECTANCE);
    s.level_out = (int)level;
    return s;
}

bwr_shape_t bwr_shape_spectral_reflectance(unsigned level, size_t bands, const bwr_filter_t *basis)
{
    bwr_shape_t s = shape0(BWR_SPECTRAL_REFLECTANCE);
    s.level_out = (int)level;
    s.bands = bands;
    s.basis = basis;
    return s;
}

bwr_shape_t bwr_shape_brdf(unsigned level_in, unsigned level_out)
{
    bwr_shape_t s = shape0(BWR_BRDF);
    s.level_in = (int)level_in;
    s.n_in = (size_t)4 << (2u * level_in);
    s.level_out = (int)level_out;
    return s;
}

bwr_shape_t bwr_shape_brdf_isotropic(size_t n_in, unsigned level_out)
{
    bwr_shape_t s = shape0(BWR_BRDF);
    s.n_in = n_in;
    s.level_out = (int)level_out;
    return s;
}

bwr_shape_t bwr_shape_spectral_brdf(int level_in, size_t n_in, unsigned level_out, size_t bands,
                                    const bwr_filter_t *basis)
{
    bwr_shape_t s = shape0(BWR_SPECTRAL_BRDF);
    s.level_in = level_in;
    s.n_in = level_in >= 0 ? (size_t)4 << (2u * (unsigned)level_in) : n_in;
    s.level_out = (int)level_out;
    s.bands = bands;
    s.basis = basis;
    return s;
}

const char *bwr_kind_name(bwr_kind_t k)
{
    switch (k) {
    case BWR_SPECTRUM: return "Spectrum";
    case BWR_REFLECTANCE: return "Reflectance";
    case BWR_SPECTRAL_REFLECTANCE: return "Spectral Reflectance";
    case BWR_BRDF: return "BRDF";
    case BWR_SPECTRAL_BRDF: return "Spectral BRDF";
    }
    return "?";
}

void bwr_model_free(bwr_model_t *m)
{
    bwr_sphere_free(&m->sph_in);
    bwr_sphere_free(&m->sph_out);
    free(m->in_psi2);
    free(m->out_psi2);
    free(m->spec_norm2);
    memset(m, 0, sizeof *m);
}

int bwr_model_init(bwr_model_t *m, const bwr_shape_t *sh)
{
    memset(m, 0, sizeof *m);
    m->shape = *sh;
    if (sh->n_in == 0 || sh->bands == 0 || sh->level_in > (int)BWR_SPHERE_MAX_LEVEL ||
        sh->level_out > (int)BWR_SPHERE_MAX_LEVEL)
        return -1;
    if (sh->level_in >= 0 && sh->n_in != ((size_t)4 << (2u * (unsigned)sh->level_in)))
        return -1;
    m->n_in = sh->n_in;
    m->n_out = sh->level_out >= 0 ? (size_t)4 << (2u * (unsigned)sh->level_out) : 1;
    m->bands = sh->bands;
    m->have_in = sh->level_in >= 0;
    m->have_in1d = sh->level_in < 0 && sh->in_basis != NULL;
    m->have_out = sh->level_out >= 0;
    m->have_spec = sh->bands > 1 && sh->basis != NULL;
    if (sh->bands > 1 && sh->basis == NULL)
        return -1;
    if (m->have_in && bwr_sphere_init(&m->sph_in, (unsigned)sh->level_in) != 0)
        goto fail;
    if (m->have_out && bwr_sphere_init(&m->sph_out, (unsigned)sh->level_out) != 0)
        goto fail;
    m->ncoef_spec = m->bands;
    if (m->have_spec) {
        if (bwr_dwt_plan_ext(&m->dwt, sh->basis, m->bands, sh->spec_levels, sh->spec_ext) != 0)
            goto fail;
        m->ncoef_spec = m->dwt.ncoef;
    }
    m->nci = m->n_in;
    if (m->have_in1d) {
        if (bwr_dwt_plan_ext(&m->dwt_in, sh->in_basis, m->n_in, sh->in_levels, sh->spec_ext) != 0)
            goto fail;
        m->nci = m->dwt_in.ncoef;
    }
    m->n_samples = m->n_in * m->n_out * m->bands;
    m->n_coefs = m->nci * m->n_out * m->ncoef_spec;
    m->in_psi2 = malloc(m->nci * sizeof(double));
    m->out_psi2 = malloc(m->n_out * sizeof(double));
    m->spec_norm2 = malloc(m->ncoef_spec * sizeof(double));
    if (m->in_psi2 == NULL || m->out_psi2 == NULL || m->spec_norm2 == NULL)
        goto fail;
    for (size_t i = 0; i < m->nci; i++)
        m->in_psi2[i] = m->have_in ? m->sph_in.psi2[i] : 1.0;
    if (m->have_in1d && bwr_dwt_synthesis_norms2(&m->dwt_in, m->in_psi2) != 0)
        goto fail;
    for (size_t o = 0; o < m->n_out; o++)
        m->out_psi2[o] = m->have_out ? m->sph_out.psi2[o] : 1.0;
    if (m->have_spec) {
        if (bwr_dwt_synthesis_norms2(&m->dwt, m->spec_norm2) != 0)
            goto fail;
    } else {
        for (size_t k = 0; k < m->ncoef_spec; k++)
            m->spec_norm2[k] = 1.0;
    }
    return 0;
fail:
    bwr_model_free(m);
    return -1;
}

int bwr_model_forward(const bwr_model_t *m, const double *samples, double *coef)
{
    size_t blk = m->n_out * m->bands; /* one Reflectance / Spectral Reflectance */
    size_t nbuf = m->nci * blk;       /* >= n_samples */
    double *a = malloc(nbuf * sizeof *a), *b = malloc(nbuf * sizeof *b);
    int rc = -1;
    if (a == NULL || b == NULL)
        goto done;
    memcpy(a, samples, m->n_samples * sizeof *a);
    /* 1. incoming sphere: elements are whole (spectral) reflectances */
    if (m->have_in) {
        bwr_type_t t = bwr_type_vector(blk);
        if (bwr_biohaar_forward(&m->sph_in, &t, a, b) != 0)
            goto done;
        double *s = a;
        a = b;
        b = s;
    } else if (m->have_in1d) {
        bwr_type_t t = bwr_type_vector(blk);
        if (bwr_dwt_forward(&m->dwt_in, &t, a, b) != 0)
            goto done;
        double *s = a;
        a = b;
        b = s;
    }
    /* 2. outgoing sphere of every incoming coefficient: elements are spectra */
    if (m->have_out) {
        bwr_type_t vt = bwr_type_vector(m->bands);
        const bwr_type_t *t = m->bands == 1 ? &bwr_type_real : &vt;
        for (size_t i = 0; i < m->nci; i++)
            if (bwr_biohaar_forward(&m->sph_out, t, a + i * blk, b + i * blk) != 0)
                goto done;
        double *s = a;
        a = b;
        b = s;
    }
    /* 3. spectral axis of every vector coefficient */
    size_t nv = m->nci * m->n_out;
    for (size_t v = 0; v < nv; v++) {
        if (m->have_spec) {
            if (bwr_dwt_forward(&m->dwt, &bwr_type_real, a + v * m->bands,
                                coef + v * m->ncoef_spec) != 0)
                goto done;
        } else {
            memcpy(coef + v * m->ncoef_spec, a + v * m->bands, m->bands * sizeof *a);
        }
    }
    rc = 0;
done:
    free(a);
    free(b);
    return rc;
}

int bwr_model_inverse(const bwr_model_t *m, const double *coef, double *samples)
{
    size_t blk = m->n_out * m->bands;
    size_t nbuf = m->nci * blk;
    double *a = malloc(nbuf * sizeof *a), *b = malloc(nbuf * sizeof *b);
    int rc = -1;
    if (a == NULL || b == NULL)
        goto done;
    size_t nv = m->nci * m->n_out;
    for (size_t v = 0; v < nv; v++) {
        if (m->have_spec) {
            if (bwr_dwt_inverse(&m->dwt, &bwr_type_real, coef + v * m->ncoef_spec,
                                a + v * m->bands) != 0)
                goto done;
        } else {
            memcpy(a + v * m->bands, coef + v * m->ncoef_spec, m->bands * sizeof *a);
        }
    }
    if (m->have_out) {
        bwr_type_t vt = bwr_type_vector(m->bands);
        const bwr_type_t *t = m->bands == 1 ? &bwr_type_real : &vt;
        for (size_t i = 0; i < m->nci; i++)
            if (bwr_biohaar_inverse(&m->sph_out, t, a + i * blk, b + i * blk) != 0)
                goto done;
        double *s = a;
        a = b;
        b = s;
    }
    if (m->have_in || m->have_in1d) {
        bwr_type_t t = bwr_type_vector(blk);
        if ((m->have_in ? bwr_biohaar_inverse(&m->sph_in, &t, a, b)
                        : bwr_dwt_inverse(&m->dwt_in, &t, a, b)) != 0)
            goto done;
        double *s = a;
        a = b;
        b = s;
    }
    memcpy(samples, a, m->n_samples * sizeof *a);
    rc = 0;
done:
    free(a);
    free(b);
    return rc;
}
