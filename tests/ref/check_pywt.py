#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""Checks the reference model's 1-D wavelets against PyWavelets.

For every basis bwref ships: the four filters, and the multi-level transform
(PyWavelets modes 'periodization' and 'symmetric', wavedec order) of test
signals of several lengths (even, odd, shorter than the filter) and depths,
coefficient by coefficient, plus the round trip. Prints one line per failure and "RESULT: N passed, M failed".

    check_pywt.py [BWREF]      (default build/host/bwref)
"""
import os
import subprocess
import sys
import tempfile

import warnings

import numpy as np
import pywt

# short signals at the maximum level: PyWavelets warns about boundary effects
warnings.simplefilter('ignore', UserWarning)

TOL = 1e-10
BWREF = sys.argv[1] if len(sys.argv) > 1 else 'build/host/bwref'


def parse(text):
    """bwref wavedec output -> {basis: {field: ...}}"""
    out = {}
    cur = None
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == 'basis':
            cur = {'levels': int(f[f.index('levels') + 1]), 'len': int(f[f.index('len') + 1])}
            out[f[1]] = cur
        elif f[0] in ('dec_lo', 'dec_hi', 'rec_lo', 'rec_hi', 'coef'):
            cur[f[0]] = np.array([float(v) for v in f[1:]])
        elif f[0] == 'lens':
            cur['lens'] = [int(v) for v in f[1:]]
        elif f[0] == 'roundtrip_max_abs':
            cur['rt'] = float(f[1])
    return out


def signal(n, seed):
    rng = np.random.RandomState(seed)
    t = np.linspace(0.0, 1.0, n)
    # a smooth part, a step, a peak and noise: every subband gets energy
    return (0.4 + 0.3 * np.sin(7.0 * t) + 0.2 * (t > 0.37) + np.exp(-((t - 0.7) / 0.02) ** 2)
            + 0.05 * rng.randn(n))


def main():
    passed = failed = 0
    names_seen = None

    def check(ok, what):
        nonlocal passed, failed
        if ok:
            passed += 1
        else:
            failed += 1
            print('FAIL:', what)

    cases = [('periodization', n, lv) for n, lv in
             ((256, None), (81, None), (1024, 3), (2151, None), (37, 1), (64, 2), (81, 'deep'),
              (71, 'deep'))]
    cases += [('symmetric', n, lv) for n, lv in ((256, None), (81, None), (71, 3), (13, 2), (500, 'deep'))]
    with tempfile.TemporaryDirectory() as tmp:
        for mode, n, levels in cases:
            x = signal(n, n)
            path = os.path.join(tmp, 'x.txt')
            np.savetxt(path, x, fmt='%.17g')
            cmd = [BWREF, 'wavedec', '-i', path, '--mode', mode]
            if levels is not None:
                cmd += ['--levels', str(levels)]
            res = subprocess.run(cmd, capture_output=True, text=True)
            if res.returncode != 0:
                check(False, '%s exited %d: %s' % (' '.join(cmd), res.returncode, res.stderr.strip()))
                continue
            got = parse(res.stdout)
            if names_seen is None:
                names_seen = sorted(got)
                # the shipped set: haar, db2-10, sym2-10, coif1-5, bior and rbio 1.1-6.8
                want = {'haar'} | {'db%d' % k for k in range(2, 11)} | \
                       {'sym%d' % k for k in range(2, 11)} | {'coif%d' % k for k in range(1, 6)}
                for b in pywt.wavelist(family='bior'):
                    want |= {b, b.replace('bior', 'rbio')}
                check(set(got) == want, 'shipped bases differ from the expected 54: %s' %
                      sorted(set(got) ^ want))
            for name, g in sorted(got.items()):
                w = pywt.Wavelet(name)
                what = '%s %s n=%d' % (name, mode, n)
                if n == 256 and mode == 'periodization':  # filters once
                    for fld in ('dec_lo', 'dec_hi', 'rec_lo', 'rec_hi'):
                        ref = np.array(getattr(w, fld))
                        mine = g.get(fld)
                        same_len = mine is not None and len(mine) == len(ref)
                        err = np.max(np.abs(mine - ref)) if same_len else float('inf')
                        check(err <= TOL, '%s %s differs from PyWavelets (max %.3g)' % (name, fld, err))
                if levels == 'deep':  # as many levels as shorten the signal, down to 2
                    lev, m = 0, n
                    while m > 2:
                        nm = (m + 1) // 2 if mode == 'periodization' else (m + w.dec_len - 1) // 2
                        if nm >= m:
                            break
                        m, lev = nm, lev + 1
                else:
                    lev = levels if levels is not None else pywt.dwt_max_level(n, w.dec_len)
                check(g['levels'] == lev, '%s: %d levels, expected %d' % (what, g['levels'], lev))
                ref = pywt.wavedec(x, w, mode=mode, level=lev)
                lens = [len(c) for c in ref]
                check(g['lens'] == lens, '%s: subband lengths %s, PyWavelets %s' % (
                    what, g['lens'], lens))
                if g['lens'] != lens:
                    continue
                refc = np.concatenate(ref)
                err = np.max(np.abs(g['coef'] - refc)) / max(1.0, np.max(np.abs(refc)))
                check(err <= TOL, '%s levels=%d: coefficients differ by %.3g' % (what, lev, err))
                rec = pywt.waverec(ref, w, mode=mode)[:n]
                check(np.max(np.abs(rec - x)) <= 1e-9, 'PyWavelets round trip %s' % what)
                check(g['rt'] <= 1e-12 * max(1.0, np.max(np.abs(x))),
                      '%s: round trip error %.3g' % (what, g['rt']))
    print('RESULT: %d passed, %d failed' % (passed, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
