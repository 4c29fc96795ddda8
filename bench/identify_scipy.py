"""Baseline for bench_identify_vs_scipy: the same R-test identification with NumPy and
scipy.optimize.least_squares (default trust-region reflective, 2-point Jacobian).

The model is the tilting table t-(C)-Z-Y-b-X-B-C-w with mtacc's conventions
(docs/conventions.md): tool chain bed -> Y -> Z (directions tilted by C0Y and A0Z, B0Z),
workpiece chain bed -> X -> B -> C, each rotary axis preceded by its location error
E = Trans(x, y, z) Rx(a) Ry(b) Rz(c); workpiece-side joints turn by -q. The R-test reads
R_nominal(q) (TCP_in_workpiece - sphere).

Usage: identify_scipy.py DATA.csv REPEATS -> one JSON line {"seconds": [...], "values": [...]}
"""
import json
import sys
import time

import numpy as np
from scipy.optimize import least_squares

NAMES = ["X0B", "Y0B", "Z0B", "A0B", "C0B", "X0C", "Z0C", "A0C", "B0C", "C0C", "C0Y", "A0Z", "B0Z"]


def rx(a):
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)


def ry(a):
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


def rz(a):
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


def rxyz(a, b, c):
    return rx(np.asarray(a, float)) @ ry(np.asarray(b, float)) @ rz(np.asarray(c, float))


def readings(p, q, sphere):
    x0b, y0b, z0b, a0b, c0b, x0c, z0c, a0c, b0c, c0c, c0y, a0z, b0z = p
    # Tool chain: Y then Z, directions tilted by the squareness errors.
    ydir = rxyz(0.0, 0.0, c0y) @ np.array([0.0, 1.0, 0.0])
    zdir = rxyz(a0z, b0z, 0.0) @ np.array([0.0, 0.0, 1.0])
    tool = q[:, 1:2] * ydir + q[:, 2:3] * zdir
    # Workpiece chain: W = Trans(-x) E_B Rot(y, -b) E_C Rot(z, -c); TCP_wp = W^-1 tool.
    eb_r, eb_t = rxyz(a0b, 0.0, c0b), np.array([x0b, y0b, z0b])
    ec_r, ec_t = rxyz(a0c, b0c, c0c), np.array([x0c, 0.0, z0c])
    rb, rc = ry(-q[:, 3]), rz(-q[:, 4])
    v = tool - np.stack([-q[:, 0], np.zeros(len(q)), np.zeros(len(q))], -1)
    v = (v - eb_t) @ eb_r  # E_B^-1
    v = np.einsum("nji,nj->ni", rb, v)  # Rot_B^-1
    v = (v - ec_t) @ ec_r  # E_C^-1
    v = np.einsum("nji,nj->ni", rc, v)  # Rot_C^-1
    nominal = rb @ rc
    return np.einsum("nij,nj->ni", nominal, v - sphere)


def main():
    data = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
    repeats = int(sys.argv[2])
    q, sphere, measured = data[:, 0:5], data[:, 5:8], data[:, 8:11]

    def residual(p):
        return (readings(p, q, sphere) - measured).ravel()

    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        result = least_squares(residual, np.zeros(len(NAMES)), x_scale="jac")
        seconds.append(time.perf_counter() - start)
    print(json.dumps({"seconds": seconds, "values": result.x.tolist(), "nfev": int(result.nfev),
                      "njev": int(result.njev or 0), "cost": float(result.cost)}))


if __name__ == "__main__":
    main()
