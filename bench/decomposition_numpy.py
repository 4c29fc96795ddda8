"""Baseline for bench_decomposition_vs_numpy: seed 004's pipeline on recorded signals with
NumPy/SciPy, written as a competent user would: per feed the command trace's clock offset by a
coarse scan (np.interp, vectorised over samples) refined by scipy's least_squares with the
analytic Jacobian (the spline's derivative) on the not-a-knot CubicSpline misfit, both traces resampled by CubicSpline at the instrument's
samples inside the moved traces, the nominal and identified TCP of the inclined-A machine
(TCP = R_C(C) R_A(A) (X, Y, Z), checked against mtacc's before timing) vectorised over samples,
then the Legendre degree-20 fit of the reference test in the normalised path travelled (legvander +
lstsq), drift (constant in the machine frame), dynamic error, shares and per-direction RMS.

Usage: decomposition_numpy.py DIR REPEATS -> one JSON line {"seconds": [one per run], "tests": [{offset, drift, rms, shares}]}
"""
import json
import pathlib
import sys
import time

import numpy as np
from numpy.polynomial import legendre
from scipy.interpolate import CubicSpline
from scipy.optimize import least_squares


def rotations(axis, angle):
    """Rodrigues' rotation matrices (n x 3 x 3) about a unit axis."""
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1 - c) * (k @ k)


A_AXIS = np.array([1.0, 0.0, 1.0]) / np.sqrt(2.0)
C_AXIS = np.array([0.0, 0.0, 1.0])


def to_workpiece(q):
    """q: n x 5 -> the rotations (n x 3 x 3) from the machine frame into the workpiece frame."""
    return rotations(C_AXIS, q[:, 4]) @ rotations(A_AXIS, q[:, 3])


def tcp(q):
    """q: n x 5 (X, Y, Z mm, A, C rad) -> TCP in the workpiece frame, n x 3."""
    return np.einsum("nij,nj->ni", to_workpiece(q), q[:, :3])


def compared(cmd_t, enc_t, lo, hi):
    """The encoder samples inside the command's span for every offset in [lo, hi] (as mtacc rounds)."""
    period = enc_t[1] - enc_t[0]
    first = max(0.0, np.ceil((cmd_t[0] + hi - enc_t[0]) / period - 1e-9))
    last = min(len(enc_t), np.floor((cmd_t[-1] + lo - enc_t[0]) / period + 1e-9) + 1)
    use = np.zeros(len(enc_t), bool)
    use[int(first):max(int(first), int(last))] = True
    return use


