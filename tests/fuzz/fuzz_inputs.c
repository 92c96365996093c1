/* SPDX-License-Identifier: BSD-2-Clause */
/*
 * libFuzzer target: the host library's readers of measurement files
 * (bwh_input.h) on arbitrary bytes: the input is written to a file and read
 * as every format (Spectral Evolution, Spectra Vista, ASD, USGS with itself
 * as the wavelength table, ENVI as a header with itself as the data, CSV,
 * numpy, an RGL BRDF, a goniometer's CSV, raw samples), and detected.
 *
 * Every reader must return 0, or -1 with a message, without a fault the
 * sanitizers see; what it accepts must hold samples (count > 0, a whole
 * number of spectra, as many as the shape it states) whose floats can be
 * formed, and metadata that writes.
 *
 * Built by tests/fuzz/run.sh with the library's sources, as fuzz_host is.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bw_codec.h"
#include "bwh_error.h"
#include "bwh_input.h"
#include "bwh_meta.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void require(int cond, const char *what, const char *format)
{
    if (!cond) {
        fprintf(stderr, "fuzz_inputs: %s: %s (last error: %s)\n", format, what, bwh_last_error());
        abort();
    }
}

static char dir[64];

static void put(const char *name, const uint8_t *data, size_t size, char *path, size_t cap)
{
    snprintf(path, cap, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    require(f != NULL && fwrite(data, 1, size, f) == size && fclose(f) == 0, "cannot write",
            path);
}

/* what a reader accepted */
static void accepted(const bwh_measure_t *m, const char *format)
{
    require(m->count > 0 && (m->values != NULL) != (m->ints != NULL), "no samples", format);
    if (m->bands)
        require(m->count % m->bands == 0, "samples not a whole number of spectra", format);
    bw_dims_t d;
    if (m->shape >= 0 && m->bands &&
        bw_dims_make(&d, (bw_shape_t)m->shape, m->level_out, m->level_in, m->n_in, m->bands) ==
            BW_OK)
        require(bw_dims_samples(&d) == m->count, "the shape stated does not hold the samples",
                format);
    float *f = bwh_measure_floats(m);
    require(f != NULL, "no floats", format);
    free(f);
    uint8_t *area = NULL;
    size_t len = 0;
    require(bwh_meta_encode(&m->meta, &area, &len) == 0, "its metadata does not write", format);
    free(area);
}

static void read_as(int format, const char *path, const bwh_read_opts_t *o)
{
    bwh_measure_t m;
    bwh_measure_init(&m);
    const char *name = bwh_input_format_name(format);
    int rc = bwh_measure_read(&path, 1, format, o, &m);
    require(rc == 0 || rc == -1, "a status other than 0 or -1", name);
    if (rc == 0)
        accepted(&m, name);
    else
        require(bwh_last_error()[0] != '\0', "an error without a message", name);
    bwh_measure_free(&m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!dir[0]) {
        snprintf(dir, sizeof dir, "/tmp/bw_fuzz_inputs.%ld", (long)getpid());
        char cmd[128];
        snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
        require(system(cmd) == 0, "cannot make the directory", dir);
    }
    char in[128], hdr[128], dat[128];
    put("in", data, size, in, sizeof in);
    put("cube.hdr", data, size, hdr, sizeof hdr);
    put("cube.img", data, size, dat, sizeof dat);
    bwh_read_opts_t o = BWH_READ_OPTS_INIT;
    o.level = 1; /* data sampled onto the grid: a small grid */
    o.wavelengths = in;
    int detected = bwh_input_detect(in);
    require(detected >= -1 && detected < BWH_IN_COUNT, "bwh_input_detect", "auto");
    for (int f = BWH_IN_F32; f < BWH_IN_COUNT; f++)
        read_as(f, f == BWH_IN_ENVI ? hdr : in, &o);
    read_as(BWH_IN_AUTO, in, &o);
    return 0;
}

#ifdef BW_FUZZ_REPLAY
#define BW_FUZZ_NAME "fuzz_inputs"
#include "replay_main.h"
#endif
