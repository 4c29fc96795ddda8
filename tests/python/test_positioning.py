"""`mtacc positioning` and `mtacc.positioning` (ISO 230-2): the library's numbers against a vectorised
NumPy evaluation of the standard's formulas on the real motion-stage file and the rotary example,
the CLI's JSON equal to the API's, the chart, and the report section."""
import json
import pathlib
import re
import subprocess

import numpy as np
import pytest

import mtacc
from mtacc import plots

DATA = pathlib.Path(__file__).resolve().parents[2] / "data" / "positioning"


def numpy_iso230_2(up, down):
    """ISO 230-2:2014 from deviations (targets x cycles), written with NumPy, independently of the library."""
    mu, md = up.mean(1), down.mean(1)
    su, sd = up.std(1, ddof=1), down.std(1, ddof=1)
    mean, b = (mu + md) / 2, mu - md
    ru, rd = 4 * su, 4 * sd
    r = np.maximum.reduce([2 * su + 2 * sd + abs(b), ru, rd])
    hi_u, lo_u, hi_d, lo_d = (mu + 2 * su).max(), (mu - 2 * su).min(), (md + 2 * sd).max(), (md - 2 * sd).min()
    return {"A_forward": hi_u - lo_u, "A_backward": hi_d - lo_d, "A": max(hi_u, hi_d) - min(lo_u, lo_d),
            "E_forward": np.ptp(mu), "E_backward": np.ptp(md), "E": max(mu.max(), md.max()) - min(mu.min(), md.min()),
            "M": np.ptp(mean), "B": abs(b).max(), "B_mean": b.mean(),
            "R_forward": ru.max(), "R_backward": rd.max(), "R": r.max()}, {"mean": mean, "reversal": b, "repeatability": r}


def read_dat(path):
    values = {}
    for line in open(path):
        m = re.match(r"(TGT_DATA|REF_DATA_FWD|REF_DATA_BWD)\[(\d+)(?:,(\d+))?\]=(.*)", line.strip())
        if m:
            values[(m[1], int(m[2]), int(m[3] or 0))] = float(m[4])
    m = max(k[1] for k in values)
    n = max(k[2] for k in values)
    targets = np.array([values[("TGT_DATA", i, 0)] for i in range(1, m + 1)])
    up = np.array([[values[("REF_DATA_FWD", i, j)] for j in range(1, n + 1)] for i in range(1, m + 1)]) - targets[:, None]
    down = np.array([[values[("REF_DATA_BWD", i, j)] for j in range(1, n + 1)] for i in range(1, m + 1)]) - targets[:, None]
    return targets, up, down


def test_real_file_matches_numpy():
    targets, up, down = read_dat(DATA / "ecmc-motion-stage.dat")
    expected, per_target = numpy_iso230_2(up * 1e3, down * 1e3)
    r = mtacc.positioning(DATA / "ecmc-motion-stage.dat")
    assert r["unit"] == "um" and r["cycles"] == 5 and r["notes"] == []
    for key, value in expected.items():
        assert r["axis_values"][key] == pytest.approx(value, abs=1e-9), key
    for key, values in per_target.items():
        assert [p[key] for p in r["positions"]] == pytest.approx(values, abs=1e-9), key
    assert [p["target"] for p in r["positions"]] == pytest.approx(targets)


def test_rotary_csv_matches_numpy():
    lines = [line for line in open(DATA / "rotary-table.csv") if not line.startswith("#")]
    rows = np.loadtxt(lines[1:], delimiter=",")
    targets = np.unique(rows[:, 0])
    up = np.array([rows[rows[:, 0] == t, 2] for t in targets]) * 3600
    down = np.array([rows[rows[:, 0] == t, 3] for t in targets]) * 3600
    expected, _ = numpy_iso230_2(up, down)
    r = mtacc.positioning(DATA / "rotary-table.csv")
    assert r["axis"] == "rotary" and r["unit"] == "arcsec" and r["target_unit"] == "deg"
    for key, value in expected.items():
        assert r["axis_values"][key] == pytest.approx(value, abs=1e-9), key


