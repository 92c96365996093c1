/* SPDX-License-Identifier: BSD-2-Clause */
/* Vectors and the random numbers of the renderer (inline, header only). */
#ifndef RENDER_VEC_H
#define RENDER_VEC_H

#include <math.h>
#include <stdint.h>

#define R_PI 3.14159265358979323846

typedef struct {
    double x, y, z;
} v3;

static inline v3 vec(double x, double y, double z) { return (v3){x, y, z}; }
static inline v3 add(v3 a, v3 b) { return vec(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline v3 sub(v3 a, v3 b) { return vec(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline v3 mul(v3 a, double s) { return vec(a.x * s, a.y * s, a.z * s); }
static inline v3 mulv(v3 a, v3 b) { return vec(a.x * b.x, a.y * b.y, a.z * b.z); } /* per channel */
static inline double dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline v3 cross(v3 a, v3 b)
{
    return vec(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline v3 norm(v3 a) { return mul(a, 1.0 / sqrt(dot(a, a))); }

/* random numbers: splitmix64 seeding, xorshift64* stream */
typedef struct {
    uint64_t s;
} rng_t;

static inline uint64_t splitmix(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* uniform in [0, 1) */
static inline double rnd(rng_t *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return (double)((r->s * 0x2545f4914f6cdd1dull) >> 11) * 0x1.0p-53;
}

#endif
