"""Baseline for bench_identify_vs_scipy: the same R-test identification with NumPy and
scipy.optimize.least_squares, written as a competent SciPy user would: the model vectorised
over all points, the rotations that depend only on the data built once per solve, an analytic
Jacobian, and Levenberg-Marquardt (method="lm", MINPACK).

The model is the tilting table t-(C)-Z-Y-b-X-B-C-w with mtacc's conventions
(docs/conventions.md): tool chain bed -> Y -> Z (directions tilted by C0Y and A0Z, B0Z),
workpiece chain bed -> X -> B -> C, each rotary axis preceded by its location error
E = Trans(x, y, z) Rx(a) Ry(b) Rz(c); workpiece-side joints turn by -q. The R-test reads
R_nominal(q) (TCP_in_workpiece - sphere), which simplifies to

    r = Rb Ec^T (Rb^T Eb^T (v0 - tB) - tC) - Rb Rc s,   v0 = Y ydir + Z zdir + (X, 0, 0)

with Rb = Ry(-B), Rc = Rz(-C). Every parameter enters through one factor, so each Jacobian
column is one product.

Usage: identify_scipy.py DATA.csv REPEATS
    -> one JSON line {"seconds": [...], "values": [...], "nfev", "njev", "cost"}
"""
import json
import sys
import time

import numpy as np
from scipy.optimize import least_squares

NAMES = ["X0B", "Y0B", "Z0B", "A0B", "C0B", "X0C", "Z0C", "A0C", "B0C", "C0C", "C0Y", "A0Z", "B0Z"]


def rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def ry(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def drx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[0, 0, 0], [0, -s, -c], [0, c, -s]])


def dry(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[-s, 0, c], [0, 0, 0], [-c, 0, -s]])


def drz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[-s, -c, 0], [c, -s, 0], [0, 0, 0]])


class RTest:
    """The data and everything that depends only on it, built once per solve."""

    def __init__(self, q, sphere, measured):
        n = len(q)
        self.x, self.y, self.z = q[:, 0], q[:, 1], q[:, 2]
        cb, sb = np.cos(-q[:, 3]), np.sin(-q[:, 3])
        cc, sc = np.cos(-q[:, 4]), np.sin(-q[:, 4])
        self.rb = np.zeros((n, 3, 3))
        self.rb[:, 0, 0], self.rb[:, 0, 2], self.rb[:, 1, 1], self.rb[:, 2, 0], self.rb[:, 2, 2] = cb, sb, 1, -sb, cb
        rc = np.zeros((n, 3, 3))
        rc[:, 0, 0], rc[:, 0, 1], rc[:, 1, 0], rc[:, 1, 1], rc[:, 2, 2] = cc, -sc, sc, cc, 1
        self.rbrc_s = np.einsum("nij,njk,nk->ni", self.rb, rc, sphere)
        self.measured = measured

    def parts(self, p):
        x0b, y0b, z0b, a0b, c0b, x0c, z0c, a0c, b0c, c0c, c0y, a0z, b0z = p
        ydir = rz(c0y)[:, 1]
        zdir = (rx(a0z) @ ry(b0z))[:, 2]
        v0 = np.outer(self.y, ydir) + np.outer(self.z, zdir)
        v0[:, 0] += self.x
        eb, ec = rx(a0b) @ rz(c0b), rx(a0c) @ ry(b0c) @ rz(c0c)
        tb, tc = np.array([x0b, y0b, z0b]), np.array([x0c, 0.0, z0c])
        d = v0 - tb
        u = d @ eb  # Eb^T (v0 - tB), row-wise
        w = np.einsum("nji,nj->ni", self.rb, u) - tc  # Rb^T u - tC
        return dict(ydir=ydir, zdir=zdir, eb=eb, ec=ec, d=d, u=u, w=w)

    def residual(self, p):
        f = self.parts(p)
        return (np.einsum("nij,nj->ni", self.rb, f["w"] @ f["ec"]) - self.rbrc_s - self.measured).ravel()

    def jacobian(self, p):
        x0b, y0b, z0b, a0b, c0b, x0c, z0c, a0c, b0c, c0c, c0y, a0z, b0z = p
        f = self.parts(p)
        eb, ec, rb = f["eb"], f["ec"], self.rb
        n = len(self.x)
        # Columns in the frame just before the last Rb, then one batched product.
        inner = np.empty((n, 3, len(NAMES)))

        def through_eb(dv):  # dv in the bed frame -> Ec^T Rb^T Eb^T dv
            return np.einsum("nji,nj->ni", rb, dv @ eb) @ ec

        ex = np.eye(3)
        for k in range(3):  # tB
            inner[:, :, k] = -through_eb(np.broadcast_to(ex[k], (n, 3)))
        deb = [drx(a0b) @ rz(c0b), rx(a0b) @ drz(c0b)]
        for k, m in enumerate(deb):  # Eb angles
            inner[:, :, 3 + k] = np.einsum("nji,nj->ni", rb, f["d"] @ m) @ ec
        inner[:, :, 5] = -np.broadcast_to(ec.T @ ex[0], (n, 3))  # tC
        inner[:, :, 6] = -np.broadcast_to(ec.T @ ex[2], (n, 3))
        dec = [drx(a0c) @ ry(b0c) @ rz(c0c), rx(a0c) @ dry(b0c) @ rz(c0c), rx(a0c) @ ry(b0c) @ drz(c0c)]
        for k, m in enumerate(dec):  # Ec angles
            inner[:, :, 7 + k] = f["w"] @ m
        inner[:, :, 10] = through_eb(np.outer(self.y, drz(c0y)[:, 1]))
        inner[:, :, 11] = through_eb(np.outer(self.z, (drx(a0z) @ ry(b0z))[:, 2]))
        inner[:, :, 12] = through_eb(np.outer(self.z, (rx(a0z) @ dry(b0z))[:, 2]))
        return np.einsum("nij,njk->nik", rb, inner).reshape(3 * n, len(NAMES))


def main():
    data = np.loadtxt(sys.argv[1], delimiter=",", skiprows=1)
    repeats = int(sys.argv[2])
    q, sphere, measured = data[:, 0:5], data[:, 5:8], data[:, 8:11]

    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        problem = RTest(q, sphere, measured)
        result = least_squares(problem.residual, np.zeros(len(NAMES)), jac=problem.jacobian, method="lm", x_scale="jac")
        seconds.append(time.perf_counter() - start)
    print(json.dumps({"seconds": seconds, "values": result.x.tolist(), "nfev": int(result.nfev),
                      "njev": int(result.njev or 0), "cost": float(result.cost)}))


if __name__ == "__main__":
    main()
