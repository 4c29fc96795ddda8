"""Baseline for bench_dynamics_vs_numpy: the same computation with NumPy/SciPy, written as a
competent NumPy user would: vectorised over a chunk of positions at once, the constant
matrices (mass, its Cholesky factor, element stiffness and damping in their frames) built
once, real arithmetic for the modal sums. For every set of axis positions: assemble K and D
of the rigid-body model (6 DOF per body, elements as 6-DOF spring-dampers, points moving with
their body, beam carriages on the segment under them), solve the undamped modes of
(K, M) through M = L L^T and a batched symmetric eigensolver, superpose all modes with modal
damping to the 3x3 FRF at every frequency, and keep the largest |H_ij| of each entry.

Usage: dynamics_numpy.py MODEL.json POSITIONS -> one JSON line {"seconds", "positions", "peaks"}
"""
import json
import sys
import time

import numpy as np

CHUNK = 50  # positions at a time: the modal sums of a chunk take CHUNK x 500 x modes doubles


def point_motion(r):
    """6x6 maps of the body's (translation, rotation) to the motion of points r (... x 3)."""
    a = np.zeros(r.shape[:-1] + (6, 6))
    a[..., [0, 1, 2], [0, 1, 2]] = 1.0
    a[..., 3:6, 3:6] = np.eye(3)
    # -skew(r) in the upper right block
    a[..., 0, 4], a[..., 0, 5] = r[..., 2], -r[..., 1]
    a[..., 1, 3], a[..., 1, 5] = -r[..., 2], r[..., 0]
    a[..., 2, 3], a[..., 2, 4] = r[..., 1], -r[..., 0]
    return a


class Structure:
    def __init__(self, model):
        self.model = model
        bodies = model["bodies"]
        self.nb = len(bodies)
        n = 6 * self.nb
        mass = np.zeros((n, n))
        for i, b in enumerate(bodies):
            mass[6 * i:6 * i + 3, 6 * i:6 * i + 3] = b["mass"] * np.eye(3)
            mass[6 * i + 3:6 * i + 6, 6 * i + 3:6 * i + 6] = np.array(b["inertia"])
        self.linv = np.linalg.inv(np.linalg.cholesky(mass))
        self.axes = np.array(model["axes"])
        self.moves = np.array([b["moves"] for b in bodies], float)  # bodies x axes
        self.centres0 = np.array([b["centre"] for b in bodies])
        self.connections = []
        for c in model["connections"]:
            frame = np.zeros((6, 6))
            frame[0:3, 0:3] = frame[3:6, 3:6] = np.array(c["frame"])
            self.connections.append(dict(c, kl=frame @ np.diag(c["stiffness"]) @ frame.T,
                                         dl=frame @ np.diag(c["damping"]) @ frame.T, point=np.array(c["point"])))
        self.beams = [dict(b, start=np.array(b["from"]), axis=np.array(b["axis"])) for b in model["beams"]]
        w = 2 * np.pi * np.array(model["frequencies"])
        self.w2, self.w = w**2, w

    def shift(self, body, q):  # P x 3
        return np.zeros((len(q), 3)) if body < 0 else (q * self.moves[body]) @ self.axes

    def segment(self, beam, p, q):  # P segment bodies of the beam carriage at points p
        b = self.beams[beam]
        s = ((p - b["start"] - self.shift(b["first"], q)) @ b["axis"]) / b["length"]
        return b["first"] + np.sum(s[:, None] > np.array([1, 3, 5, 7]) / 8, axis=1)

    def peaks(self, q):
        count, n = len(q), 6 * self.nb
        rows = np.arange(count)[:, None, None]
        centres = self.centres0[None] + np.einsum("pa,ba,ak->pbk", q, self.moves, self.axes)  # P x bodies x 3
        k = np.zeros((count, n, n))
        d = np.zeros((count, n, n))
        for c in self.connections:
            p = c["point"] + self.shift(c["a"] if c["follows_a"] else c["b"], q)
            ends = [self.segment(c["beam_a"], p, q) if c["beam_a"] >= 0 else np.full(count, c["a"]),
                    self.segment(c["beam_b"], p, q) if c["beam_b"] >= 0 else np.full(count, c["b"])]
            grounded = [e[0] < 0 for e in ends]
            maps = [None if g else point_motion(p - centres[np.arange(count), e]) for e, g in zip(ends, grounded)]
            for s, bs, a_s, gs in zip((-1.0, 1.0), ends, maps, grounded):
                if gs:
                    continue
                ks = s * np.swapaxes(a_s, 1, 2) @ c["kl"]
                ds = s * np.swapaxes(a_s, 1, 2) @ c["dl"]
                idx_s = (6 * bs[:, None] + np.arange(6))[:, :, None]
                for t, bt, a_t, gt in zip((-1.0, 1.0), ends, maps, grounded):
                    if gt:
                        continue
                    idx_t = (6 * bt[:, None] + np.arange(6))[:, None, :]
                    k[rows, idx_s, idx_t] += t * ks @ a_t
                    d[rows, idx_s, idx_t] += t * ds @ a_t
        sel = np.zeros((count, 3, n))
        m = self.model
        for body, point, sign in ((m["tcp_body"], m["tcp_point"], 1.0), (m["wp_body"], m["wp_point"], -1.0)):
            if body >= 0:
                r = np.array(point) + self.shift(body, q) - centres[:, body]
                sel[:, :, 6 * body:6 * body + 6] += sign * point_motion(r)[:, 0:3]
        w2, y = np.linalg.eigh(self.linv @ k @ self.linv.T)
        phi = self.linv.T @ y  # mass-normalised modes, P x n x modes
        c = np.einsum("pir,pir->pr", phi, d @ phi)
        a = sel @ phi  # P x 3 x modes
        aa = a[:, [0, 1, 2, 0, 0, 1]] * a[:, [0, 1, 2, 1, 2, 2]]  # P x 6 x modes: xx yy zz xy xz yz
        re = w2[:, None, :] - self.w2[None, :, None]  # P x F x modes
        im = self.w[None, :, None] * c[:, None, :]
        norm = 1.0 / (re * re + im * im)
        h_re = (re * norm) @ np.swapaxes(aa, 1, 2)  # P x F x 6
        h_im = (im * norm) @ np.swapaxes(aa, 1, 2)
        peak = np.sqrt((h_re * h_re + h_im * h_im).max(axis=1))  # P x 6: xx yy zz xy xz yz
        return peak[:, [0, 3, 4, 3, 1, 5, 4, 5, 2]].reshape(count, 3, 3)


def main():
    model = json.load(open(sys.argv[1]))
    count = int(sys.argv[2])
    positions = np.array(model["positions"])[:count]
    start = time.perf_counter()
    structure = Structure(model)
    peaks = np.concatenate([structure.peaks(positions[i:i + CHUNK]) for i in range(0, len(positions), CHUNK)])
    seconds = time.perf_counter() - start
    print(json.dumps({"seconds": seconds, "positions": len(positions), "peaks": peaks.tolist()}))


if __name__ == "__main__":
    main()
