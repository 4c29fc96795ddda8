"""Baseline for bench_cubic_zmap: the machined surface as a NumPy z-buffer of the same swept
envelopes, written as a user of NumPy would: for every tool move, the lowest point of the ball
swept along it, evaluated at once for every cell of the move's bounding box (the box of the
segment widened by the ball's radius), and the z-buffer lowered there by np.minimum.

The swept ball's lowest point over a vertical line (x, y) is that of the capsule about the move
a -> b: where the line meets the cylinder of radius r about the segment (the lower root of
horizontal h^2 - 2 s dz h + q2 l2 - s^2 - r^2 l2 = 0, h = z - a.z, s = q . d, kept when its
projection lies on the segment), else the lower of the two end spheres.

Usage: machined_surface_numpy.py MOVES.bin GRIDS.json OUT.bin REPEATS
  MOVES.bin: float64 rows (ax, ay, az, bx, by, bz); GRIDS.json: spacing, radius, reference, depth
  and "windows", each a grid of cells {x0, y0, nx, ny} (cell (i, j) centred at x0 + (i + 0.5)
  spacing, y0 + (j + 0.5) spacing) to cut with every move.
  OUT.bin: each window's heights relative to the reference, float32, row by row, one window after
  the other, as mtacc's map.
  -> one JSON line {"seconds": [...]} (each repetition: all the windows)
"""
import json
import sys
import time

import numpy as np


def cut(moves, g, w):
    nx, ny = w["nx"], w["ny"]
    s, r = g["spacing"], g["radius"]
    xs = w["x0"] + (np.arange(nx) + 0.5) * s
    ys = w["y0"] + (np.arange(ny) + 0.5) * s
    zbuf = np.full((ny, nx), np.inf)
    a, b = moves[:, 0:3], moves[:, 3:6]
    lo = np.minimum(a[:, :2], b[:, :2]) - r
    hi = np.maximum(a[:, :2], b[:, :2]) + r
    # Each move's box in cells (cell k's centre at x0 + (k + 0.5) s).
    ci0 = np.clip(np.ceil((lo[:, 0] - w["x0"]) / s - 0.5).astype(np.int64), 0, nx)
    ci1 = np.clip(np.floor((hi[:, 0] - w["x0"]) / s - 0.5).astype(np.int64) + 1, 0, nx)
    cj0 = np.clip(np.ceil((lo[:, 1] - w["y0"]) / s - 0.5).astype(np.int64), 0, ny)
    cj1 = np.clip(np.floor((hi[:, 1] - w["y0"]) / s - 0.5).astype(np.int64) + 1, 0, ny)
    r2 = r * r
    for k in np.flatnonzero((ci1 > ci0) & (cj1 > cj0)):
        ax, ay, az = a[k]
        dx, dy, dz = b[k] - a[k]
        qx = xs[ci0[k]:ci1[k]] - ax
        qy = (ys[cj0[k]:cj1[k]] - ay)[:, None]
        q2 = qx * qx + qy * qy
        with np.errstate(invalid="ignore"):
            za = np.where(q2 <= r2, az - np.sqrt(r2 - q2), np.inf)
            px, py = qx - dx, qy - dy
            p2 = px * px + py * py
            z = np.minimum(za, np.where(p2 <= r2, b[k, 2] - np.sqrt(r2 - p2), np.inf))
            horizontal = dx * dx + dy * dy
            l2 = horizontal + dz * dz
            if horizontal > 1e-24 * (1 + l2):
                sq = qx * dx + qy * dy
                half = -sq * dz
                disc = half * half - horizontal * (q2 * l2 - sq * sq - r2 * l2)
                h = (-half - np.sqrt(disc)) / horizontal
                t = sq + h * dz
                z = np.where((disc >= 0) & (t >= 0) & (t <= l2), az + h, z)
        window = zbuf[cj0[k]:cj1[k], ci0[k]:ci1[k]]
        np.minimum(window, z, out=window)
    depth = np.float32(g["depth"])
    relative = zbuf - g["reference"]
    return np.where(relative < depth, relative.astype(np.float32), depth)


def main():
    moves = np.fromfile(sys.argv[1], dtype=np.float64).reshape(-1, 6)
    with open(sys.argv[2]) as f:
        grids = json.load(f)
    repeats = int(sys.argv[4])
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        heights = [cut(moves, grids, w) for w in grids["windows"]]
        seconds.append(time.perf_counter() - start)
    np.concatenate([h.ravel() for h in heights]).astype(np.float32).tofile(sys.argv[3])
    print(json.dumps({"seconds": seconds}))


if __name__ == "__main__":
    main()
