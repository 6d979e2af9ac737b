#!/usr/bin/env python3
"""The wall time of `hgrid run` on P cores, projected from one run's
per-point times (how much more cores would shorten `make figures SCALE=paper`).

  python3 bench/pool_projection.py results/fig11-paper.csv results/fig12-paper.csv \
          results/occupancy-paper.csv --cores 2 16 64

Each row of the result files is one job: its seconds (packing, sizes, grid
build and query, as that run measured them, one thread each) run on one of P
workers in the runner's order (src/scenes/runner.cpp: estimated work, largest
first, ties in scene order; a worker takes the next job when it is free).
A packing two scenes share was made once: its second row holds the load
time. What this leaves out, said plainly: per-core speed on another machine
(the times are the measuring machine's, with its other core busy); the
threads a job gains when the pool runs dry (the Metropolis moves would use
them, the event chains not); start-up and the figures drawn after the scenes.
The projection is a list schedule, so it is never below the longest single
job or the total over P."""
import argparse
import csv
import heapq
import math


def estimated_work(r):
    """The runner's estimate (src/scenes/runner.cpp, estimated_work)."""
    n = float(r['n'])
    if r['placement'] != 'excluded':
        return n
    dense = float(r['nu']) / 0.35
    eq = 2 if int(r.get('equilibration_sweeps') or 0) > 0 else 1
    return n * (1 + dense * dense * math.sqrt(max(1.0, float(r['omega']))) * eq)


def jobs(paths):
    out = []
    for path in paths:
        with open(path) as f:
            rows = list(csv.DictReader(l for l in f if not l.startswith('#')))
        for r in rows:
            secs = sum(float(r[k]) for k in ('seconds_packing', 'seconds_sizes', 'seconds_build', 'seconds_query'))
            out.append((estimated_work(r), secs, f"{path.split('/')[-1]}: n={r['n']} omega={r['omega']} "
                        f"nu={float(r['nu']):.2f} alpha={r['alpha']} {r['boundary']} {r['placement']}"))
    # Largest estimate first; Python's sort is stable, so ties keep the files' order.
    out.sort(key=lambda j: -j[0])
    return out


def makespan(js, cores):
    free = [0.0] * cores  # when each worker is free
    heapq.heapify(free)
    end = 0.0
    for _, secs, _ in js:
        t = heapq.heappop(free) + secs
        end = max(end, t)
        heapq.heappush(free, t)
    return end


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('results', nargs='+', help='result CSV files of one run (hgrid run)')
    ap.add_argument('--cores', type=int, nargs='+', default=[2, 16, 64])
    a = ap.parse_args()
    js = jobs(a.results)
    total = sum(j[1] for j in js)
    longest = max(js, key=lambda j: j[1])
    print(f"{len(js)} jobs, {total:.0f} core-s in all; the longest {longest[1]:.0f} s ({longest[2]})")
    for p in a.cores:
        m = makespan(js, p)
        print(f"{p:4d} cores: {m:7.0f} s ({m / 60:.1f} min); bounds: total/P {total / p:.0f} s, longest job {longest[1]:.0f} s")


if __name__ == '__main__':
    main()
