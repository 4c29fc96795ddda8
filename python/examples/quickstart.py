"""Quick start: the README's Python example, run by the test suite (tests/python/test_examples.py)."""
import numpy as np

import mtacc
from mtacc import plots

m = mtacc.Machine("tilting-table")               # bundled machine with its errors, or a YAML file
m.errors["X0C"] = "8 um"                          # ISO names or aliases, values with units
q = np.array([[10, 20, 30, -15, 45], [0, 0, 100, -30, 90]])   # axis positions, mm and degrees
tcp, tool = m.fk(q)                               # (n, 3) TCP [mm], (n, 3) tool direction
err = m.tcp_errors(q)                             # (n, 6) dx dy dz [um], rotation [urad]

phi = np.radians(np.arange(0, 360, 5))            # a circle with the tool tilted 30 deg to its centre
tcps = np.stack([40 * np.cos(phi) - 60, 40 * np.sin(phi), np.full_like(phi, 50)], axis=1)
tools = np.stack([-0.5 * np.cos(phi), -0.5 * np.sin(phi), np.full_like(phi, np.sqrt(0.75))], axis=1)
path = m.ik_path(tcps, tools, branch="negative")  # (n, axes) for a continuous path

names, J = m.jacobian(q[0])                       # 6 x parameters, exact model
budget = m.budget()                               # the same numbers as `mtacc budget --json`
cone = m.cone(single_errors=True)                 # the seed 000 cone frustum, as `mtacc cone`
cubic = m.cubic(grid=0.05)                        # seed 001 cubic test; cubic["heights_um"] is the surface
fig = plots.volumetric_error_map(m, ("X", "Y"))

if __name__ == "__main__":
    print(f"TCP error at the first pose: {err[0, :3].round(3)} um")
    print(f"largest single error: {budget['entries'][0]['error']}, cone form error {cone['form_error_um']:.2f} um")
    print("cubic test zone heights referenced to zone I [um]:",
          ", ".join(f"{z['name']} {z['measured']['mean_um']:.2f}" for z in cubic["zones"]))
    fig.savefig("map.svg")
