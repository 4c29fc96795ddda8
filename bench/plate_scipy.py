#!/usr/bin/python3
"""Baseline for bench_plate_identification: the same linear plate identification with NumPy and
SciPy, as a competent user would write it. The design matrix is built vectorised over all
features of a placement from the first-order model of seed 003 §4.4 (F-matrices) for the Maho
machine at B = C = 0: an error (e, eps) of element k moves the tool point p by
sign_k (e + eps x (p - o_k)), o_k the element's frame origin in the workpiece frame, sign +1 for
the ram Z (tool side) and -1 for the table axes X, Y; a tilt of an axis direction by w moves it by
q (w x d). Readings are -(u, v) . displacement plus a translation and a rotation per plate, weighted
by the probe noise; the solution is the minimum-norm least squares of the column-scaled matrix by
scipy.linalg.svd, with its covariance and rank.

Usage: plate_scipy.py DIR ROWS COLUMNS REPEATS   (DIR/campaign.json, DIR/design.bin: mtacc's matrix)
    -> one JSON line {"seconds", "build_seconds", "solve_seconds", "values", "rank", "design_difference"}
"""
import json
import sys
import time

import numpy as np
import scipy.linalg

L = 150.0  # the bundled tool length
TILTS = {"C0Y": ("Y", np.array([1.0, 0.0, 0.0])), "A0Z": ("Z", np.array([0.0, -1.0, 0.0])), "B0Z": ("Z", np.array([1.0, 0.0, 0.0]))}


def basis(q, p):
    if p["period"] > 0:
        u = np.mod(q - p["zero"], p["period"])
    else:
        u = np.clip(q, p["breaks"][0], p["breaks"][-1])
    if p["knot"] == 0:
        return u ** p["power"]
    v = u - p["breaks"][p["knot"]]
    return np.where(v > 0, v ** p["power"], 0.0)


def design(campaign):
    params = campaign["parameters"]
    n_params = len(params)
    blocks, rhs = [], []
    n_place = len(campaign["placements"])
    for k, place in enumerate(campaign["placements"]):
        f = np.asarray(place["features"])
        q = {"X": f[:, 0], "Y": f[:, 1], "Z": f[:, 2]}
        tcp = np.column_stack([350.0 - q["X"], L - 105.0 - q["Y"], q["Z"] - 310.0])
        point = tcp + np.asarray(place["stylus"])
        ones = np.ones_like(q["X"])
        origin = {"Z": np.column_stack([350.0 - q["X"], -95.0 - q["Y"], 495.0 * ones]),
                  "Y": np.column_stack([350.0 - q["X"], 327.5 * ones, 515.0 * ones]),
                  "X": np.column_stack([0.0 * ones, 395.0 * ones, 375.0 * ones])}
        sign = {"Z": 1.0, "Y": -1.0, "X": -1.0}
        u, v = np.asarray(place["u"]), np.asarray(place["v"])
        disp = np.empty((len(ones), n_params, 3))
        for j, p in enumerate(params):
            if "tilt" in p:
                axis, w = TILTS[p["tilt"]]
                disp[:, j, :] = q[axis][:, None] * w
                continue
            b = basis(q[p["axis"]], p)
            c = p["component"]
            if c < 3:
                d = np.zeros((len(ones), 3))
                d[:, c] = b
            else:
                w = np.zeros(3)
                w[c - 3] = 1.0
                d = b[:, None] * np.cross(w, point - origin[p["axis"]])
            disp[:, j, :] = sign[p["axis"]] * d
        rows = np.empty((2 * len(ones), n_params + 3 * n_place))
        rows[:, :] = 0.0
        rows[0::2, :n_params] = -disp @ u
        rows[1::2, :n_params] = -disp @ v
        rows[0::2, n_params + 3 * k] = 1.0
        rows[1::2, n_params + 3 * k + 1] = 1.0
        rows[0::2, n_params + 3 * k + 2] = -f[:, 4]
        rows[1::2, n_params + 3 * k + 2] = f[:, 3]
        weights = np.tile(1.0 / np.asarray(place["noise"]), len(ones))
        blocks.append(rows * weights[:, None])
        rhs.append(f[:, 5:7].reshape(-1) * weights)
    return np.vstack(blocks), np.concatenate(rhs)


def solve(a, b):
    norms = np.linalg.norm(a, axis=0)
    u, s, vt = scipy.linalg.svd(a / norms, full_matrices=False, lapack_driver="gesdd")
    rank = int(np.sum(s > 1e-8 * s[0]))
    x = vt[:rank].T @ ((u[:, :rank].T @ b) / s[:rank])
    covariance = (vt[:rank].T / s[:rank] ** 2) @ vt[:rank] / np.outer(norms, norms)
    return x / norms, np.sqrt(np.diag(covariance)), rank


def main():
    folder, rows, cols, repeats = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    with open(f"{folder}/campaign.json") as f:
        campaign = json.load(f)
    theirs = np.fromfile(f"{folder}/design.bin").reshape(rows, cols)
    seconds, build, solving = [], [], []
    for _ in range(repeats):
        t0 = time.perf_counter()
        a, b = design(campaign)
        t1 = time.perf_counter()
        values, _, rank = solve(a, b)
        t2 = time.perf_counter()
        seconds.append(t2 - t0)
        build.append(t1 - t0)
        solving.append(t2 - t1)
    print(json.dumps({"seconds": seconds, "build_seconds": build, "solve_seconds": solving,
                      "values": values[:len(campaign["parameters"])].tolist(), "rank": rank,
                      "design_difference": float(np.abs(a - theirs).max())}))


if __name__ == "__main__":
    main()
