"""`mtacc plate`, `mtacc simulate plate`, `Machine.compare_plate` and `Machine.simulate_plate` (seed 003
hole plates): CLI and API alike, a plate simulated with the machine's own errors leaves only the
probe noise, one simulated with another model does not, and the plot and report section."""
import json
import pathlib
import subprocess

import numpy as np
import pytest

import mtacc
from mtacc import plots

DATA = pathlib.Path(__file__).resolve().parents[2] / "data" / "plates"


def test_cli_json_equals_api(cli):
    out = subprocess.run([cli, "plate", "maho", str(DATA / "maho-xy-z292.csv"), "--json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == mtacc.Machine("maho").compare_plate(DATA / "maho-xy-z292.csv")


def test_residual_is_the_probe_noise(tmp_path):
    # Simulated with 0.5 um noise on each coordinate of the App. D machine: against the same model
    # the residual's RMS is that noise (less the three misalignment terms), inside the k = 2 bound;
    # against the error-free model it is the App. D deviations, beyond it.
    m = mtacc.Machine("maho")
    path = tmp_path / "xz.csv"
    m.simulate_plate(path, origin=(-350, -400, -310), axes=((1, 0, 0), (0, 0, 1)), noise="0.5 um", probe=(0.63, 0.84),
                     simulation=6.3, seed=4)
    same = m.compare_plate(path)
    assert same["residual_rms_um"] == pytest.approx(0.5, rel=0.15)
    assert same["bound_um"] == pytest.approx(np.sqrt(6.3 ** 2 + 2 * (0.7 ** 2 + 0.63 ** 2 + 0.84 ** 2)))
    assert same["beyond_bound"] == 0
    free = tmp_path / "free.yaml"
    free.write_text("errors: {}\n")
    other = mtacc.Machine("maho", errors=free).compare_plate(path)
    assert other["residual_rms_um"] > 5 * same["residual_rms_um"]


def test_plot_and_report_section(cli, tmp_path):
    fig = plots.plate_vectors(mtacc.Machine("maho").compare_plate(DATA / "maho-xy-z292.csv"))
    assert len(fig.axes) == 2
    run = subprocess.run([cli, "report", "maho", "-o", str(tmp_path), "--samples", "3", "--plate", str(DATA / "maho-xy-z292.csv")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "Hole and ball plates (seed 003)" in (tmp_path / "maho-report.html").read_text()
