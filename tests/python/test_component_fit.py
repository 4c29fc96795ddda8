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


def _coefficient_basis(name, q, trend_breaks, periodic):
    # The basis of a fitted coefficient `k<i>c<p>` (file-formats.md, "Component runs"): u^p for
    # i = 0, else (u - t_i)_+^p; u is the position clamped to the trend's breaks, or the position
    # modulo the period from the periodic term's zero (its breaks split the period in quarters).
    knot, power = (int(x) for x in name.split(".k")[1].split("#")[0].split("c"))
    if "#" in name:
        period, zero = periodic
        u, breaks = np.mod(q - zero, period), [period * k / 4 for k in range(5)]
    else:
        u, breaks = np.clip(q, trend_breaks[0], trend_breaks[-1]), trend_breaks
    v = u if knot == 0 else np.maximum(u - breaks[knot], 0.0)
    return v ** power


@pytest.mark.parametrize("data, options", [("maho-xrx.csv", {"breaks": XRX_BREAKS}), ("maho-xtx.csv", {"pieces": 7, "period": 39.6})])
def test_the_fit_writes_the_machines_errors_with_its_record(cli, tmp_path, data, options):
    # Issue 44: `fit --errors-out` writes the form identify writes. The machine's other errors are
    # kept, the component is the fitted function, and the record's covariance of the coefficients
    # gives the fit's own standard uncertainty at every position (through the periodic term's map
    # from its free parameters to its coefficients where there is one).
    import hashlib
    import yaml
    m = mtacc.Machine("maho")
    path = tmp_path / "fitted.yaml"
    r = m.fit_component(DATA / data, errors_out=path, **options)
    args = ["--breaks", ",".join(map(str, XRX_BREAKS))] if "breaks" in options else ["--pieces", "7", "--period", "39.6"]
    subprocess.run([cli, "fit", "maho", str(DATA / data), *args, "--errors-out", str(tmp_path / "cli.yaml")], check=True, capture_output=True)
    strip = lambda text: [line for line in text.splitlines() if "date:" not in line]
    assert strip((tmp_path / "cli.yaml").read_text()) == strip(path.read_text())
    assert subprocess.run([cli, "check", "maho", "--errors", str(path)], capture_output=True).returncode == 0

    fitted = dict(mtacc.Machine("maho", errors=path).errors)
    alone = tmp_path / "alone.yaml"
    alone.write_text("errors:\n" + r["yaml"])
    component = r["iso_name"] + "."
    # The same function both ways, to the last bit of its values: a coefficient that is zero in one
    # may be a rounding residue (1e-18 mm) in the other, listed there and not here.
    written = {k: v for k, v in fitted.items() if k.startswith(component)}
    expected = dict(mtacc.Machine("maho", errors=alone).errors)
    for name in set(written) | set(expected):
        assert written.get(name, 0.0) == pytest.approx(expected.get(name, 0.0), rel=1e-6, abs=1e-15), name
    assert {k: v for k, v in fitted.items() if not k.startswith(component)} == pytest.approx(
        {k: v for k, v in m.errors.items() if not k.startswith(component)}, rel=1e-12, abs=1e-15)
    record = yaml.safe_load(path.read_text())["identification"]
    assert record["by"].endswith(" fit") and record["held"] == {}
    assert record["data"][0]["sha256"] == hashlib.sha256((DATA / data).read_bytes()).hexdigest()
    assert record["removed_terms"] == r["fit"]["removed"]
    estimates = record["estimates"]
    assert all(e["parameter"].startswith(r["iso_name"] + ".k") for e in estimates)
    covariance = np.array(record["covariance"], dtype=float)
    scale = [float(e["standard_uncertainty"].split()[0]) for e in estimates]
    assert np.sqrt(np.diag(covariance)) == pytest.approx(scale, rel=1e-12)
    periodic = (r["fit"]["periodic"], 0.0) if r["fit"]["periodic"] else None
    # The units: the coefficient of u^p in um (or urad) per mm^p.
    x = np.array(r["fit"]["grid"])
    basis = np.array([_coefficient_basis(e["parameter"], x, r["fit"]["breaks"], periodic) for e in estimates])
    values = np.array([float(e["value"].split()[0]) for e in estimates])
    assert values @ basis == pytest.approx(r["fit"]["grid_value"], abs=1e-9 * max(1.0, np.abs(r["fit"]["grid_value"]).max()))
    # 15 digits a covariance entry; the quadratic form over u^2 up to 700^2 mm^2 cancels about 7 of them.
    assert np.sqrt(np.einsum("ip,ij,jp->p", basis, covariance, basis)) == pytest.approx(r["fit"]["grid_uncertainty"], rel=1e-6)


def test_simulated_runs_round_trip(cli, tmp_path):
    out = tmp_path / "ztz.csv"
    run = subprocess.run([cli, "simulate", "component", "maho", "--component", "ztz", "--noise", "0.3um", "--runs", "5", "-o", str(out),
                          "--json"], capture_output=True, text=True, check=True)
    assert json.loads(run.stdout) == {"output": str(out), "component": "ztz", "positions": 61, "runs_each_way": 5}
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
