"""Baseline for bench_sensor_selection_vs_numpy: forward stepwise selection of temperature
sensors for a drift regression by K-fold cross-validated RMS (contiguous blocks), written as a
competent NumPy user would: the blocks' Gram matrices of [1, T - mean(T)] by BLAS once, then at
each step every remaining candidate's training systems for every fold solved at once by batched
np.linalg.solve, the held-out squares from the Gram matrices; the final model by lstsq on
[1, T_S - T_S(0)].

Usage: sensor_selection_numpy.py DIR -> one JSON line {"seconds", "steps": [{sensor, rms}], "coefficients"}
"""
import json
import pathlib
import sys
import time

import numpy as np


def main():
    folder = pathlib.Path(sys.argv[1])
    meta = json.loads((folder / "meta.json").read_text())
    n, p, folds = meta["samples"], meta["sensors"], meta["folds"]
    temperatures = np.fromfile(folder / "temperatures.bin").reshape(p, n).T  # Eigen stores columns
    drift = np.fromfile(folder / "drift.bin")

    start = time.perf_counter()
    z = np.empty((n, p + 1))
    z[:, 0] = 1.0
    z[:, 1:] = temperatures - temperatures.mean(axis=0)
    y = drift - drift.mean()
    bounds = [n * f // folds for f in range(folds + 1)]
    blocks = list(zip(bounds[:-1], bounds[1:]))
    gram = np.stack([z[a:b].T @ z[a:b] for a, b in blocks])
    zy = np.stack([z[a:b].T @ y[a:b] for a, b in blocks])
    yy = np.array([y[a:b] @ y[a:b] for a, b in blocks])
    total_gram, total_zy = gram.sum(axis=0), zy.sum(axis=0)

    def cross_validated_rms(models):
        """models: c x m column indices -> the c models' cross-validated RMS."""
        rows, cols = models[:, :, None], models[:, None, :]
        held = gram[:, rows, cols]                           # folds x c x m x m
        train = total_gram[rows, cols][None] - held
        held_zy = zy[:, models]                              # folds x c x m
        beta = np.linalg.solve(train, (total_zy[models][None] - held_zy)[..., None])[..., 0]
        squares = yy[:, None] - 2 * np.einsum("fcm,fcm->fc", beta, held_zy) + np.einsum("fcm,fcmk,fck->fc", beta, held, beta)
        return np.sqrt(np.maximum(squares, 0).sum(axis=0) / n)

    keep = 1 - meta["minimum_improvement"]
    columns = [0]
    steps = [{"sensor": -1, "added": True, "rms": float(cross_validated_rms(np.array([columns]))[0])}]
    for _ in range(4 * p):
        if len(columns) - 1 >= min(meta["maximum_sensors"], p):
            break
        candidates = np.array([i for i in range(1, p + 1) if i not in columns])
        rms = cross_validated_rms(np.array([columns + [i] for i in candidates]))
        best = int(np.argmin(rms))
        if not rms[best] <= keep * steps[-1]["rms"]:
            break
        columns.append(int(candidates[best]))
        steps.append({"sensor": int(candidates[best]) - 1, "added": True, "rms": float(rms[best])})
        while len(columns) > 2:  # backward: drop the chosen sensor that costs least, if it costs too little
            without = [columns[:j] + columns[j + 1:] for j in range(1, len(columns) - 1)]
            rms = cross_validated_rms(np.array(without))
            cheapest = int(np.argmin(rms))
            if not keep * rms[cheapest] <= steps[-1]["rms"]:
                break
            steps.append({"sensor": columns[cheapest + 1] - 1, "added": False, "rms": float(rms[cheapest])})
            columns = without[cheapest]
    chosen = [c - 1 for c in columns[1:]]
    design = np.column_stack([np.ones(n), temperatures[:, chosen] - temperatures[0, chosen]])
    beta = np.linalg.lstsq(design, drift, rcond=None)[0]
    seconds = time.perf_counter() - start
    print(json.dumps({"seconds": seconds, "steps": steps, "coefficients": beta[1:].tolist()}))


if __name__ == "__main__":
    main()
