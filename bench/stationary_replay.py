#!/usr/bin/env python3
"""Replays the stationarity test (src/packing/detail/gen_stationary.cpp) on
the T/N series that long equilibrations record, at several floors, and
prints a markdown table: where the test passes at each floor and T/N there
against the same chain's mean over its last fifth (the choice of the
Metropolis moves' floor, paper_figs/metropolis-floor.md).

Make the runs first, each to its cap with a test that cannot pass, so that
the whole series is kept, e.g. for every Fig. 12 packing:

  build/hgrid generate --d 3 --n 100000 --nu 0.6 --alpha -3 --omega 10 \\
      --boundary walls --placement excluded --method growth --seed 1 \\
      --equilibrate --sweeps 1000 --stop stationary --stationary-tol 1e-9 \\
      --threads 1 --cache results/packings

then: python3 bench/stationary_replay.py FILE.h5 ... [--floors 120 200]
"""
import argparse
import json
import math
import statistics
import subprocess

SAMPLE_SWEEPS = 2  # kStationarySampleSweeps
MAX_RHO = 0.95     # kStationaryMaxRho


def stationary(series, rel_tol, min_samples):
    """test_stationary: drift per doubling of the run over its second half,
    plus two standard errors widened for lag-1 autocorrelation, within
    rel_tol of the mean."""
    n = len(series)
    if n < max(min_samples, 4):
        return False
    first = n // 2
    xs = [math.log((k + 1) * SAMPLE_SWEEPS) for k in range(first, n)]
    ys = series[first:]
    m = len(xs)
    xm, ym = sum(xs) / m, sum(ys) / m
    sxx = sum((x - xm) ** 2 for x in xs)
    b = sum((x - xm) * (y - ym) for x, y in zip(xs, ys)) / sxx
    rss = lag = prev = 0.0
    for i, (x, y) in enumerate(zip(xs, ys)):
        r = y - ym - b * (x - xm)
        rss += r * r
        if i > 0:
            lag += r * prev
        prev = r
    rho = min(max(lag / rss, 0.0), MAX_RHO) if rss > 0 else 0.0
    se = math.sqrt(rss / (m - 2) / sxx * (1 + rho) / (1 - rho))
    return abs(b * math.log(2)) + 2 * se * math.log(2) <= rel_tol * abs(ym)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('files', nargs='+')
    ap.add_argument('--hgrid', default='build/hgrid')
    ap.add_argument('--floors', type=int, nargs='+', default=[120, 200], help='floors in sweeps')
    ap.add_argument('--tol', type=float, default=1e-3, help='the test tolerance (kStationaryRelTol)')
    args = ap.parse_args()
    head = '| N | boundary | alpha | omega | seed |'
    rule = '|---|---|---|---|---|'
    for f in args.floors:
        head += f' sweeps, floor {f} | T/N there vs last fifth |'
        rule += '---|---|'
    print(head + ' sd of one sample, last fifth |')
    print(rule + '---|')
    worst = [0.0] * len(args.floors)
    work = [0.0] * len(args.floors)
    for path in args.files:
        a = json.loads(subprocess.run([args.hgrid, 'info', path, '--json'], check=True, capture_output=True,
                                      text=True).stdout)['attributes']
        s = [float(v) for v in a['stationarity_series'].split(',')]
        late = s[len(s) * 4 // 5:]
        mean = statistics.mean(late)
        row = '| %d | %s | %g | %g | %d |' % (a['n'], 'walls' if 'boundary=walls' in a['cache_key'] else 'periodic',
                                              a['alpha'], a['omega'], a['seed'])
        for i, floor in enumerate(args.floors):
            k = next((j for j in range(1, len(s) + 1) if stationary(s[:j], args.tol, floor // SAMPLE_SWEEPS)), len(s))
            d = 100 * (s[k - 1] / mean - 1)
            worst[i] = max(worst[i], abs(d))
            work[i] += k * SAMPLE_SWEEPS * a['n']
            row += ' %d | %+.2f %% |' % (k * SAMPLE_SWEEPS, d)
        print(row + ' %.2f %% |' % (100 * statistics.stdev(late) / mean))
    print()
    for i, floor in enumerate(args.floors):
        print(f'Floor {floor} sweeps: largest |difference| {worst[i]:.2f} %, sweeps times N {work[i] / 1e5:.0f} x 10^5.')


if __name__ == '__main__':
    main()
