"""Baseline for bench_program_compensation: the inverse error model of every point of a 5-axis
axis program, vectorised in NumPy as a competent user would write it. The tilting table
t-(C)-Z-Y-b-X-B-C-w with location errors, in mtacc's conventions (docs/conventions.md, and the
model of bench/identify_scipy.py): the TCP and the tool direction in the workpiece frame are

    p = Rc^T Ec^T (Rb^T Eb^T (v0 - tB) - tC),   d = Rc^T Ec^T Rb^T Eb^T e_z,
    v0 = Y ydir + Z zdir + (X, 0, 0),  Rb^T = Ry(B), Rc^T = Rz(C).

Newton's method on all points at once from the nominal commands: the residual (position, and the
direction times 1000 mm/rad as mtacc weighs it), an analytic 6 x 5 Jacobian per point, and a
batched least-squares step (normal equations, np.linalg.solve), until every point is within
1e-7 mm and 1e-9 rad (mtacc's tolerances for programs). Then the same check mtacc makes between written points: the midpoint of
each segment, with the correction interpolated, against the nominal path.

Usage: compensation_numpy.py Q.bin N ERRORS.json REPEATS OUT.bin
    Q.bin: N x 5 float64 (X, Y, Z mm, B, C rad), the program's points
    -> one JSON line {"seconds": [...], "iterations": k, "midpoints_over": m}; OUT.bin the commands
"""
import json
import sys
import time

import numpy as np

WEIGHT = 1000.0  # mm per rad


def rot(axis, a):
    c, s = np.cos(a), np.sin(a)
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    r = np.eye(3)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return r


def batch_ry(b):  # Ry(b) for each b: (n, 3, 3)
    c, s = np.cos(b), np.sin(b)
    r = np.zeros((len(b), 3, 3))
    r[:, 0, 0], r[:, 0, 2], r[:, 1, 1], r[:, 2, 0], r[:, 2, 2] = c, s, 1.0, -s, c
    return r


def batch_rz(a):
    c, s = np.cos(a), np.sin(a)
    r = np.zeros((len(a), 3, 3))
    r[:, 0, 0], r[:, 0, 1], r[:, 1, 0], r[:, 1, 1], r[:, 2, 2] = c, -s, s, c, 1.0
    return r


def d_batch_ry(b):
    c, s = np.cos(b), np.sin(b)
    r = np.zeros((len(b), 3, 3))
    r[:, 0, 0], r[:, 0, 2], r[:, 2, 0], r[:, 2, 2] = -s, c, -c, -s
    return r


def d_batch_rz(a):
    c, s = np.cos(a), np.sin(a)
    r = np.zeros((len(a), 3, 3))
    r[:, 0, 0], r[:, 0, 1], r[:, 1, 0], r[:, 1, 1] = -s, -c, c, -s
    return r


class Machine:
    def __init__(self, e):
        g = lambda k: e.get(k, 0.0)
        self.ydir = rot(2, g("C0Y"))[:, 1]
        self.zdir = (rot(0, g("A0Z")) @ rot(1, g("B0Z")))[:, 2]
        self.ebT = (rot(0, g("A0B")) @ rot(2, g("C0B"))).T
        self.ecT = (rot(0, g("A0C")) @ rot(1, g("B0C")) @ rot(2, g("C0C"))).T
        self.tb = np.array([g("X0B"), g("Y0B"), g("Z0B")])
        self.tc = np.array([g("X0C"), g("Y0C"), g("Z0C")])

    def pose(self, q, jacobian=False):
        """TCP (n, 3) and direction (n, 3); with jacobian, also d(p, d)/dq (n, 6, 5)."""
        n = len(q)
        v0 = np.outer(q[:, 1], self.ydir) + np.outer(q[:, 2], self.zdir)
        v0[:, 0] += q[:, 0]
        ryb, rzc = batch_ry(q[:, 3]), batch_rz(q[:, 4])
        u = (v0 - self.tb) @ self.ebT.T  # Eb^T (v0 - tB)
        w = np.einsum("nij,nj->ni", ryb, u) - self.tc
        ecw = w @ self.ecT.T
        p = np.einsum("nij,nj->ni", rzc, ecw)
        ez = self.ebT @ np.array([0.0, 0.0, 1.0])
        bz = np.einsum("nij,j->ni", ryb, ez)
        ecbz = bz @ self.ecT.T
        d = np.einsum("nij,nj->ni", rzc, ecbz)
        if not jacobian:
            return p, d
        j = np.zeros((n, 6, 5))
        m = np.einsum("nij,jk,nkl->nil", rzc, self.ecT, ryb)  # Rc^T Ec^T Ry(B)
        for k, axis in enumerate((np.array([1.0, 0.0, 0.0]), self.ydir, self.zdir)):
            j[:, :3, k] = m @ (self.ebT @ axis)
        dryb = d_batch_ry(q[:, 3])
        j[:, :3, 3] = np.einsum("nij,jk,nk->ni", rzc, self.ecT, np.einsum("nij,nj->ni", dryb, u))
        j[:, 3:, 3] = np.einsum("nij,jk,nk->ni", rzc, self.ecT, np.einsum("nij,j->ni", dryb, ez))
        drzc = d_batch_rz(q[:, 4])
        j[:, :3, 4] = np.einsum("nij,nj->ni", drzc, ecw)
        j[:, 3:, 4] = np.einsum("nij,nj->ni", drzc, ecbz)
        j[:, 3:, :] *= WEIGHT
        return p, d, j


def compensate(actual, nominal, q):
    want_p, want_d = nominal.pose(q)
    x = q.copy()
    iterations = 0
    while True:
        p, d, j = actual.pose(x, jacobian=True)
        r = np.concatenate([p - want_p, WEIGHT * (d - want_d)], axis=1)
        if np.all(np.linalg.norm(r[:, :3], axis=1) <= 1e-7) and np.all(np.linalg.norm(r[:, 3:], axis=1) / WEIGHT <= 1e-9):
            break
        if iterations == 10:
            break
        jt = np.transpose(j, (0, 2, 1))
        step = np.linalg.solve(jt @ j, -np.einsum("nij,nj->ni", jt, r)[:, :, None])[:, :, 0]
        x += step
        iterations += 1
    # Midpoints of the written segments, the correction interpolated, against the nominal path.
    mid_nominal = 0.5 * (q[1:] + q[:-1])
    mid_written = 0.5 * (x[1:] + x[:-1])
    mp, md = actual.pose(mid_written)
    np_, nd = nominal.pose(mid_nominal)
    over = np.count_nonzero(np.linalg.norm(mp - np_, axis=1) > 1e-4)
    return x, iterations, int(over)


def main():
    n = int(sys.argv[2])
    q = np.fromfile(sys.argv[1], dtype=np.float64).reshape(n, 5)
    errors = json.load(open(sys.argv[3]))
    repeats = int(sys.argv[4])
    actual, nominal = Machine(errors), Machine({})
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        x, iterations, over = compensate(actual, nominal, q)
        seconds.append(time.perf_counter() - start)
    x.tofile(sys.argv[5])
    print(json.dumps({"seconds": seconds, "iterations": iterations, "midpoints_over": over}))


if __name__ == "__main__":
    main()
