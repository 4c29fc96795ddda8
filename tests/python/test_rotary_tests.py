"""`mtacc rotary-tests` and `Machine.rotary_tests` (ISO 10791-6): the CLI's JSON equals the API's, the
plan written is the one `simulate` reads (its runs simulate to the results reported), the programs are
written one per test, and a location error shows in the results the set-up is designed for."""
import json
import subprocess

import pytest

import mtacc


def test_cli_equals_api_and_the_plan_and_programs_are_written(cli, tmp_path):
    m = mtacc.Machine("tilting-table")
    r = m.rotary_tests(positions=12, points=72, plan_out=tmp_path / "plan.yaml", programs=tmp_path / "nc")
    out = subprocess.run([cli, "rotary-tests", "tilting-table", "--positions", "12", "--points", "72", "--plan-out",
                          str(tmp_path / "plan.yaml"), "--programs", str(tmp_path / "nc"), "--json"],
                         capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == r
    names = [t["name"] for t in r["tests"]]
    assert names == ["B-rtest-1", "B-rtest-2", "B-ballbar-radial", "B-ballbar-tangential", "B-ballbar-axial",
                     "C-rtest-1", "C-rtest-2", "C-ballbar-radial", "C-ballbar-tangential", "C-ballbar-axial"]
    assert sorted(p.stem for p in (tmp_path / "nc").glob("*.nc")) == sorted(names)
    runs = m.simulate(str(tmp_path / "plan.yaml"))
    assert [run["name"] for run in runs["runs"]] == names


def test_an_offset_of_the_c_line_shows_radially_not_axially():
    m = mtacc.Machine("tilting-table")
    for name in list(m.errors):
        del m.errors[name]
    m.errors["X0C"] = "10 um"
    tests = {t["name"]: t["results"] for t in m.rotary_tests(positions=12, points=72)["tests"]}
    assert tests["C-rtest-1"]["radial"]["range_um"] == pytest.approx(20, abs=1e-6)  # the circle's centre 10 um off
    assert tests["C-rtest-1"]["axial"]["range_um"] < 1e-6
    assert tests["B-rtest-1"]["radial"]["range_um"] < 1e-6
    assert "X0C" in [e["parameter"] for e in tests["C-ballbar-radial"]["length"]["sees"]]
