#!/usr/bin/env python3
"""A bed tiled side by side: NX (x NY in 3D) copies of one snapshot along the
floor's axes, written as a CSV table with `# box` and `# boundary walls`
(docs/PARTICLE_FILES.md), for timing the recommendation at larger N on the
same local structure (docs/MODEL.md section 14, results/bed-seconds.csv).

Usage: PYTHONPATH=build/python bench/tile_bed.py FILE FRAME NX NY OUT.csv
"""
import os
import sys

import numpy as np

import hgridlab


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__.strip().splitlines()[-1])
    path, frame, nx, ny, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
    if nx < 1 or ny < 1:
        print("tile_bed.py: NX and NY must be >= 1", file=sys.stderr)
        sys.exit(2)
    p = hgridlab.read_packing(path, frame=frame)
    d = p["d"]
    pos, rad, box = p["positions"], p["radii"], np.array(p["box"][:d], float)
    shifts = [(i, j) for i in range(nx) for j in range(ny if d == 3 else 1)]
    tiled = np.vstack([pos + np.array([i * box[0], j * box[1], 0][:d]) for i, j in shifts])
    radii = np.tile(rad, len(shifts))
    big = box.copy()
    big[0] *= nx
    if d == 3:
        big[1] *= ny
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        f.write("# box " + " ".join(repr(float(b)) for b in big) + "\n# boundary walls\n")
        f.write("x,y,z,r\n" if d == 3 else "x,y,r\n")
        for x, r in zip(tiled, radii):
            f.write(",".join(repr(float(v)) for v in x) + "," + repr(float(r)) + "\n")
    os.replace(tmp, out)
    print("%s: %d particles, box %s" % (out, len(radii), " ".join("%g" % b for b in big)))


if __name__ == "__main__":
    main()
