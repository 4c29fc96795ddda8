"""`mtacc acceptance` and `Machine.acceptance`: the bundled example's verdicts follow the decision
rule from each value, U and tolerance; the CLI's JSON equals the API's; the HTML report has the
summary first and a section with a figure per test, and renders in headless Chromium without errors;
bad input stops before any report is written."""
import json
import pathlib
import re
import subprocess

import pytest

import mtacc
from test_report import rendered_in_chromium

DATA = pathlib.Path(__file__).resolve().parents[2] / "data" / "acceptance"
TESTS = DATA / "tilting-table-acceptance.yaml"


def test_verdicts_follow_the_rule_and_the_cli_equals_the_api(cli):
    r = mtacc.Machine("tilting-table").acceptance(str(TESTS))
    out = subprocess.run([cli, "acceptance", "tilting-table", "--tests", str(TESTS), "--json"], capture_output=True, text=True,
                         check=True)
    assert json.loads(out.stdout) == r
    assert [t["standard"] for t in r["tests"]] == ["ISO 230-2"] + ["ISO 10791-6"] * 4 + ["ISO 230-1"] * 2 + ["ISO 230-4", "ISO 230-3"]
    for s in r["summary"]:
        expected = ("pass" if s["value"] + s["U"] <= s["tolerance"] else
                    "fail" if s["value"] - s["U"] > s["tolerance"] else "undecided")
        assert s["verdict"] == expected, s
        assert s["U"] > 0
    verdicts = {s["verdict"] for s in r["summary"]}
    assert verdicts == {"pass", "fail", "undecided"} and r["overall"] == "fail"
    rtest = r["tests"][1]
    assert rtest["section"] == "rotary_rtest" and set(rtest["detail"]["deviations"]) == {"radial", "tangential", "axial"}
    assert r["tests"][5]["section"] == "straightness" and r["tests"][6]["section"] == "angular_deviation"
    circle = r["tests"][7]
    assert circle["section"] == "circular" and [v["quantity"] for v in circle["conformance"]["verdicts"]] == ["G", "H", "F"]
    # The circle's G against the ISO 230-4 evaluation `evaluate` gives: the same number.
    evaluated = mtacc.Machine("tilting-table").evaluate_ballbar(str(DATA / "runs" / "ballbar-XY.csv"))
    assert circle["conformance"]["verdicts"][0]["value"] == pytest.approx(max(d["circular_deviation_um"] for d in evaluated["directions"]), abs=1e-9)
    drift = r["tests"][8]
    direct = mtacc.drift_test(str(DATA.parent / "thermal" / "z-axis-drift.csv"))
    ranges = {d["direction"]: d["range"] for d in direct["directions"]}
    assert {v["quantity"]: v["value"] for v in drift["conformance"]["verdicts"]} == pytest.approx({"Y": ranges["Y"], "Z": ranges["Z"]})
    assert [k["symbol"] for k in drift["uncertainty"]["contributors"]] == ["u_DEVICE"]  # the drift is the measurand


def test_html_report_renders_in_chromium(cli, tmp_path, artifacts):
    page = tmp_path / "acceptance.html"
    run = subprocess.run([cli, "acceptance", "tilting-table", "--tests", str(TESTS), "--html", str(page)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    text = page.read_text()
    assert text.index("<h2>Summary</h2>") < text.index("<h2>X positioning: ISO 230-2</h2>")
    assert "Overall verdict: <b" in text and "ISO 14253-1" in text and "u_DEVICE" in text
    assert text.count('<figure class="plot">') == 2 * 9
    assert not re.search(r'(src|href)\s*=\s*["\']?(https?:)?//', text)
    expected, rendered, errors = rendered_in_chromium(page, tmp_path / "chromium-profile")
    assert expected == 18 and rendered == expected and errors == ""
    (artifacts / "acceptance-tilting-table.html").write_text(text)


def test_bad_tests_file_writes_nothing(cli, tmp_path):
    bad = tmp_path / "tests.yaml"
    bad.write_text("tests:\n  - test: positioning\n    data: missing.dat\n")
    page = tmp_path / "acceptance.html"
    run = subprocess.run([cli, "acceptance", "tilting-table", "--tests", str(bad), "--html", str(page)], capture_output=True, text=True)
    assert run.returncode == 2 and run.stderr.count("\n") == 1 and "missing.dat" in run.stderr
    assert not page.exists()
    with pytest.raises(mtacc.InputError, match="no tolerance file"):
        (tmp_path / "ok.yaml").write_text(f"tests:\n  - test: positioning\n    data: {DATA.parent / 'positioning' / 'rotary-table.csv'}\n")
        mtacc.Machine("tilting-table").acceptance(str(tmp_path / "ok.yaml"))
