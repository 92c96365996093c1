#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""Generates host-tools/ref/bwr_filters.c: the 1-D wavelet filter tables of
the float reference model (54 bases).

    /usr/bin/python3 host-tools/ref/gen/gen_filters.py > host-tools/ref/bwr_filters.c

Needs numpy only. Conventions are those of PyWavelets (dec_lo, rec_lo of the
same even length F; the high-pass filters follow from them in bwr_filters.h:
rec_hi[n] = (-1)^n dec_lo[n], dec_hi[n] = (-1)^(n+1) rec_lo[n]).

Derivations
-----------
With y = sin^2(w/2) = (2 - z - 1/z) / 4, every compactly supported orthogonal
or biorthogonal pair with N and N~ vanishing moments satisfies
    H(z) H~(1/z) = cos^(2K)(w/2) P_K(y),   P_K(y) = sum_{k<K} C(K-1+k, k) y^k,
2K = N + N~ (Daubechies 1992, "Ten Lectures", ch. 6 and 8; Cohen, Daubechies
and Feauveau 1992).

* Daubechies dbN (N = 2..10): K = N; every root y_r of P_N gives the pair
  z, 1/z of z^2 - (2 - 4 y_r) z + 1 = 0; the minimum-phase choice keeps the
  root inside the unit circle: rec_lo = sqrt2 ((1 + z^-1)/2)^N prod (1 - r z^-1)
  / prod (1 - r), dec_lo its reverse.
* Symlets symN (N = 2..10): the same roots, one of each pair z, 1/z chosen so
  that the phase is as nearly linear as possible. That choice is a published
  convention (Daubechies 1992, sec. 8.1.1; the tables of PyWavelets); SYM_CHOICE
  below records it as one bit per real root or conjugate pair of roots of P_N
  (sorted by real part, then imaginary part; 0 = the root inside the unit
  circle) and whether the result is stored reversed.
* Coiflets coifN (N = 1..5): the defining conditions (2N vanishing moments
  of psi, 2N - 1 of phi) are nonlinear and have no closed form; the values are
  those of Daubechies (1992, Table 8.1), as printed to 17 significant digits by
  PyWavelets 1.1.1 (MIT licence). The tests check orthonormality and the
  vanishing moments independently.
* Biorthogonal CDF biorNr.Nd: Nr vanishing moments on the reconstruction side,
  Nd on the decomposition side, K = (Nr + Nd) / 2.
  - Nr = 1, 2, 3 (spline family): rec_lo = sqrt2 ((1 + z)/2)^Nr (a B-spline),
    dec_lo = sqrt2 ((1 + z)/2)^Nd P_K(y).
  - bior4.4 (CDF 9/7), bior5.5, bior6.8 (CDF 17/11): the roots of P_K are
    shared between the filters, rec_lo = sqrt2 ((1+z)/2)^a prod_{y_r in R}
    (1 - y/y_r), dec_lo = sqrt2 ((1+z)/2)^b prod_{other roots} (1 - y/y_r);
    (a, b, R) in BIOR_SPLIT below (4.4: 4, 4, the real root; 5.5: 6, 4, the
    conjugate pair of smaller |y|; 6.8: 6, 8, the pair of middle |y|), the
    split of PyWavelets' tables.
  Symmetric filters are centred in the array of length F (the longest length
  rounded up to even): odd lengths at F/2 (dec_lo) and F/2 - 1 (rec_lo), even
  lengths at (F - 1)/2.
  rbioNr.Nd (reverse biorthogonal) swaps the roles: dec_lo(rbio) =
  reverse(rec_lo(bior)), rec_lo(rbio) = reverse(dec_lo(bior)).
