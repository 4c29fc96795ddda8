"""Baseline for bench_experiment_design_vs_numpy: the same D-optimal exchange as mtacc's
designExperiment, written as a competent NumPy user would: the greedy start scores every
candidate at once (X M^-1 for all candidates by one matrix product, the 3x3 determinant-lemma
matrices batched into np.linalg.slogdet); Fedorov's exchange scores, for each chosen block, the
swap with every candidate at once (the 6x6 lemma matrices batched), the best improving swap made,
until none improves.

Usage: experiment_design_numpy.py ROWS.bin META.json -> one JSON line {"seconds", "chosen", "criterion", "exchanges"}
"""
import json
import sys
import time

import numpy as np


def design(blocks, count, ridge, max_exchanges):
    n, r, p = blocks.shape
    info = np.einsum("nrp,nrq->npq", blocks, blocks)
    eye = np.eye(r)
    ridge_matrix = ridge * np.max(np.einsum("nrp,nrp->p", blocks, blocks)) * np.eye(p)
    chosen = []
    m = np.zeros((p, p))
    for _ in range(count):  # greedy start: log det(I + X_c (M + ridge)^-1 X_c^T)
        g = blocks @ np.linalg.inv(m + ridge_matrix)
        sign, logdet = np.linalg.slogdet(eye + np.einsum("nrp,nsp->nrs", g, blocks))
        best = int(np.argmax(np.where(sign > 0, logdet, -np.inf)))
        chosen.append(best)
        m += info[best]
    current = np.linalg.slogdet(m)[1]
    exchanges = 0
    k_matrix = np.empty((n, 2 * r, 2 * r))
    while exchanges < max_exchanges:
        g = blocks @ np.linalg.inv(m)
        k_matrix[:, :r, :r] = eye + np.einsum("nrp,nsp->nrs", g, blocks)
        best_value, best_out, best_in = current, -1, -1
        for k, out in enumerate(chosen):
            x_out = blocks[out]
            c = g @ x_out.T                                   # X_c M^-1 X_out^T, every candidate
            k_matrix[:, :r, r:] = c
            k_matrix[:, r:, :r] = -c.transpose(0, 2, 1)
            k_matrix[:, r:, r:] = eye - g[out] @ x_out.T
            sign, logdet = np.linalg.slogdet(k_matrix)
            values = np.where(sign > 0, current + logdet, -np.inf)
            values[out] = -np.inf
            i = int(np.argmax(values))
            if values[i] > best_value * (1 + 1e-12) + 1e-12:
                best_value, best_out, best_in = values[i], k, i
        if best_out < 0:
            break
        chosen[best_out] = best_in
        m = info[chosen].sum(axis=0)
        current = np.linalg.slogdet(m)[1]
        exchanges += 1
    return sorted(chosen), float(current), exchanges


def main():
    meta = json.loads(open(sys.argv[2]).read())
    n, r, p = meta["candidates"], meta["rows"], meta["parameters"]
    blocks = np.fromfile(sys.argv[1]).reshape(p, n * r).T.reshape(n, r, p)  # Eigen stores columns
    start = time.perf_counter()
    chosen, criterion, exchanges = design(blocks, meta["count"], meta["ridge"], meta["max_exchanges"])
    seconds = time.perf_counter() - start
    print(json.dumps({"seconds": seconds, "chosen": chosen, "criterion": criterion, "exchanges": exchanges}))


if __name__ == "__main__":
    main()
