"""Python side of bench_python_batch_fk: Machine.fk on the poses of POSES.csv (mm, deg), at one
thread, timed per call.

Usage: python_batch_fk.py PACKAGE_DIR POSES.csv REPEATS
    -> one JSON line {"seconds": [...], "tcp": [[x, y, z] of the first 1000 poses]}
"""
import json
import sys
import time

import numpy as np

sys.path.insert(0, sys.argv[1])
import mtacc  # noqa: E402


def main():
    q = np.loadtxt(sys.argv[2], delimiter=",")
    repeats = int(sys.argv[3])
    machine = mtacc.Machine("tilting-table")
    seconds = []
    for _ in range(repeats):
        start = time.perf_counter()
        tcp, _ = machine.fk(q, threads=1)
        seconds.append(time.perf_counter() - start)
    print(json.dumps({"seconds": seconds, "tcp": tcp[:1000].tolist()}))


if __name__ == "__main__":
    main()