def test_cli_json_equals_api_and_csv_is_written(cli, tmp_path):
    path = DATA / "ecmc-motion-stage.dat"
    out = subprocess.run([cli, "iso230-2", str(path), "--json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == mtacc.positioning(path)
    table = tmp_path / "iso.csv"
    subprocess.run([cli, "positioning", str(path), "-o", str(table)], capture_output=True, text=True, check=True)
    text = table.read_text()
    assert "# R: " in text and "# U_R: " in text and text.count("\n") == 12 + 11 + 1 + 1 + 5
    bad = tmp_path / "bad.dat"
    bad.write_text("UNIT=mm\nCYCLES=5\nPOSITIONS=2\nTGT_DATA[1]=0\nTGT_DATA[3]=1\n")
    run = subprocess.run([cli, "positioning", str(bad), "-o", str(tmp_path / "none.csv")], capture_output=True, text=True)
    assert run.returncode != 0 and run.stderr.count("\n") == 1 and f"{bad}:5: TGT_DATA[3]:" in run.stderr
    assert not (tmp_path / "none.csv").exists()


def test_chart_and_report_section(cli, tmp_path):
    fig = plots.positioning_chart(mtacc.positioning(DATA / "rotary-table.csv"))
    assert fig.axes[0].get_ylabel() == "positional deviation [arcsec]"
    run = subprocess.run([cli, "report", "three-axis-vertical", "-o", str(tmp_path), "--samples", "3",
                          "--positioning", str(DATA / "ecmc-motion-stage.dat")], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    html = (tmp_path / "three-axis-vertical-report.html").read_text()
    assert "Positioning (ISO 230-2)" in html and "ecmc-motion-stage" in html


def test_uncertainty_and_verdicts_on_the_real_file(cli):
    """The bundled conditions and tolerances: the CLI's JSON equals the API's, every U combines the
    contributors the budget says enter it, and every verdict follows ISO 14253-1 from value, U and
    tolerance."""
    args = dict(data=DATA / "ecmc-motion-stage.dat", conditions=DATA / "ecmc-motion-stage-conditions.yaml",
                tolerances=DATA / "ecmc-motion-stage-tolerances.yaml")
    r = mtacc.positioning(**args)
    out = subprocess.run([cli, "positioning", str(args["data"]), "--conditions", str(args["conditions"]),
                          "--tolerances", str(args["tolerances"]), "--json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == r
    budget = r["uncertainty"]
    assert budget["measured_length"] == {"value": 40, "unit": "mm"} and budget["defaulted"] == []
    for q, values in budget["quantities"].items():
        entering = [c["u"] for c in budget["contributors"] if q in c["quantities"]]
        assert values["U"] == pytest.approx(2 * np.sqrt(values["u_cycles"] ** 2 + np.sum(np.square(entering))), rel=1e-12), q
        assert values["value"] == pytest.approx(r["axis_values"][q], abs=1e-12), q
    conformance = r["conformance"]
    assert conformance["decision_rule"] == "iso14253-1"
    verdicts = {v["quantity"]: v for v in conformance["verdicts"]}
    assert {q: v["verdict"] for q, v in verdicts.items()} == {"A": "pass", "B": "undecided", "E": "undecided", "M": "fail",
                                                              "R": "pass"}
    for v in verdicts.values():
        expected = ("pass" if v["value"] + v["U"] <= v["tolerance"] else
                    "fail" if v["value"] - v["U"] > v["tolerance"] else "undecided")
        assert v["verdict"] == expected and v["U"] == budget["quantities"][v["quantity"]]["U"]
    assert conformance["overall"] == "fail"


def test_rotary_axis_with_its_tolerances():
    r = mtacc.positioning(DATA / "rotary-table.csv", tolerances=DATA / "rotary-tolerances.yaml")
    assert [c["symbol"] for c in r["uncertainty"]["contributors"]] == ["u_DEVICE", "u_EVE"]
    assert r["uncertainty"]["defaulted"] == ["calibration", "drift"]
    assert {v["quantity"] for v in r["conformance"]["verdicts"]} == {"A", "E", "R", "B"}
    with pytest.raises(mtacc.InputError, match="conditions.yaml:5: type: a rotary axis"):
        mtacc.positioning(DATA / "rotary-table.csv", conditions=DATA / "ecmc-motion-stage-conditions.yaml")