"""
import sys
from math import comb, sqrt

import numpy as np

SQRT2 = sqrt(2.0)

# symN: (choice bit per root group, stored reversed)
SYM_CHOICE = {
    2: ((0,), 1),
    3: ((1,), 0),
    4: ((1, 0), 0),
    5: ((0, 1), 0),
    6: ((0, 1, 0), 0),
    7: ((0, 1, 1), 0),
    8: ((0, 1, 0, 1), 1),
    9: ((0, 1, 1, 0), 1),
    10: ((0, 1, 0, 1, 0), 0),
}

# bior Nr.Nd with shared roots: (zeros at z = -1 of rec_lo, of dec_lo, the
# roots of P_K that go to rec_lo: 'real' = the real root, i = the i-th
# conjugate pair in order of increasing |y|)
BIOR_SPLIT = {
    (4, 4): (4, 4, 'real'),
    (5, 5): (6, 4, 0),
    (6, 8): (6, 8, 1),
}

COIF = {
    'coif1': [
        -0.07273261951252645,
        0.3378976624574818,
        0.8525720202116004,
        0.3848648468648578,
        -0.07273261951252645,
        -0.015655728135791993,
    ],
    'coif2': [
        0.01638733646320364,
        -0.04146493678687178,
        -0.0673725547237256,
        0.3861100668227629,
        0.8127236354494135,
        0.4170051844232391,
        -0.07648859907828076,
        -0.05943441864643109,
        0.02368017194684777,
        0.005611434819368834,
        -0.0018232088709110323,
        -0.000720549445520347,
    ],
    'coif3': [
        -0.003793512864380802,
        0.007782596425672746,
        0.023452696142077168,
        -0.06577191128146936,
        -0.06112339000297255,
        0.40517690240911824,
        0.7937772226260872,
        0.42848347637737,
        -0.07179982161915484,
        -0.08230192710629983,
        0.03455502757329774,
        0.015880544863669452,
        -0.009007976136730624,
        -0.0025745176881367972,
        0.0011175187708306303,
        0.0004662169598204029,
        -7.0983302506379e-05,
        -3.459977319727278e-05,
    ],
    'coif4': [
        0.000892313902537003,
        -0.001629492425226786,
        -0.007346167936268051,
        0.01606894713157503,
        0.02668230466960483,
        -0.08126671024919373,
        -0.05607731960356926,
        0.41530842700068227,
        0.7822389344242826,
        0.43438603311435653,
        -0.06662747236681717,
        -0.09622042453595264,
        0.03933442260558915,
        0.02508225333794961,
        -0.015211728187697211,
        -0.0056582838001308835,
        0.0037514346971460866,
        0.0012665610789256603,
        -0.0005890202246332165,
        -0.0002599743371222568,
        6.233885431278719e-05,
        3.1229861599195265e-05,
        -3.259647940030751e-06,
        -1.7849909144933469e-06,
    ],
    'coif5': [
        -0.000212081862067494,
        0.0003585777411617577,
        0.0021782943778456947,
        -0.00415931262757864,
        -0.010131584846900276,
        0.023408322118927783,
        0.028169744270532353,
        -0.09192158806008609,
        -0.052046670253554764,
        0.42157126673075435,
        0.7742936228603274,
        0.4379823066591634,
        -0.06203775157498196,
        -0.10556315130733723,
        0.041287530472117834,
        0.032674799467057355,
        -0.019758391600965465,
        -0.009159507338676163,
        0.006761520220620417,
        0.0024315754425382886,
        -0.0016616273039298788,
        -0.0006375589261258812,
        0.0003018579416682448,
        0.00014035632812373243,
        -4.12198619242655e-05,
        -2.1270221672515614e-05,
        3.7007277113394796e-06,
        2.0612203985788783e-06,
        -1.6237995172048338e-07,
        -9.604010112767894e-08,
    ],
}


def p_coeffs(k):
    return [comb(k - 1 + j, j) for j in range(k)]


def y_roots(k):
    """Roots of P_K(y), sorted by real part then imaginary part."""
    if k < 2:
        return []
    c = p_coeffs(k)
    r = np.roots(c[::-1])
    return sorted(r, key=lambda v: (round(v.real, 9), v.imag))


def root_groups(roots):
    """Real roots and conjugate pairs (represented by the root with imag > 0)."""
    return [v for v in roots if abs(v.imag) < 1e-12 * max(1.0, abs(v)) or v.imag > 0]


def z_pair(y):
    """Roots (inside, outside) of z^2 - (2 - 4y) z + 1."""
    b = 2.0 - 4.0 * y
    d = np.sqrt(complex(b * b - 4.0))
    r1, r2 = (b + d) / 2.0, (b - d) / 2.0
    return (r1, r2) if abs(r1) < abs(r2) else (r2, r1)


def from_zroots(nzeros, zs):
    """sqrt2 ((1 + z^-1)/2)^nzeros prod (1 - r z^-1) / prod (1 - r), as taps of z^0, z^-1, ..."""
    p = np.array([1.0 + 0j])
    for _ in range(nzeros):
        p = np.convolve(p, [0.5, 0.5])
    norm = 1.0 + 0j
    for r in zs:
        p = np.convolve(p, [1.0, -r])
        norm *= 1.0 - r
    p = p / norm * SQRT2
    assert np.max(np.abs(p.imag)) < 1e-9, p
    return list(p.real)


def daubechies(n, choice=None):
    groups = root_groups(y_roots(n))
    if choice is None:
        choice = (0,) * len(groups)
    zs = []
    for g, c in zip(groups, choice):
        r = z_pair(g)[c]
        if abs(g.imag) < 1e-12:
            zs.append(r.real + 0j)
        else:
            zs += [r, np.conj(r)]
    return from_zroots(n, zs)


# Laurent polynomials in z as (coefficient array, lowest power)
def lmul(a, b):
    return (np.convolve(a[0], b[0]), a[1] + b[1])


def y_factor(yr):
    # 1 - y / yr with y = (-z^-1 + 2 - z) / 4
    return (np.array([1.0 / (4.0 * yr), 1.0 - 2.0 / (4.0 * yr), 1.0 / (4.0 * yr)], dtype=complex), -1)


def half_one_plus_z(n):
    p = (np.array([1.0 + 0j]), 0)
    for _ in range(n):
        p = lmul(p, (np.array([0.5, 0.5], dtype=complex), 0))
    return p


def p_of_y(k):
    # P_K(y) as a Laurent polynomial in z
    y = (np.array([-0.25, 0.5, -0.25], dtype=complex), -1)
    acc = (np.array([0j]), 0)
    yp = (np.array([1.0 + 0j]), 0)
    for j, c in enumerate(p_coeffs(k)):
        if j > 0:
            yp = lmul(yp, y)
        # add c * yp aligned
        lo = min(acc[1], yp[1])
        hi = max(acc[1] + len(acc[0]), yp[1] + len(yp[0]))
        s = np.zeros(hi - lo, dtype=complex)
        s[acc[1] - lo:acc[1] - lo + len(acc[0])] += acc[0]
        s[yp[1] - lo:yp[1] - lo + len(yp[0])] += c * yp[0]
        acc = (s, lo)
    return acc


def taps(lp):
    c = lp[0] * SQRT2
    assert np.max(np.abs(c.imag)) < 1e-9
    return list(c.real)


def bior_pair(nr, nd):
    k = (nr + nd) // 2
    if (nr, nd) in BIOR_SPLIT:
        a, b, which = BIOR_SPLIT[(nr, nd)]
        groups = root_groups(y_roots(k))
        if which == 'real':
            rec_groups = [g for g in groups if abs(g.imag) < 1e-12]
        else:
            pairs = sorted([g for g in groups if abs(g.imag) >= 1e-12], key=abs)
            rec_groups = [pairs[which]]
        rec = half_one_plus_z(a)
        dec = half_one_plus_z(b)
        for g in groups:
            f = y_factor(g)
            if abs(g.imag) >= 1e-12:
                f = lmul(f, y_factor(np.conj(g)))
            if any(g is h for h in rec_groups):
                rec = lmul(rec, f)
            else:
                dec = lmul(dec, f)
        return taps(dec), taps(rec)
    rec = half_one_plus_z(nr)
    dec = lmul(half_one_plus_z(nd), p_of_y(k))
    return taps(dec), taps(rec)


def place(t, f, is_dec):
    """Centre the symmetric filter t in an array of length f."""
    n = len(t)
    if n % 2 == 0:
        off = (f - n) // 2
    else:
        centre = f // 2 if is_dec else f // 2 - 1
        off = centre - (n - 1) // 2
    out = [0.0] * f
    out[off:off + n] = t
    return out


BIOR_NAMES = [(1, 1), (1, 3), (1, 5), (2, 2), (2, 4), (2, 6), (2, 8), (3, 1), (3, 3), (3, 5),
              (3, 7), (3, 9), (4, 4), (5, 5), (6, 8)]


def all_bases():
    """[(name, family, dec_lo, rec_lo)] in the order of the C table."""
    out = []
    h = [SQRT2 / 2, SQRT2 / 2]
    out.append(('haar', 'haar', h[:], h[:]))
    for n in range(2, 11):
        rec = daubechies(n)
        out.append(('db%d' % n, 'daubechies', rec[::-1], rec))
    for n in range(2, 11):
        bits, rev = SYM_CHOICE[n]
        h = daubechies(n, bits)
        dec = h if rev == 0 else h[::-1]
        out.append(('sym%d' % n, 'symlets', dec, dec[::-1]))
    for n in range(1, 6):
        rec = COIF['coif%d' % n]
        out.append(('coif%d' % n, 'coiflets', rec[::-1], rec))
    pairs = {}
    for nr, nd in BIOR_NAMES:
        dec, rec = bior_pair(nr, nd)
        f = max(len(dec), len(rec))
        f += f % 2
        pairs[(nr, nd)] = (place(dec, f, True), place(rec, f, False))
    for nr, nd in BIOR_NAMES:
        dec, rec = pairs[(nr, nd)]
        out.append(('bior%d.%d' % (nr, nd), 'biorthogonal', dec, rec))
    for nr, nd in BIOR_NAMES:
        dec, rec = pairs[(nr, nd)]
        out.append(('rbio%d.%d' % (nr, nd), 'reverse biorthogonal', rec[::-1], dec[::-1]))
    return out


def c_array(vals):
    return ''.join('    %s,\n' % repr(float(v)) for v in vals)


def main():
    bases = all_bases()
    w = sys.stdout.write
    w('/* SPDX-License-Identifier: BSD-2-Clause */\n'
      '/* Generated by host-tools/ref/gen/gen_filters.py: do not edit.\n'
      ' * 1-D wavelet filters (PyWavelets conventions); derivations in the\n'
      ' * generator. */\n#include "bwr_filters.h"\n\n')
    for name, fam, dec, rec in bases:
        cid = name.replace('.', '_')
        w('static const double %s_dec_lo[%d] = {\n%s};\n' % (cid, len(dec), c_array(dec)))
        w('static const double %s_rec_lo[%d] = {\n%s};\n\n' % (cid, len(rec), c_array(rec)))
    w('const bwr_filter_t bwr_filters[BWR_NUM_FILTERS] = {\n')
    for name, fam, dec, rec in bases:
        cid = name.replace('.', '_')
        orth = 1 if fam in ('haar', 'daubechies', 'symlets', 'coiflets') else 0
        w('    {"%s", "%s", %d, %d, %s_dec_lo, %s_rec_lo},\n' % (name, fam, len(dec), orth, cid, cid))
    w('};\n')
    assert len(bases) == 54, len(bases)


if __name__ == '__main__':
    main()
