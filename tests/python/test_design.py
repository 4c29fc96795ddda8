"""`mtacc design` and `Machine.design`: the CLI's JSON equals the API's, the plan written is read by
`observability` with the prediction the design printed, the report is written whole for the operator,
and what cannot be designed is refused with its reason and leaves no file."""
import json
import pathlib
import subprocess

import pytest

import mtacc

ROOT = pathlib.Path(__file__).resolve().parents[2]
HEAD = str(ROOT / "docs" / "examples" / "inclined-head.yaml")


def test_cli_equals_api_and_the_plan_predicts_what_the_design_printed(cli, tmp_path):
    m = mtacc.Machine("tilting-table")
    r = m.design(time="30min", plan="tilting-table-rtest", plan_out=tmp_path / "designed.yaml")
    out = subprocess.run([cli, "design", "tilting-table", "--time", "30min", "--plan", "tilting-table-rtest", "--plan-out",
                          str(tmp_path / "designed.yaml"), "--json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == r
    assert r["design"]["time_min"] <= 30 + 1e-9
    assert r["own_plan"]["time_min"] > r["design"]["time_min"]
    predicted = m.observability(str(tmp_path / "designed.yaml"))["prediction"]
    assert predicted["noise_source"] == "the runs' own noise"
    by_name = {e["parameter"]: e["expanded_uncertainty_k2"] for e in predicted["estimates"] if not e["setup"]}
    for p in r["design"]["parameters"]:
        assert by_name[p["name"]] == pytest.approx(p["u_k2"], rel=1e-6)
    times = [p["time_min"] for p in r["pareto"] if "time_min" in p]
    tcp = [p["tcp_rms_k2_um"] for p in r["pareto"] if "time_min" in p]
    assert times == sorted(times) and tcp == sorted(tcp, reverse=True)  # more time, less uncertainty


def test_the_report_is_written_for_the_operator(cli, tmp_path):
    report = tmp_path / "design.html"
    subprocess.run([cli, "design", "docs/examples/inclined-head.yaml", "--plan", "docs/examples/inclined-head-rtest.yaml", "--time",
                    "29.5min", "--criterion", "plan", "--html", str(report)], capture_output=True, text=True, check=True,
                   cwd=ROOT)
    text = report.read_text()
    for heading in ("The plan, in the order it is run", "What it determines", "Time against uncertainty", "The plan file"):
        assert heading in text
    assert text.count("<svg") == 4  # timeline, set-ups, uncertainties, Pareto
    assert "your plan" in text


def test_what_no_run_can_separate_is_refused_and_nothing_is_written(cli, tmp_path):
    plan = tmp_path / "plan.yaml"
    out = subprocess.run([cli, "design", "docs/examples/inclined-head.yaml", "--params", "X0B,X0C,C.zero", "--instruments", "rtest",
                          "--time", "1h", "--plan-out", str(plan), "--html", str(tmp_path / "r.html")],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 2
    assert "X0B and X0C act alike" in out.stderr and "C.zero has no effect" in out.stderr
    assert not plan.exists() and not (tmp_path / "r.html").exists()
    with pytest.raises(mtacc.InputError, match="act alike"):
        mtacc.Machine(HEAD).design(time="1h", parameters=["X0B", "X0C"], instruments="rtest")
