"""`mtacc fit`, `mtacc simulate component` and `Machine.fit_component`: the same numbers from the
CLI and the API, the fitted YAML loading into the machine, the pump's disturbances found in the
bundled runs, the plot and the report section. (The recovery of the truth is checked in C++:
ComponentFit.*, ComponentFitWorkflow.*.)"""
import json
import pathlib
import subprocess

import numpy as np
import pytest

import mtacc
from mtacc import plots

DATA = pathlib.Path(__file__).resolve().parents[2] / "data" / "direct-measurements"
XRX_BREAKS = [0, 50, 100, 200, 300, 400, 500, 600, 700]


def test_cli_json_equals_api(cli):
    out = subprocess.run([cli, "fit", "maho", str(DATA / "maho-xrx.csv"), "--breaks", ",".join(map(str, XRX_BREAKS)), "--json"],
                         capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == mtacc.Machine("maho").fit_component(DATA / "maho-xrx.csv", breaks=XRX_BREAKS)


def test_fitted_yaml_is_the_machines_error(tmp_path):
    # maho-xrx.csv was simulated with a 4" peak every 30 min (mtacc simulate component): the peaks
    # are flagged at that interval. The fitted entry, as the machine's only error, turns the tool
    # about X by -xrx at C = B = 0 (seed 003 §4.4: the B-chain's rotations are subtracted).
    r = mtacc.Machine("maho").fit_component(DATA / "maho-xrx.csv", breaks=XRX_BREAKS, remove_disturbed=True)
    assert r["disturbances"]["interval_s"] == pytest.approx(1800, abs=6)
    assert len(r["disturbances"]["readings"]) >= 8
    path = tmp_path / "xrx.yaml"
    path.write_text("errors:\n" + r["yaml"])
    m = mtacc.Machine("maho", errors=path)
    names = [a["name"] for a in m.axes]
    x = np.array(r["fit"]["grid"])
    q = np.zeros((len(x), len(names)))
    q[:, names.index("X")] = x
    assert m.tcp_errors(q)[:, 3] == pytest.approx(-np.array(r["fit"]["grid_value"]), abs=1e-6)


def test_simulated_runs_round_trip(cli, tmp_path):
    out = tmp_path / "ztz.csv"
    subprocess.run([cli, "simulate", "component", "maho", "--component", "ztz", "--noise", "0.3um", "--runs", "5", "-o", str(out)],
                   capture_output=True, text=True, check=True)
    r = mtacc.Machine("maho").fit_component(out, pieces=3)
    assert r["iso_name"] == "EZZ" and len(r["runs_forward"]) == 5 and len(r["positions"]) == 61
    mtacc.Machine("maho").simulate_component("ztz", tmp_path / "api.csv", runs=5, noise="0.3 um")
    assert (tmp_path / "api.csv").read_text() == out.read_text()


def test_unsettled_runs_are_flagged_and_can_be_left_out(cli, tmp_path):
    # A 2" drift at the start dying away in 15 min: the first runs are flagged (the C++ test
    # Seed003DirectMeasurement.UnsettledRunsAtTheStartAreFlagged pins how many); left out, the mean
    # of the rest is closer to the machine's xrx than the mean of all.
    out = tmp_path / "xrx.csv"
    subprocess.run([cli, "simulate", "component", "maho", "--component", "xrx", "--noise", "0.1arcsec", "--settling", "2arcsec",
                    "--settling-time", "900", "--seed", "3", "-o", str(out)], capture_output=True, text=True, check=True)
    m = mtacc.Machine("maho")
    flagged = m.fit_component(out, pieces=7)
    unsettled = flagged["disturbances"]["unsettled_runs"]
    assert unsettled == list(range(1, len(unsettled) + 1)) and len(unsettled) >= 3
    left_out = m.fit_component(out, pieces=7, remove_disturbed=True)
    assert f"the first {len(unsettled)} run(s), not yet settled, left out" in left_out["corrections"]
    # Their drift, about (1.25 + 0.48 + 0.18 + 0.07)" / 20 = 0.1" = 0.48 urad on the mean of all 20 runs, leaves it.
    shift = np.mean(np.asarray(flagged["mean"]) - np.asarray(left_out["mean"]))
    assert 0.3 < shift < 0.6
    assert m.fit_component(DATA / "maho-xrx.csv", pieces=7)["disturbances"]["unsettled_runs"] == []


def test_plot_and_report_section(cli, tmp_path):
    fig = plots.component_fit(mtacc.Machine("maho").fit_component(DATA / "maho-xtx.csv", pieces=7, period=39.6))
    assert fig.axes[0].get_ylabel() == "xtx [um]"
    run = subprocess.run([cli, "report", "maho", "-o", str(tmp_path), "--samples", "3", "--component", str(DATA / "maho-xrx.csv")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    html = (tmp_path / "maho-report.html").read_text()
    assert "Component errors from direct measurements" in html and "piecewise:" in html
