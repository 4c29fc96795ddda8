"""Identification through the Python module and the CLI: the same files give the same numbers."""
import json
import os
import pathlib
import re
import subprocess

import pytest

import mtacc

CLI = os.environ.get("MTACC_CLI", "mtacc")


def test_api_and_cli_identify_alike(tmp_path):
    m = mtacc.Machine("tilting-table")
    runs = m.simulate("tilting-table-rtest", noise="0.5 um", seed=3, output=tmp_path)["runs"]
    files = [r["file"] for r in runs]
    assert files == [str(tmp_path / (r["name"] + ".csv")) for r in runs]
    params = ["X0B", "Z0B", "A0B", "C0B", "X0C", "Y0C", "A0C", "B0C", "C0Y", "A0Z", "B0Z"]
    api = m.identify(files, params)
    # One --data with several files, and --data repeated: both forms of the README.
    one = subprocess.run([CLI, "identify", "tilting-table", "--json", "--params", ",".join(params), "--data", *files],
                         capture_output=True, text=True, check=True).stdout
    repeated = subprocess.run([CLI, "identify", "tilting-table", "--json", "--params", ",".join(params),
                               *sum((["--data", f] for f in files), [])], capture_output=True, text=True, check=True).stdout
    assert one == repeated
    assert json.loads(one) == api  # the same workflow, serialised once
    assert api["observability"]["identifiable"]
    assert [e["parameter"] for e in api["estimates"]][:len(params)] == params
    n = len(api["estimates"])
    assert len(api["covariance"]) == n and len(api["correlation"]) == n
    assert api["quality"]["noise_source"] == "the files' '# noise:' lines"
    assert 0 <= api["quality"]["p_value"] <= 1


def test_noise_argument_and_warnings(tmp_path):
    m = mtacc.Machine("tilting-table")
    files = [r["file"] for r in m.simulate("tilting-table-rtest", noise="0.5 um", output=tmp_path)["runs"]]
    params = ["X0B", "Z0B", "A0B", "C0B", "X0C", "Y0C", "A0C", "B0C", "C0Y", "A0Z", "B0Z"]
    # A stated noise a tenth of the true one: the residuals cannot be explained by it.
    doubtful = m.identify(files, params, noise="0.05 um")
    assert doubtful["quality"]["noise_source"] == "--noise"
    assert doubtful["quality"]["p_value"] < 0.01
    assert any("larger than the stated noise" in w for w in doubtful["quality"]["warnings"])
    with pytest.raises(mtacc.InputError, match="uncertainty_fraction"):
        m.identify(files, params, uncertainty_fraction=0)


def test_unidentifiable_set_is_refused(tmp_path):
    m = mtacc.Machine("tilting-table")
    files = [r["file"] for r in m.simulate("tilting-table-rtest", output=tmp_path)["runs"]]
    with pytest.raises(mtacc.InputError, match="B0B and B0C act alike"):
        m.identify(files, ["B0B", "B0C"])


def test_ballbar_evaluation(tmp_path):
    out = tmp_path / "xy.csv"
    subprocess.run([CLI, "simulate", "ballbar", "three-axis-vertical", "--centre", "300,200,250", "--radius", "100mm",
                    "--lag", "X=1ms", "-o", str(out)], check=True, capture_output=True)
    ev = mtacc.Machine("three-axis-vertical").evaluate_ballbar(out)
    assert ev["diagnostics"]["servo_mismatch_ms"] == pytest.approx(1.0, rel=0.02)
    assert len(ev["directions"]) == 2
    cli = json.loads(subprocess.run([CLI, "evaluate", "three-axis-vertical", str(out), "--json"], capture_output=True, text=True,
                                    check=True).stdout)
    assert cli == ev


def test_held_errors_are_named_and_from_nominal_holds_them_at_zero(tmp_path):
    # Data simulated on the machine with its full model; identified with the plan's location
    # errors only. Against the machine file's values the other errors are already right (and
    # named as held); against the nominal machine they are missing and the fit says so.
    m = mtacc.Machine("tilting-table")
    files = [r["file"] for r in m.simulate("tilting-table-rtest", noise="0.5 um", seed=5, output=tmp_path)["runs"]]
    held = m.identify(files, plan="tilting-table-rtest")
    assert "EXX.cyc" in held["held"] and "X0B" not in held["held"]
    out = subprocess.run([CLI, "identify", "tilting-table", "--plan", "tilting-table-rtest", "--data", *files],
                         capture_output=True, text=True, check=True).stdout
    assert f"not determined: {', '.join(held['held'][:8])}, ... ({len(held['held'])}); --from-nominal holds them at zero" in out
    nominal = m.identify(files, plan="tilting-table-rtest", from_nominal=True)
    assert nominal["held"] == []
    assert held["quality"]["p_value"] > 0.001 and nominal["quality"]["p_value"] < 1e-6


