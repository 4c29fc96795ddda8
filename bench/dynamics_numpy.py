"""Baseline for bench_dynamics_vs_numpy: the same computation with NumPy/SciPy. For every set
of axis positions: assemble K and D of the rigid-body model (6 DOF per body, elements as
6-DOF spring-dampers, points moving with their body, beam carriages on the segment under
them), solve the undamped modes with scipy.linalg.eigh(K, M), superpose all modes with modal
damping to the 3x3 FRF at every frequency, and keep the largest |H_ij| of each entry.

Usage: dynamics_numpy.py MODEL.json POSITIONS -> one JSON line {"seconds", "peaks"}
"""
import json
import sys
import time

import numpy as np
import scipy.linalg


def skew(r):
    return np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])


def point_motion(r):
    a = np.eye(6)
    a[0:3, 3:6] = -skew(r)
    return a


def main():
    model = json.load(open(sys.argv[1]))
    count = int(sys.argv[2])
    bodies, axes = model["bodies"], np.array(model["axes"])
    n = 6 * len(bodies)
    mass = np.zeros((n, n))
    for i, b in enumerate(bodies):
        mass[6 * i:6 * i + 3, 6 * i:6 * i + 3] = b["mass"] * np.eye(3)
        mass[6 * i + 3:6 * i + 6, 6 * i + 3:6 * i + 6] = np.array(b["inertia"])
    moves = np.array([b["moves"] for b in bodies], float)  # bodies x axes
    freqs = np.array(model["frequencies"])
    w = 2 * np.pi * freqs
    positions = np.array(model["positions"])[:count]

    def shift(body, q):
        return np.zeros(3) if body < 0 else (moves[body] * q) @ axes

    def segment(beam, p, q):
        b = model["beams"][beam]
        s = (p - np.array(b["from"]) - shift(b["first"], q)) @ np.array(b["axis"]) / b["length"]
        return b["first"] + int(np.sum(s > np.array([1, 3, 5, 7]) / 8))

    start = time.perf_counter()
    peaks = []
    for q in positions:
        centres = [np.array(b["centre"]) + shift(i, q) for i, b in enumerate(bodies)]
        k = np.zeros((n, n))
        d = np.zeros((n, n))
        for c in model["connections"]:
            p = np.array(c["point"]) + shift(c["a"] if c["follows_a"] else c["b"], q)
            ends = [segment(c["beam_a"], p, q) if c["beam_a"] >= 0 else c["a"],
                    segment(c["beam_b"], p, q) if c["beam_b"] >= 0 else c["b"]]
            frame = np.zeros((6, 6))
            frame[0:3, 0:3] = frame[3:6, 3:6] = np.array(c["frame"])
            kl = frame @ np.diag(c["stiffness"]) @ frame.T
            dl = frame @ np.diag(c["damping"]) @ frame.T
            for s, bs in zip((-1.0, 1.0), ends):
                if bs < 0:
                    continue
                a_s = point_motion(p - centres[bs])
                for t, bt in zip((-1.0, 1.0), ends):
                    if bt < 0:
                        continue
                    a_t = point_motion(p - centres[bt])
                    k[6 * bs:6 * bs + 6, 6 * bt:6 * bt + 6] += s * t * a_s.T @ kl @ a_t
                    d[6 * bs:6 * bs + 6, 6 * bt:6 * bt + 6] += s * t * a_s.T @ dl @ a_t
        sel = np.zeros((3, n))
        for body, point, sign in ((model["tcp_body"], model["tcp_point"], 1.0), (model["wp_body"], model["wp_point"], -1.0)):
            if body >= 0:
                r = np.array(point) + shift(body, q) - centres[body]
                sel[:, 6 * body:6 * body + 6] += sign * point_motion(r)[0:3]
        w2, phi = scipy.linalg.eigh(k, mass)
        c = np.einsum("ir,ij,jr->r", phi, d, phi)
        a = sel @ phi  # 3 x modes
        den = 1.0 / (w2[None, :] - w[:, None] ** 2 + 1j * w[:, None] * c[None, :])  # freqs x modes
        h = np.einsum("ir,jr,fr->fij", a, a, den)
        peaks.append(np.abs(h).max(axis=0))
    seconds = time.perf_counter() - start
    print(json.dumps({"seconds": seconds, "positions": len(positions), "peaks": np.array(peaks).tolist()}))


if __name__ == "__main__":
    main()