def clock_offset(cmd_t, cmd, enc_t, enc, lo, hi):
    spread = enc.std(axis=0)
    moving = spread > 1e-12 * (1 + np.abs(enc.mean(axis=0)))
    cmd, enc, spread = cmd[:, moving], enc[:, moving], spread[moving]
    period = enc_t[1] - enc_t[0]
    step = max(period, (hi - lo) / 20000)
    best, best_cost = None, np.inf
    for offset in np.minimum(lo + step * np.arange(int(np.ceil((hi - lo) / step)) + 1), hi):
        use = compared(cmd_t, enc_t, offset, offset)
        if use.sum() < max(4, len(enc_t) // 4):
            continue
        moved = np.column_stack([np.interp(enc_t[use] - offset, cmd_t, cmd[:, a]) for a in range(cmd.shape[1])])
        cost = np.mean(((enc[use] - moved) / spread) ** 2)
        if cost < best_cost:
            best, best_cost = offset, cost
    lo, hi = max(best - step, lo), min(best + step, hi)
    use = compared(cmd_t, enc_t, lo, hi)
    spline = CubicSpline(cmd_t, cmd, axis=0)
    slope = spline.derivative()
    target, times = enc[use], enc_t[use]
    found = least_squares(lambda d: ((target - spline(times - d[0])) / spread).ravel(), [best],
                          jac=lambda d: (slope(times - d[0]) / spread).reshape(-1, 1), bounds=([lo], [hi]),
                          xtol=1e-15, ftol=1e-15, gtol=1e-15)
    return found.x[0]


def motion_span(cmd_t, cmd):
    """The command's last sample at its first values and its first sample at its last values."""
    still = 1e-9 * (cmd.max(axis=0) - cmd.min(axis=0)) + 1e-12
    moved_from_start = np.any(np.abs(cmd - cmd[0]) > still, axis=1)
    moved_to_end = np.any(np.abs(cmd - cmd[-1]) > still, axis=1)
    departure = max(int(np.argmax(moved_from_start)) - 1, 0) if moved_from_start.any() else 0
    arrival = min(len(cmd_t) - 1 - int(np.argmax(moved_to_end[::-1])) + 1, len(cmd_t) - 1) if moved_to_end.any() else len(cmd_t) - 1
    return cmd_t[departure], cmd_t[arrival]


def decompose(meta, data):
    aligned = []
    lo, hi = meta["search"]
    ball = np.array(meta["ball"])
    for k, feed in enumerate(meta["feeds"]):
        cmd_t, cmd, enc_t, enc, inst_t, inst = data[k]
        offset = clock_offset(cmd_t, cmd, enc_t, enc, lo, hi)
        departure, arrival = motion_span(cmd_t, cmd)
        use = (inst_t >= max(departure + offset, enc_t[0])) & (inst_t <= min(arrival + offset, enc_t[-1]))
        t = inst_t[use]
        q_nom = CubicSpline(cmd_t + offset, cmd, axis=0)(t)
        q_enc = CubicSpline(enc_t, enc, axis=0)(t)
        chi_nom, chi_enc = tcp(q_nom) - ball, tcp(q_enc) - ball
        link = tcp(q_enc) - (chi_enc + ball)  # the identified machine is the nominal one here
        fgroup = np.column_stack([q_enc[:, :3], np.degrees(q_enc[:, 3:])])  # FGROUP: mm and deg on one length
        path = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(fgroup, axis=0), axis=1))])
        aligned.append((offset, path, inst[use], chi_enc, chi_nom, link, to_workpiece(q_enc)))

    def basis(path):
        return legendre.legvander(2 * (path - path[0]) / (path[-1] - path[0]) - 1, meta["degree"])

    ref = aligned[0]
    coef = np.linalg.lstsq(basis(ref[1]), ref[2] - ref[3] - ref[5], rcond=None)[0]
    out = []
    for k, (offset, path, chi, chi_enc, chi_nom, link, rotation) in enumerate(aligned):
        motion = basis(path) @ coef
        rest = chi - chi_enc - link - motion
        # The drift constant in the machine frame (seed 004): the mean of the rest turned there.
        drift = np.zeros(3) if k == 0 else np.einsum("nji,nj->ni", rotation, rest).mean(axis=0)
        drift_along = np.einsum("nij,j->ni", rotation, drift)
        dynamic = rest - drift_along
        contouring = chi_enc - chi_nom
        c, qs, d = (np.linalg.norm(v, axis=1) for v in (contouring, link + motion + drift_along, dynamic))
        total = c + qs + d
        out.append({"offset": offset, "drift": drift.tolist(), "rms": np.sqrt((dynamic ** 2).mean(axis=0)).tolist(),
                    "shares": [100 * np.mean(v / total) for v in (c, qs, d)], "samples": int(len(path))})
    return out


def main():
    folder, repeats = pathlib.Path(sys.argv[1]), int(sys.argv[2])
    meta = json.loads((folder / "meta.json").read_text())
    data = []
    for k in range(len(meta["feeds"])):
        traces = []
        for name, channels in (("command", 5), ("encoder", 5), ("instrument", 3)):
            start, period = meta[name][k]
            values = np.fromfile(folder / f"{name}{k}.bin").reshape(channels, -1).T.copy()
            traces += [start + period * np.arange(values.shape[0]), values]
        data.append(traces)
    check = np.array(meta["check_poses"])
    assert np.allclose(tcp(check[:, :5]), check[:, 5:], atol=1e-9), "the NumPy TCP differs from mtacc's"
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        tests = decompose(meta, data)
        seconds.append(time.perf_counter() - start)
    print(json.dumps({"seconds": seconds, "tests": tests}))


if __name__ == "__main__":
    main()
