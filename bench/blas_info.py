"""Which BLAS NumPy runs here, for the benchmarks' header: the BLAS and LAPACK libraries loaded once
NumPy has multiplied two matrices (Debian's alternatives choose among OpenBLAS, ATLAS, BLIS and the
reference BLAS at run time), and for OpenBLAS the core it chose for this CPU.

Usage: blas_info.py -> one line
"""
import ctypes
import os
import re

import numpy as np


def main():
    np.ones((64, 64)) @ np.ones((64, 64))
    np.linalg.solve(np.eye(4), np.ones(4))
    with open("/proc/self/maps") as maps:
        loaded = sorted({line.split()[-1] for line in maps if re.search(r"(blas|lapack|atlas|blis|mkl)[^/]*\.so", line)})
    def describe(path):
        if "openblas" in path:
            library = ctypes.CDLL(path)
            library.openblas_get_corename.restype = library.openblas_get_config.restype = ctypes.c_char_p
            return f"OpenBLAS, core {library.openblas_get_corename().decode()} ({library.openblas_get_config().decode()}) {path}"
        kind = "ATLAS" if "atlas" in path else "BLIS" if "blis" in path else "MKL" if "mkl" in path else "reference"
        return f"{kind} {path}"

    blas = [p for p in loaded if re.search(r"(open)?blas|blis|mkl", os.path.basename(p))]
    lapack = [p for p in loaded if "lapack" in os.path.basename(p)]
    print(f"BLAS: {', '.join(describe(p) for p in blas) or 'none found'}; LAPACK: {', '.join(lapack) or 'in the BLAS'}")

if __name__ == "__main__":
    main()