def test_simulate_takes_set_up_errors_as_the_cli_does(tmp_path):
    m = mtacc.Machine("tilting-table")
    api = m.simulate("tilting-table-rtest", noise="0.5 um", seed=2, setup={"xW": "10 um", "zT": "-5 um"}, output=tmp_path / "api")
    subprocess.run([CLI, "simulate", "plan", "tilting-table", "--plan", "tilting-table-rtest", "--noise", "0.5um", "--seed", "2",
                    "--setup", "xW=10um,zT=-5um", "-o", str(tmp_path / "cli")], capture_output=True, text=True, check=True)
    for run in api["runs"]:
        assert (tmp_path / "cli" / (run["name"] + ".csv")).read_text() == (tmp_path / "api" / (run["name"] + ".csv")).read_text()
    plain = m.simulate("tilting-table-rtest", noise="0.5 um", seed=2)
    assert api["runs"][0]["readings_um"] != plain["runs"][0]["readings_um"]
    with pytest.raises(mtacc.InputError, match="missing unit"):
        m.simulate("tilting-table-rtest", setup={"xW": 0.01})


def test_plan_names_component_terms_the_errors_do_not_define(tmp_path):
    # The truth has a second harmonic of C's positioning error at 30 deg and a linear X scale
    # error; the identifying machine defines neither. The plan names them as terms: ECC.h2
    # (amplitude and phase, as its cosine and sine parts) and EXX.c1 (the slope over half the
    # X travel). Noise-free data and a model that holds the truth: recovered to the solver's
    # stopping step (1e-6 of a typical 1 um or 10 urad), checked to 1e-4.
    truth = tmp_path / "truth.yaml"
    truth.write_text("errors:\n  X0C: -5 um\n  Y0C: 4 um\n"
                     "  ECC:\n    harmonics: {terms: [{order: 2, amplitude: 8 urad, phase: 30 deg}]}\n"
                     "  EXX:\n    linear: {value: 3 um, over: 800 mm}\n")
    files = [r["file"] for r in mtacc.Machine("tilting-table", errors=truth).simulate("tilting-table-rtest", output=tmp_path)["runs"]]
    plan = tmp_path / "plan.yaml"
    rtest = (pathlib.Path(__file__).parents[2] / "data" / "plans" / "tilting-table-rtest.yaml").read_text()
    plan.write_text(re.sub(r"(?m)^parameters: .*$", "parameters: [X0C, Y0C, ECC.h2, EXX.c1]", rtest))
    bare = tmp_path / "bare.yaml"  # no component error defined: the plan's terms are new
    bare.write_text("errors:\n  X0C: 0 um\n")
    found = mtacc.Machine("tilting-table", errors=bare).identify(files, plan=plan)
    names = [e["parameter"] for e in found["estimates"]][:5]
    assert names == ["X0C", "Y0C", "ECC.h2c", "ECC.h2s", "EXX.c1"]
    value = {e["parameter"]: e["value"] for e in found["estimates"]}
    assert value["X0C"] == pytest.approx(-5, abs=1e-4) and value["Y0C"] == pytest.approx(4, abs=1e-4)
    x_travel = mtacc.Machine("tilting-table").axes[0]["travel"]
    assert value["EXX.c1"] == pytest.approx(3 / 800 * (x_travel[1] - x_travel[0]) / 2, abs=1e-4)  # um at the travel's end
    (harmonic,) = found["harmonics"]
    assert harmonic["term"] == "ECC.h2" and harmonic["unit"] == "urad"
    assert harmonic["amplitude"] == pytest.approx(8, abs=1e-4) and harmonic["phase_deg"] == pytest.approx(30, abs=1e-3)
    out = subprocess.run([CLI, "identify", "tilting-table", "--errors", str(bare), "--plan", str(plan), "--data", *files],
                         capture_output=True, text=True, check=True).stdout
    assert re.search(r"ECC\.h2 +amplitude 8\.0000 ± 0\.0000 urad, phase 30\.00 ± 0\.00 deg", out), out
    with pytest.raises(mtacc.InputError, match=r"unknown error parameter 'EXX.q1'.*X0B.*E<D><axis>\.c<k>.*ECC\.h1"):
        mtacc.Machine("tilting-table").identify(files, ["EXX.q1"])


def test_docs_example_inclined_head_identifies(tmp_path):
    # docs/examples/README.md: the nutating head simulated with its errors file and identified
    # with its R-test plan. X0C, Y0C stand for X0C - X0B, Y0C - Y0B (they act alike); B's own
    # zero offset comes out as B.zero. Noise-free; X0B, Y0B and C.zero (in the truth, not
    # identified) alias only to first order: the second-order rest, about (30 urad)^2 x 250 mm =
    # 2e-4 um, bounds the agreement, checked to 1e-3.
    examples = pathlib.Path(__file__).parents[2] / "docs" / "examples"
    machine, plan = str(examples / "inclined-head.yaml"), str(examples / "inclined-head-rtest.yaml")
    subprocess.run([CLI, "simulate", "plan", machine, "--errors", str(examples / "inclined-head-errors.yaml"), "--plan", plan,
                    "-o", str(tmp_path)], check=True, capture_output=True)
    found = json.loads(subprocess.run([CLI, "identify", machine, "--plan", plan, "--json", "--data", *sorted(map(str, tmp_path.glob("*.csv")))],
                                      check=True, capture_output=True, text=True).stdout)
    value = {e["parameter"]: e["value"] for e in found["estimates"]}
    expected = {"X0C": -6 - 8, "Y0C": 4 - (-5), "A0B": 20, "B.zero": 30, "A0C": 15, "B0C": -12}
    for name, v in expected.items():
        assert value[name] == pytest.approx(v, abs=1e-3), name
