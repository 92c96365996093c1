#!/usr/bin/python3
# SPDX-License-Identifier: BSD-2-Clause
"""make reproduce: the experiments of Claustres, Paulin and Boucher (2003) with
the float reference model (build/host/bwref), written to build/report/paper.md
with the paper's numbers beside ours, plus build/report/figure5.png.

Environment: BW (brdfwave CLI), BWREF (bwref), REPORT_DIR (build/report).
Needs python3-numpy; python3-matplotlib for the plot (skipped without it).
"""
import csv
import glob
import io
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
BW = os.environ.get('BW', 'build/host/brdfwave')
BWREF = os.environ.get('BWREF', 'build/host/bwref')
OUT = os.environ.get('REPORT_DIR', 'build/report')
WORK = os.path.join(OUT, 'work')
RATIOS = [1, 2, 8, 16, 64, 128, 256]

# ---- the paper's numbers (docs: /work/shared/paper/tables.md) --------------
# Table 2: r_c -> (Phong1 L1, L2, Phong2 L1, L2, Ward L1, L2)
PAPER_T2 = {
    1: (0, 0, 0, 0, 0, 0),
    2: (0.039, 0.089, 0.036, 0.1, 0.32, 0.076),
    8: (2, 3.1, 3.9, 7.4, 3.1, 5.4),
    16: (4, 6.2, 8.6, 15.6, 10, 22),
    64: (15, 20, 51, 69, 16, 28),
    128: (16, 21, 49, 65, 16, 30),
    256: (17, 23, 50, 65, 17, 31),
}
# Table 1 (Spectralon column only: the material we also have) and Table 3
# Table 1 Cloth and Plastic columns: r_c -> (Cloth L1, L2, Plastic L1, L2)
PAPER_T1_CLOTH_PLASTIC = {1: (0.26, 1, 0.19, 1), 2: (0.62, 1.1, 0.26, 1), 8: (1.8, 2.3, 1, 1.5),
                          16: (2.6, 3.2, 8.1, 11), 64: (4.2, 5.4, 36, 80), 128: (4.5, 5.9, 45, 100),
                          256: (4.9, 6.8, 48, 112)}
PAPER_T1_SPECTRALON = {1: (0.07, 0.33), 2: (0.12, 0.33), 8: (0.61, 0.76), 16: (1.2, 1.4),
                       64: (2.1, 2.5), 128: (2.8, 3.3), 256: (2.9, 3.5)}
PAPER_T3_SPECTRALON = {1: (0.078, 0.36), 2: (0.19, 0.4), 8: (0.29, 0.47), 16: (0.36, 0.56),
                       64: (1, 1.2), 128: (1.1, 1.4), 256: (1.1, 1.4)}
# Table 4: case -> (initial data, strips, total kB, compressed data, strips, total kB)
PAPER_T4 = {
    'mono isotropic': (16384, 2088, 237, 64, 23, 3),
    'mono anisotropic (Ward)': (1048576, 133250, 15136, 4444, 2225, 163),
    'spectral isotropic': (3281920, 411688, 46109, 13966, 8855, 617),
}


# a progress line on standard error, only when it is a terminal: the
# commands run so far, the time spent and the one running now
_PROGRESS = {'n': 0, 't0': time.time(), 'shown': 0}


def progress(text=None):
    if not sys.stderr.isatty():
        return
    if text is None:  # cleared
        line = ''
    else:
        _PROGRESS['n'] += 1
        line = 'reproduce: command %d, %.0f s: %s' % (_PROGRESS['n'],
                                                       time.time() - _PROGRESS['t0'], text)
        line = line[:max(20, shutil.get_terminal_size().columns - 1)]
    sys.stderr.write('\r' + line + ' ' * max(0, _PROGRESS['shown'] - len(line)) +
                     ('\r' if text is None else ''))
    sys.stderr.flush()
    _PROGRESS['shown'] = len(line)


def sh(*args):
    progress(' '.join(os.path.basename(str(a)) if k == 0 else str(a)
                      for k, a in enumerate(args[:4])))
    r = subprocess.run([str(a) for a in args], capture_output=True, text=True)
    if r.returncode != 0:
        progress()
        raise SystemExit('failed: %s\n%s' % (' '.join(map(str, args)), r.stderr.strip()))
    return r.stdout


def ratios(path, *args):
    """bwref ratios -> (initial row, [rows]) with numbers converted"""
    text = sh(BWREF, 'ratios', '-i', path, *args)
    rows = list(csv.DictReader(io.StringIO(text)))
    for r in rows:
        for k, v in r.items():
            if k not in ('target', 'basis') and v not in ('', None):
                r[k] = float(v)
    return rows[0], rows[1:]


def fmt(v, nd=3):
    """compact number like the paper's tables"""
    if v is None:
        return '-'
    if v == 0:
        return '0'
    a = abs(v)
    if a >= 100:
        return '%.0f' % v
    if a >= 0.01:
        s = '%.*g' % (nd, v)
        return s
    return '%.1e' % v


def pow2(n):
    k = math.log2(n) if n > 0 else 0
    return '2^%d' % round(k) if n > 0 and abs(k - round(k)) < 1e-9 else '%d' % n


def md_table(header, rows):
    out = ['| ' + ' | '.join(header) + ' |', '|' + '---|' * len(header)]
    out += ['| ' + ' | '.join(str(c) for c in r) + ' |' for r in rows]
    return '\n'.join(out) + '\n'


def differs(ours, paper):
    """more than a few percent apart (and not both negligible)"""
    if paper == 0 and ours < 1e-6:
        return False
    return abs(ours - paper) > 0.05 * max(abs(paper), 1e-12) and abs(ours - paper) > 0.02


def read_sed(path):
    lines = open(path, encoding='latin-1').read().splitlines()
    start = [k for k, l in enumerate(lines) if l.startswith('Data:')][0] + 2
    rows = [l.split() for l in lines[start:] if l.strip()]
    return np.array([float(r[0]) for r in rows]), np.array([float(r[-1]) for r in rows])


def write_f64(path, a):
    np.ascontiguousarray(a, dtype='<f8').tofile(path)


def f32_metrics(ref, test):
    r = ref.astype(np.float64)
    t = test.astype(np.float64)
    nz = r != 0
    rel = (t[nz] - r[nz]) / r[nz]
    return 100 * np.mean(np.abs(rel)), 100 * math.sqrt(np.mean(rel * rel)), np.max(np.abs(t - r))


class Report:
    def __init__(self):
        self.parts = []
        self.notes = []

    def add(self, s):
        self.parts.append(s)


def main():
    t0 = time.time()
    os.makedirs(WORK, exist_ok=True)
    R = Report()
    p = lambda name: os.path.join(WORK, name)

    # ---- synthetic sets (the paper's Table 2 and Figure 5) -----------------
    sh(BW, 'synth', '--model', 'phong', '--kd', '0.75', '--ks', '0.25', '--n', '20', '--level', '4',
       '--incoming', '16', '-o', p('phong1.f32'))
    sh(BW, 'synth', '--model', 'phong', '--kd', '0.5', '--ks', '0.5', '--n', '50', '--level', '4',
       '--incoming', '16', '-o', p('phong2.f32'))
    sh(BW, 'synth', '--model', 'ward', '--ax', '0.35', '--ay', '0.05', '--kd', '0.75', '--ks',
       '0.25', '--level', '4', '--level-in', '4', '-o', p('ward.f32'))
    sh(BW, 'synth', '--model', 'phong', '--kd', '0.75', '--ks', '0.25', '--n', '30', '--level', '4',
       '--level-in', '4', '-o', p('phong30.f32'))
    iso = ['--level', '4', '--incoming', '16']
    full = ['--level', '4', '--level-in', '4']
    rule_paper = ['--magnitude', 'raw', '--keep-coarse', '1']
    rule_l2 = ['--magnitude', 'l2', '--keep-coarse', '1']
    ratio_arg = ['--ratios', ','.join(str(r) for r in RATIOS)]
    t2 = {}
    for rule, rargs in (('paper', rule_paper), ('l2', rule_l2)):
        for name, shape in (('phong1', iso), ('phong2', iso), ('ward', full)):
            t2[(rule, name)] = ratios(p(name + '.f32'), *shape, *rargs, *ratio_arg)

    R.add('# The paper\'s results with the float reference model\n\n'
          'Claustres, Paulin and Boucher, *BRDF Measurement Modelling using Wavelets for '
          'Efficient Path Tracing* (Computer Graphics Forum, 2003), reproduced with the double-'
          'precision reference model in `host-tools/ref` (`bwref`), which shares no code with '
          'the fixed-point codec. Generated by `make reproduce` (%s). Errors are the paper\'s '
          'relative L1 and L2 in percent (eq. 7 and 8); r_c is the ratio of samples to '
          'coefficients kept.\n\n' % time.strftime('%Y-%m-%d'))
    R.add('**Model.** Bio-Haar on the geodesic hemisphere with d_m = s_m - s_0 (m = 1..3, '
          'relative to the centre child) and s_P = sum L_i s_i, L_i = a_i / a_P (solid angles); '
          'this is Schroeder and Sweldens\' Bio-Haar up to a factor 2 in the details. Isotropic '
          'sets transform the outgoing hemisphere only (sec. 5.2), the full BRDF both '
          'hemispheres, incoming first (sec. 4.2). Spectral and angular axes: 1-D wavelets '
          'identical to PyWavelets\' mode \'periodization\' (or \'symmetric\' where said), '
          '54 bases, `make check` comparing every one coefficient by coefficient; decomposed '
          'down to 2 coefficients unless said otherwise.\n\n'
          '**Which coefficients are kept.** To reach r_c exactly, all coefficients are ranked by '
          'magnitude and the n/r_c largest are kept. Two rankings are reported:\n\n'
          '* *paper\'s rule*: the plain threshold of sec. 4.3 on coefficient values |c|, with '
          'the coarsest scaling coefficients always kept. This is the rule that reproduces the '
          'shape of the paper\'s Table 2 (errors that level off from 64:1 on, at the error of '
          'the scaling coefficients alone), so it is our reading of how the paper was computed;\n'
          '* *L2 rule*: |c| times the L2 norm of its basis function (sqrt(a_m (1 - L_m)) on the '
          'sphere, the synthesis norm on 1-D axes), the ranking that minimises the absolute '
          'L2 error for an orthogonal basis (the Bio-Haar wavelets of different parents are '
          'orthogonal).\n\n')

    # ---- Table 2 --------------------------------------------------------------
    hdr = ['r_c', '#coef', 'Phong1 L1 paper', 'ours', 'Phong1 L2 paper', 'ours',
           'Phong2 L1 paper', 'ours', 'Phong2 L2 paper', 'ours', '#coef Ward',
           'Ward L1 paper', 'ours', 'Ward L2 paper', 'ours']
    flagged = {}
    for rule, title in (('paper', 'paper\'s rule'), ('l2', 'L2 rule')):
        rows = []
        for k, rc in enumerate(RATIOS):
            pp = PAPER_T2[rc]
            a = t2[(rule, 'phong1')][1][k]
            b = t2[(rule, 'phong2')][1][k]
            w = t2[(rule, 'ward')][1][k]
            cells = [('Phong1 L1', a['rel_l1'], pp[0]), ('Phong1 L2', a['rel_l2'], pp[1]),
                     ('Phong2 L1', b['rel_l1'], pp[2]), ('Phong2 L2', b['rel_l2'], pp[3]),
                     ('Ward L1', w['rel_l1'], pp[4]), ('Ward L2', w['rel_l2'], pp[5])]
            out = []
            for name, ours, paper in cells:
                mark = ''
                if rule == 'paper' and differs(ours, paper):
                    flagged.setdefault(name.split()[0], []).append((rc, name, paper, ours))
                    mark = ' *'
                out.append((fmt(paper), fmt(ours) + mark))
            rows.append(['%d:1' % rc, '%s (%d)' % (pow2(16384 // rc), a['kept']),
                         out[0][0], out[0][1], out[1][0], out[1][1], out[2][0], out[2][1],
                         out[3][0], out[3][1], '%s (%d)' % (pow2(1048576 // rc), w['kept']),
                         out[4][0], out[4][1], out[5][0], out[5][1]])
        R.add('## Table 2: synthetic data sets, level 4 (%s)\n\n' % title)
        if rule == 'paper':
            R.add('Phong (1): kd = 0.75, ks = 0.25, n = 20; Phong (2): kd = 0.5, ks = 0.5, '
                  'n = 50; isotropic: 16 incoming directions in the plane phi = 0 '
                  '(theta_k = (k + 1/2) 90/16 deg) x 1024 outgoing triangle centres = 2^14 '
                  'samples, outgoing transform only. Ward: ax = 0.35, ay = 0.05, kd = 0.75, '
                  'ks = 0.25, 1024 x 1024 = 2^20 samples, both hemispheres. Generated by '
                  '`brdfwave synth` (float32). #coef: the paper\'s count (ours in brackets: '
                  'fewer when the set has fewer non-zero coefficients). * = more than 5 % '
                  '(and 0.02 points) away from the paper.\n\n')
        R.add(md_table(hdr, rows) + '\n')
    nz = {n: int(t2[('paper', n)][1][0]['kept']) for n in ('phong1', 'phong2', 'ward')}
    pr = {n: t2[('paper', n)][1] for n in ('phong1', 'phong2', 'ward')}
    lv = {n: t2[('l2', n)][1] for n in ('phong1', 'phong2', 'ward')}
    idx = {rc: k for k, rc in enumerate(RATIOS)}
    within = [('Phong %d' % (1 if n == 'phong1' else 2), rc) for n in ('phong1', 'phong2')
              for rc in (16, 64, 128, 256)
              if abs(pr[n][idx[rc]]['rel_l1'] - PAPER_T2[rc][0 if n == 'phong1' else 2]) <=
              0.15 * PAPER_T2[rc][0 if n == 'phong1' else 2]]
    below, total, above = 0, 0, []
    for n, col, label in (('phong1', 1, 'Phong 1'), ('phong2', 3, 'Phong 2'), ('ward', 5, 'Ward')):
        for rc in RATIOS[2:]:
            total += 1
            if lv[n][idx[rc]]['rel_l2'] < PAPER_T2[rc][col]:
                below += 1
            else:
                above.append('%s %d:1' % (label, rc))
    R.add('**Why ours differ where they do.**\n\n'
          '* *1:1 and 2:1.* Our sets have only %d (Phong 1), %d (Phong 2) and %d (Ward) non-zero '
          'coefficients of 16,384 / 16,384 / 1,048,576: where the lobe vanishes the BRDF is '
          'exactly kd/pi in float32, so those details are exactly zero. At 2:1 nothing (Phong 2, '
          'Ward) or only tiny coefficients (Phong 1) are dropped, hence errors of 1e-6 %% or '
          'less instead of the paper\'s 0.04-0.3 %%. The paper\'s sets evidently had no exact '
          'zeros (another sampling of the directions, or noise from its virtual goniometer, '
          'which it does not describe).\n'
          '* *Ward at 2:1* the paper prints L1 = 0.32 > L2 = 0.076, which no data can give '
          '(the relative RMS error is never below the mean absolute relative error): that cell '
          'is a misprint.\n'
          '* *Phong 1 and 2 from 16:1 on.* With the paper\'s rule our L1 is within 15 %% of the '
          'paper\'s at %s, and both level off where the paper\'s do: at 256:1 only the 64 '
          'scaling coefficients (4 per incoming direction) remain, giving %s / %s %% (Phong 1) '
          'and %s / %s %% (Phong 2) against the paper\'s 17 / 23 and 50 / 65. Where ours are '
          'lower (Phong 1 at 64:1: %s / %s against 15 / 20; all sets at 8:1) the paper kept a '
          'different set of coefficients of about equal size: the scale of its details '
          '(Schroeder and Sweldens\' factor 1/2, or none) and the exact incoming directions '
          'decide which are cut, and the paper gives neither precisely.\n'
          '* *Ward* is thresholded per space in the paper (incoming objects first) with '
          'thresholds it does not give; our rows keep the same number of coefficients with one '
          'ranking over all of them, so they compare in count, not in the set kept. Our errors '
          'are of the paper\'s order up to 64:1 and higher after (L2 %s at 256:1 against 31): '
          'the raw ranking drops the small, wide incoming details that relative errors need.\n'
          '* The L2 rule minimises absolute L2, not the paper\'s relative errors; still its '
          'relative L2 is below the paper\'s in %d of the %d cells from 8:1 on%s.\n\n'
          % (nz['phong1'], nz['phong2'], nz['ward'],
             ', '.join('%s %d:1' % w for w in within) or 'no ratio',
             fmt(pr['phong1'][idx[256]]['rel_l1']), fmt(pr['phong1'][idx[256]]['rel_l2']),
             fmt(pr['phong2'][idx[256]]['rel_l1']), fmt(pr['phong2'][idx[256]]['rel_l2']),
             fmt(pr['phong1'][idx[64]]['rel_l1']), fmt(pr['phong1'][idx[64]]['rel_l2']),
             fmt(pr['ward'][idx[256]]['rel_l2']),
             below, total, (' (not at ' + ', '.join(above) + ')') if above else ''))
    if flagged:
        R.add('Cells marked * (paper\'s rule): ' + '; '.join(
            '%s at %d:1 (paper %s, ours %s)' % (name, rc, fmt(pv), fmt(ov))
            for grp in flagged.values() for rc, name, pv, ov in grp) + '.\n\n')

    # ---- Figure 5 ---------------------------------------------------------------
    fig_ratios = [2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096]
    f5 = {}
    for rule, rargs in (('paper', rule_paper), ('l2', rule_l2)):
        f5[rule] = ratios(p('phong30.f32'), *full, *rargs,
                          '--ratios', ','.join(str(r) for r in fig_ratios))[1]
    R.add('## Figure 5: Phong n = 30, compression rate against relative L2\n\n'
          'Full BRDF, level 4 on both hemispheres (2^20 samples, the resolution the paper '
          'compares with Lalonde and Fournier); kd = 0.75, ks = 0.25 (the paper gives only '
          'the exponent). t_c = 100 (1 - 1/r_c). The paper\'s curve is a figure without '
          'numbers, and Lalonde\'s is not available to us, so only ours are listed.\n\n')
    rows = []
    for k, rc in enumerate(fig_ratios):
        a, b = f5['paper'][k], f5['l2'][k]
        rows.append(['%d:1' % rc, '%.2f' % (100 * (1 - 1 / rc)), int(a['kept']),
                     fmt(a['rel_l2']), fmt(b['rel_l2'])])
    R.add(md_table(['r_c', 't_c %', '#coef', 'rel. L2 %, paper\'s rule', 'rel. L2 %, L2 rule'],
                   rows) + '\n')
    try:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 4))
        tc = [100 * (1 - 1 / r) for r in fig_ratios]
        ax.plot(tc, [r['rel_l2'] for r in f5['paper']], 'o-', label='paper\'s rule (|c|)')
        ax.plot(tc, [r['rel_l2'] for r in f5['l2']], 's-', label='L2 rule')
        ax.set_xlabel('compression rate t_c (%)')
        ax.set_ylabel('relative L2 error (%)')
        ax.set_title('Phong n = 30, full BRDF, level 4 (2^20 samples)')
        ax.grid(True, alpha=0.3)
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(OUT, 'figure5.png'), dpi=110)
        R.add('![Figure 5](figure5.png)\n\n')
    except ImportError:
        R.add('(matplotlib is not installed: no plot.)\n\n')

    # ---- real data ----------------------------------------------------------------
    spec = np.loadtxt(os.path.join(ROOT, 'tests/data/spectralon/BRF_normalization_factor.csv'),
                      delimiter=',')
    angles, A = spec[:, 0], spec[:, 1:]
    lam = np.arange(350, 2501)
    seds = sorted(glob.glob(os.path.join(ROOT, 'tests/data/field_psr3500/*.sed')))
    field = [read_sed(s) for s in seds]
    fwl = field[0][0]
    F = np.array([f[1] for f in field])
    vis = np.arange(430, 831, 5)
    Fvis = np.array([np.interp(vis, fwl, f) for f in F])
    Avis = A[:, vis - 350]
    ddrf = np.loadtxt(os.path.join(ROOT, 'tests/data/spectralon/'
                                   'Spectralon-panel-4-diffuse-reflectance_2023Jan18.txt'),
                      delimiter=',', comments='#')[:, 1]
    write_f64(p('spectralon_A.f64'), A)
    write_f64(p('spectralon_A_vis.f64'), Avis)
    write_f64(p('field.f64'), F)
    write_f64(p('field_vis.f64'), Fvis)
    write_f64(p('ddrf.f64'), ddrf)

    R.add('## Real data (not the paper\'s samples)\n\n'
          'The paper\'s goniometer measurements (ONERA: Spectralon, cloth, plastic, grass, sand, '
          'melamine; 474 directions x 1024 wavelengths) are not public. We have:\n\n'
          '* the Spectralon panel model data of grit-lab (RIT, MIT licence, '
          '`tests/data/spectralon`): A(theta_i, lambda), 71 incidence angles (0-70 deg) x '
          '2151 wavelengths (350-2500 nm), a normalisation factor the authors derived from '
          'their measurements (smooth, printed to 9 digits), and the panel\'s measured diffuse '
          'reflectance (2151 bands);\n'
          '* 60 field reflectance spectra of a Spectral Evolution PSR-3500 (MIT licence, '
          '`tests/data/field_psr3500`), 1024 bands 343-2504 nm, 5 printed decimals;\n'
          '* three measured BRDFs of the RGL database (RGB).\n\n'
          'Only the RGL BRDFs sample a hemisphere; for the others the spherical transform has '
          'nothing to act on: the angular axis of the Spectralon set gets a 1-D wavelet '
          'instead (the same '
          'generic transform with Spectrum objects as elements), and the field spectra are a '
          'set of Spectrum objects. The numbers are therefore not comparable with the paper\'s '
          'tables cell by cell; the paper\'s Spectralon column is printed beside ours for '
          'scale only.\n\n')

    # Table 1-style on measured BRDFs: RGL materials, green channel, isotropic
    rgl = [('paper_white', 'white paper'), ('satin_rosaline', 'satin vinyl film'),
           ('cc_ibiza_sunset', 'glossy vinyl film')]
    rgl_rows = {}
    rgl_info = {}
    for key, label in rgl:
        out = p('rgl_%s.f32' % key)
        info = sh(BWREF, 'import-rgl', '-i', os.path.join(ROOT, 'tests/data/rgl/%s_rgb.bsdf' % key),
                  '-o', out, '--level', '4', '--channel', 'g')
        nin = int([l for l in info.splitlines() if l.startswith('incoming:')][0].split()[1])
        data = np.fromfile(out, dtype='<f4').astype(np.float64)
        rgl_info[key] = (info, nin, data.mean(), np.mean(data < 0.05 * np.median(data)))
        for rule, rargs in (('paper', rule_paper), ('l2', rule_l2)):
            rgl_rows[(key, rule)] = ratios(out, '--level', '4', '--incoming', str(nin), *rargs,
                                           *ratio_arg)[1]
    nin = rgl_info['paper_white'][1]
    R.add('### Table 1-style: measured BRDFs at one wavelength (RGL database, green channel)\n\n'
          'Three measured isotropic BRDFs of the EPFL RGL database (Dupuy and Jakob 2018, CC0, '
          '`tests/data/rgl`), sampled by `bwref import-rgl` (inversion of the authors\' VNDF '
          'warp, as their reference loader does) at the %d measured incidence angles below '
          '89 degrees (plane phi = 0) x 1024 outgoing triangle centres of level 4 = %d samples '
          '(the paper: 16 x 1024). Green channel of the RGB files, i.e. one broad band, as the '
          'paper\'s fixed wavelength. Outgoing transform only, as sec. 5.2. Cells: L1 / L2 %% '
          '(eq. 7-8) and, in brackets, the RMS error relative to the mean value (NRMSE %%). The '
          'paper\'s Cloth and Plastic columns for scale (other materials, other instrument).\n\n'
          % (nin, nin * 1024))
    for rule, title in (('paper', 'paper\'s rule'), ('l2', 'L2 rule')):
        rows = []
        for k, rc in enumerate(RATIOS):
            row = ['%d:1' % rc, int(rgl_rows[('paper_white', rule)][k]['kept'])]
            for key, label in rgl:
                r = rgl_rows[(key, rule)][k]
                row.append('%s / %s (%s)' % (fmt(r['rel_l1']), fmt(r['rel_l2']),
                                             fmt(100 * r['rmse'] / rgl_info[key][2])))
            pc = PAPER_T1_CLOTH_PLASTIC[rc]
            row += ['%s / %s' % (fmt(pc[0]), fmt(pc[1])), '%s / %s' % (fmt(pc[2]), fmt(pc[3]))]
            rows.append(row)
        R.add('*%s*\n\n' % title.capitalize())
        R.add(md_table(['r_c', '#coef'] + [label for _, label in rgl] +
                       ['paper Cloth', 'paper Plastic'], rows) + '\n')
    def vrange(key):
        line = [l for l in rgl_info[key][0].splitlines() if l.startswith('values:')][0]
        f = line.replace(',', ' ').split()
        return float(f[f.index('min') + 1]), float(f[f.index('max') + 1])
    pw, sat, gl = vrange('paper_white'), vrange('satin_rosaline'), vrange('cc_ibiza_sunset')
    l2pw = rgl_rows[('paper_white', 'l2')]
    R.add('Measured data are harder than the paper\'s goniometer sets here for two reasons. '
          'The tables hold zeros where the outgoing direction of a cell falls below the '
          'horizon, and near the horizon at grazing incidence the loader interpolates against '
          'them; and the grazing incidences carry a strong forward-scattering peak. So even '
          'the white paper, nearly Lambertian in the middle of the hemisphere (about 0.27 / sr, '
          'see the tests), spans %s to %s / sr (%.1f %% of its samples are below 5 %% of the '
          'median): those few samples dominate the relative errors of eq. 7-8, while its NRMSE '
          'is %s %% at 2:1 and %s %% at 8:1 (L2 rule), against the paper\'s Spectralon at '
          '0.33 and 0.76 %% L2. The satin film (%s to %s / sr) matches the paper\'s cloth '
          'at 2:1 and falls behind after. The glossy film (%s to %s / sr: a specular peak four '
          'orders of magnitude above its diffuse level) shows the paper\'s plastic behaviour, '
          'in the extreme: '
          'relative errors in the thousands of percent as soon as coefficients of the peak '
          'region are dropped, although its NRMSE stays at a few percent up to 8:1.\n\n'
          % (fmt(pw[0]), fmt(pw[1]), 100 * rgl_info['paper_white'][3],
             fmt(100 * l2pw[1]['rmse'] / rgl_info['paper_white'][2]),
             fmt(100 * l2pw[2]['rmse'] / rgl_info['paper_white'][2]),
             fmt(sat[0]), fmt(sat[1]), fmt(gl[0]), fmt(gl[1])))

    # Table 1-style: fixed wavelength, along the 71 incidence angles
    deep = ['--spec-levels', 'deep']
    t1 = {}
    for wl in (600, 700, 800):
        path = p('spectralon_A_%d.f64' % wl)
        write_f64(path, A[:, wl - 350])
        t1[wl] = ratios(path, '--format', 'f64', '--bands', '71', '--basis', 'best', *deep,
                        *rule_l2, *ratio_arg)[1]
    rows = []
    for k, rc in enumerate(RATIOS):
        row = ['%d:1' % rc, int(t1[800][k]['kept'])]
        for wl in (600, 700, 800):
            row += ['%s / %s (%s)' % (fmt(t1[wl][k]['rel_l1']), fmt(t1[wl][k]['rel_l2']),
                                      t1[wl][k]['basis'])]
        row += ['%s / %s' % (fmt(PAPER_T1_SPECTRALON[rc][0]), fmt(PAPER_T1_SPECTRALON[rc][1]))]
        rows.append(row)
    R.add('### Table 1-style: one wavelength, Spectralon A(theta_i) along 71 incidence angles\n\n'
          'The angular profile as one signal, 1-D wavelet down to 2 coefficients, best of the '
          '54 bases at each ratio, L2 rule; cells L1 / L2 % (basis). 71 samples cannot go '
          'beyond 71:1 (one coefficient). The paper\'s Table 1 Spectralon column (2^14 samples '
          'over both hemispheres at 800 nm) for scale.\n\n')
    R.add(md_table(['r_c', '#coef', '600 nm', '700 nm', '800 nm', 'paper Spectralon 800 nm'],
                   rows) + '\n')
    R.add('A changes by about 30 % over 70 degrees, smoothly, so a handful of coefficients '
          'reproduce it; the paper\'s goniometer data carry measurement noise (its 1:1 row, '
          '0.07 / 0.33 %, is the error of projecting the measurements on the sphere), hence its '
          'larger errors at the low ratios.\n\n')

    # Table 3-style: spectral sets, best of 54 bases at each ratio
    sets3 = [
        ('Spectralon A, 71 angles x 81 bands (430-830 nm / 5 nm)', p('spectralon_A_vis.f64'),
         ['--bands', '81', '--in-basis', 'db2', '--in-levels', 'deep']),
        ('Spectralon A, 71 angles x 2151 bands (350-2500 nm)', p('spectralon_A.f64'),
         ['--bands', '2151', '--in-basis', 'db2', '--in-levels', 'deep']),
        ('field spectra, 60 x 81 bands (430-830 nm / 5 nm, interpolated)', p('field_vis.f64'),
         ['--bands', '81', '--per-object', '1']),
        ('field spectra, 60 x 1024 bands (343-2504 nm)', p('field.f64'),
         ['--bands', '1024', '--per-object', '1']),
        ('Spectralon diffuse reflectance, 1 x 2151 bands', p('ddrf.f64'), ['--bands', '2151']),
    ]
    t3 = []
    for title, path, args in sets3:
        init, rows3 = ratios(path, '--format', 'f64', *args, '--basis', 'best', *deep, *rule_l2,
                             *ratio_arg)
        t3.append((title, init, rows3))
    R.add('### Table 3-style: spectral sets (best of the 54 bases at each ratio, L2 rule)\n\n'
          'Like the paper (sec. 5.2.3) the spectral basis is chosen at compression time as the '
          'one of lowest L2 error (eq. 8). Spectral axis: 1-D wavelet down to 2 coefficients; '
          'the Spectralon sets also get a db2 wavelet across the 71 angles, whose elements are '
          'whole spectra (the generic transform); the field spectra are 60 unrelated targets, '
          'so each is compressed to the same ratio on its own. The visible sets are decimated '
          'to the paper\'s 430-830 nm every 5 nm (81 bands). Each cell: L1 / L2 % (basis, '
          'coefficients kept); 1:1 keeps every coefficient (odd lengths give a few more '
          'coefficients than samples).\n\n')
    hdr = ['r_c'] + [t[0] for t in t3] + ['paper Spectralon (Table 3) L1 / L2']
    rows = []
    for k, rc in enumerate(RATIOS):
        row = ['%d:1' % rc]
        for title, init, rows3 in t3:
            r = rows3[k]
            row.append('%s / %s (%s, %d coef)' % (fmt(r['rel_l1']), fmt(r['rel_l2']), r['basis'],
                                                  r['kept']))
        row.append('%s / %s' % (fmt(PAPER_T3_SPECTRALON[rc][0]), fmt(PAPER_T3_SPECTRALON[rc][1])))
        rows.append(row)
    R.add(md_table(hdr, rows) + '\n')
    fv = t3[2][2]
    R.add('The Spectralon factor is a smooth model quantity (printed to 9 digits, hence the '
          '1e-8 %% floor) and compresses to negligible error, far below the paper\'s measured '
          'Spectralon. The field spectra are the hard case: vegetation and soil, reflectance '
          'from about 0.02 (blue, red, water bands) to 0.7 (near infrared) with a steep red '
          'edge, and the relative metrics weigh the dark bands most; each 81-band spectrum '
          'keeps %d coefficients at 8:1 (L2 %s %%) and %d at 16:1 (L2 %s %%). The paper\'s '
          'spectral sets share each spectrum\'s shape over 16 x 1024 directions, so its '
          'spherical transform packs them far better than 60 unrelated spectra can be: ours '
          'are not comparable with its Table 3 beyond 2:1.\n\n'
          % (round(fv[2]['kept'] / 60), fmt(fv[2]['rel_l2']), round(fv[3]['kept'] / 60),
             fmt(fv[3]['rel_l2'])))

    # extension: periodization against symmetric on the visible field spectra
    ext_rows = []
    per = ratios(p('field_vis.f64'), '--format', 'f64', '--bands', '81', '--per-object', '1',
                 '--basis', 'best', *deep, *rule_l2, *ratio_arg)[1]
    sym = ratios(p('field_vis.f64'), '--format', 'f64', '--bands', '81', '--per-object', '1',
                 '--basis', 'best', '--extension', 'symmetric', *deep, *rule_l2, *ratio_arg)[1]
    for k, rc in enumerate(RATIOS):
        ext_rows.append(['%d:1' % rc, '%s / %s (%s, %d)' % (fmt(per[k]['rel_l1']),
                                                          fmt(per[k]['rel_l2']), per[k]['basis'],
                                                          per[k]['kept']),
                         '%s / %s (%s, %d)' % (fmt(sym[k]['rel_l1']), fmt(sym[k]['rel_l2']),
                                              sym[k]['basis'], sym[k]['kept'])])
    R.add('Extension of the spectral axis on the visible field spectra (both are PyWavelets '
          'modes and exactly invertible): periodization wraps the blue end onto the near-'
          'infrared end, a jump of 0.02 to 0.6; the half-sample symmetric extension has no jump '
          'but gives more coefficients than samples (at 1:1). L1 / L2 % (basis, coefficients '
          'kept):\n\n')
    R.add(md_table(['r_c', 'periodization', 'symmetric'], ext_rows) + '\n')

    # best-basis ranking on one set
    fam_rows = []
    for fname in ('haar', 'db2', 'db4', 'db8', 'sym4', 'sym8', 'coif1', 'coif3', 'bior2.2',
                  'bior4.4', 'bior6.8', 'rbio2.2', 'rbio3.9'):
        _, r = ratios(p('field_vis.f64'), '--format', 'f64', '--bands', '81', '--basis', fname,
                      '--per-object', '1', *deep, *rule_l2, '--ratios', '4')
        fam_rows.append([fname, fmt(r[0]['rel_l1']), fmt(r[0]['rel_l2'])])
    R.add('Some of the 54 bases on the visible field spectra at 4:1 (relative L1 / L2 %, '
          'periodization):\n\n')
    R.add(md_table(['basis', 'L1', 'L2'], fam_rows) + '\n')

    # ---- Table 4 -----------------------------------------------------------------
    R.add('## Table 4-style: memory at 256:1\n\n'
          'Sparse arrays of strips of B_s = 32 elements (sec. 4.3): data = values kept x 8 '
          'bytes (doubles, as the paper: 16,384 values = 128 kB); strips x 8 bytes (32-bit '
          'valid index + 32-bit strip number; strips kept in one array sorted by number, so '
          'no list pointers). *nested*: one sparse array per object as in sec. 4.2 (incoming '
          'array of sparse spheres of sparse spectra), *flat*: one array over all '
          'coefficients in coarse-to-fine order. kB = 1024 bytes. The paper\'s cases are a '
          'measured Spectralon (2^14), the Ward set and a spectral Spectralon (3.3 M samples); '
          'ours are the synthetic Phong 1 and the measured RGL white paper, the same Ward set, '
          'and the Spectralon A set (71 x 2151).\n\n')
    cases = [('mono isotropic', 'Phong 1 (synthetic)', p('phong1.f32'),
              ['--level', '4', '--incoming', '16'], []),
             ('mono isotropic', 'RGL white paper, 7 x 1024 (measured)', p('rgl_paper_white.f32'),
              ['--level', '4', '--incoming', str(rgl_info['paper_white'][1])], []),
             ('mono anisotropic (Ward)', 'Ward (synthetic)', p('ward.f32'),
              ['--level', '4', '--level-in', '4'], []),
             ('spectral isotropic', 'Spectralon A 71 x 2151 (paper: spectral Spectralon)',
              p('spectralon_A.f64'), ['--format', 'f64', '--bands', '2151', '--in-basis', 'db2',
                                      '--in-levels', 'deep', '--basis', 'db4', '--spec-levels',
                                      'deep'], [])]
    rows = []
    per_strip = []
    shown = set()
    for key, label, path, args, _ in cases:
        init, r = ratios(path, *args, *rule_l2, '--ratios', '256')
        r = r[0]
        pp = PAPER_T4[key]
        kb = lambda b: '%.1f' % (b / 1024.0)
        per_strip.append(r['values'] / max(1, r['strips_flat']))
        if key not in shown:
            rows.append([label, 'paper', '%d' % pp[0], '%d' % pp[1], '%d' % pp[2], '%d' % pp[3],
                         '%d' % pp[4], '%d' % pp[5]])
            shown.add(key)
        else:
            rows.append([label, '', '', '', '', '', '', ''])
        rows.append(['', 'ours, nested', '%d (%s kB)' % (init['values'], kb(8 * init['values'])),
                     '%d' % init['strips_nested'], kb(init['bytes_nested']),
                     '%d (%s kB)' % (r['values'], kb(8 * r['values'])), '%d' % r['strips_nested'],
                     kb(r['bytes_nested'])])
        rows.append(['', 'ours, flat', '', '%d' % init['strips_flat'], kb(init['bytes_flat']), '',
                     '%d' % r['strips_flat'], kb(r['bytes_flat'])])
    R.add(md_table(['case', '', 'initial data', 'initial strips', 'initial total kB',
                    '256:1 data', '256:1 strips', '256:1 total kB'], rows) + '\n')
    R.add('The paper\'s initial rows hold about 8 values per strip (16,384 / 2088) where dense '
          'strips of 32 hold 32, and spend about 40 bytes per strip (84 kB / 2088), and its '
          'totals add "extra memory cost due to our actual implementation"; ours count only '
          'the index and the strip number. What carries over is the paper\'s observation: '
          'before compression data dominate, after compression (%.1f to %.1f values per strip '
          'at 256:1, the paper 1.6 to 2.8) localisation is a large share of the memory.\n\n'
          % (min(per_strip), max(per_strip)))

    # ---- the fixed-point codec against the reference ----------------------------
    R.add('## The fixed-point codec against the reference, at matched payload sizes\n\n'
          '`brdfwave encode --bytes B` (integer lifting, quantisation, range-coded strips) '
          'against the reference keeping the most coefficients whose flat strip storage '
          '(float32 values + 8 bytes per strip) fits in the same B bytes (L2 rule, db4 or '
          'the isotropic Bio-Haar). Budgets are 4 x samples / R, i.e. R:1 against float32.\n\n')
    rows = []
    write_f32 = lambda path, a: np.ascontiguousarray(a, dtype='<f4').tofile(path)
    write_f32(p('field.f32'), F)
    write_f32(p('spectralon_A.f32'), A)
    codec_sets = [
        ('Phong 1 (16 x 1024)', p('phong1.f32'), ['--bands', '1', '--level', '4', '--incoming',
                                                  '16'], ['--level', '4', '--incoming', '16']),
        ('field spectra (60 x 1024)', p('field.f32'), ['--bands', '1024'],
         ['--bands', '1024', '--basis', 'db4', '--spec-levels', 'deep']),
        ('Spectralon A (71 x 2151)', p('spectralon_A.f32'), ['--bands', '2151'],
         ['--bands', '2151', '--basis', 'db4', '--spec-levels', 'deep', '--in-basis', 'db2',
          '--in-levels', 'deep']),
    ]
    for title, path, cargs, rargs in codec_sets:
        ref = np.fromfile(path, dtype='<f4')
        for rr in (8, 32, 128):
            budget = 4 * ref.size // rr
            bwv = p('codec.bwv')
            dec = p('codec_dec.f32')
            try:
                sh(BW, 'encode', '-i', path, '-o', bwv, *cargs, '--bytes', budget)
                sh(BW, 'decode', '-i', bwv, '-o', dec)
                got = np.fromfile(dec, dtype='<f4')
                cb = os.path.getsize(bwv)
                c1, c2, cm = f32_metrics(ref, got)
                ccell = [str(cb), fmt(c1), fmt(c2), fmt(cm)]
            except SystemExit as e:
                ccell = ['(failed: %s)' % str(e).splitlines()[-1][:60], '-', '-', '-']
            _, r = ratios(path, *rargs, '--value-bytes', '4', '--bytes', str(budget), *rule_l2)
            r = r[0]
            rows.append([title, '%d:1' % rr, budget] + ccell +
                        [int(r['kept']) if r['kept'] else 0, int(r['bytes_flat'] or 0),
                         fmt(r['rel_l1']), fmt(r['rel_l2']), fmt(r['max_abs'])])
    R.add(md_table(['set', 'R', 'budget B', 'codec bytes', 'codec L1 %', 'codec L2 %',
                    'codec max err', 'ref. coef', 'ref. bytes', 'ref. L1 %', 'ref. L2 %',
                    'ref. max err'], rows) + '\n')
    wins = sum(1 for r in rows if r[5] != '-' and r[10] != '-' and float(r[5]) < float(r[10]))
    R.add('The codec has the lower relative L2 error in %d of the %d cases. The reference '
          'stores raw float32 values and an uncoded index, while the codec quantises with a '
          'step per subband and range-codes the strips, spending far fewer bits per '
          'coefficient. Where the reference wins (the Spectralon factor at low '
          'ratios) both errors are below 1e-4 %%: the codec maps float input to integers of '
          'max|x| / 2^20 in its byte-budget mode and stops at that step before the budget is '
          'used (its "codec bytes" are then below the budget). The reference is the paper\'s '
          'memory model, not a competitor for bytes.\n\n' % (wins, len(rows)))

    R.add('---\nGenerated in %.0f s.\n' % (time.time() - t0))
    with open(os.path.join(OUT, 'paper.md'), 'w') as f:
        f.write(''.join(R.parts))
    progress()
    print('wrote %s (%.0f s)' % (os.path.join(OUT, 'paper.md'), time.time() - t0))


if __name__ == '__main__':
    main()
