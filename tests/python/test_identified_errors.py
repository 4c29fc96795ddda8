"""Issue 44: an identified model is a file. Truth -> simulated plan -> identify --errors-out ->
the file read by check and compensate without an edit; identifying again from the same data with
the written file as the starting model is a fixed point; component terms included."""
import hashlib
import json
import pathlib
import subprocess

import numpy as np
import pytest

import mtacc

ROOT = pathlib.Path(__file__).resolve().parents[2]
PROGRAM = "G90 G1 F1000\nX0 Y0 Z100 B0 C0\nX10 Y5 Z100 B10 C20\nX20 Y10 Z90 B20 C40\n"

CASES = {
    "inclined-head": dict(
        machine=str(ROOT / "docs/examples/inclined-head.yaml"), plan=str(ROOT / "docs/examples/inclined-head-rtest.yaml"),
        truth=(ROOT / "docs/examples/inclined-head-errors.yaml").read_text() + "  EXC.h2c: 3 um\n  EXC.h2s: -2 um\n  EZC.h2c: 1.5 um\n",
        params="X0C,Y0C,A0B,B.zero,A0C,B0C,EXC.h2,EZC.h2"),
    "double-pivot-head": dict(
        machine="double-pivot-head", plan="double-pivot-rtest",
        truth="errors:\n  X0B: 6 um\n  Z0B: 5 um\n  A0B: 15 urad\n  C0B: -10 urad\n  A0C: 12 urad\n  B0C: -20 urad\n"
              "  EXB.h2c: 2 um\n  EZC.h2s: 1.5 um\n",
        params=None),
}


def run(cli, *args):
    out = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stdout


@pytest.mark.parametrize("case", CASES)
def test_identified_errors_round_trip(cli, tmp_path, case):
    c = CASES[case]
    truth = tmp_path / "truth.yaml"
    truth.write_text(c["truth"])
    run(cli, "simulate", "plan", c["machine"], "--errors", truth, "--plan", c["plan"], "--noise", "0.3um", "-o", tmp_path / "data")
    data = sorted((tmp_path / "data").glob("*.csv"))
    params = ["--params", c["params"]] if c["params"] else []
    identify = ["identify", c["machine"], "--plan", c["plan"], "--data", *data, *params, "--json"]
    written = tmp_path / "identified.yaml"
    first = json.loads(run(cli, *identify, "--errors", truth, "--errors-out", written))
    assert any("." in e["parameter"] and e["parameter"].startswith("E") for e in first["estimates"]), "component terms"

    # Read by check and compensate as it is.
    run(cli, "check", c["machine"], "--errors", written)
    program = tmp_path / "p.nc"
    program.write_text(PROGRAM)
    run(cli, "compensate", c["machine"], "--errors", written, "--program", program, "--gcode", tmp_path / "out.nc")

    # The model in the file is the identified one: every estimate of a machine parameter as its value.
    m = mtacc.Machine(c["machine"], errors=written)
    machine_estimates = [e for e in first["estimates"] if not e["setup"]]
    for e in machine_estimates:
        if e["parameter"].endswith(".zero"):
            continue  # a zero offset lives in its axis's A0k B0k C0k
        scale = 1e3 if e["unit"] == "um" else 1e6
        assert m.errors.get(e["parameter"], 0.0) * scale == pytest.approx(e["value"], rel=1e-12, abs=1e-9), e["parameter"]

    # Identifying again from the same data, starting from the written model: the same values.
    second = json.loads(run(cli, *identify, "--errors", written))
    for a, b in zip(first["estimates"], second["estimates"]):
        assert a["parameter"] == b["parameter"]
        assert abs(a["value"] - b["value"]) <= 1e-6 * a["standard_uncertainty"], a["parameter"]

    # The record: what produced it, the data with their hashes, the fit's numbers.
    text = written.read_text()
    for f in data:
        assert hashlib.sha256(f.read_bytes()).hexdigest() in text
    assert f"chi_square: {first['quality']['chi_square']:.15g}" in text
    assert f"degrees_of_freedom: {first['degrees_of_freedom']}" in text
    assert f"by: \"mtacc {mtacc.__version__} identify\"" in text


def test_python_writes_the_same_file(tmp_path):
    m = mtacc.Machine("tilting-table")
    m.simulate("tilting-table-rtest", noise="0.2 um", output=tmp_path / "data")
    files = sorted((tmp_path / "data").glob("*.csv"))
    out = tmp_path / "id.yaml"
    r = m.identify(files, plan="tilting-table-rtest", errors_out=out)
    back = mtacc.Machine("tilting-table", errors=out)
    for e in r["estimates"]:
        if e["parameter"] in back.errors.names():
            scale = 1e3 if e["unit"] == "um" else 1e6
            assert back.errors.get(e["parameter"], 0.0) * scale == pytest.approx(e["value"], rel=1e-12, abs=1e-9)
    with pytest.raises(mtacc.InputError, match="errors_out"):
        m.identify(files, plan="tilting-table-rtest", errors_out=tmp_path / "missing" / "id.yaml")
    assert not (tmp_path / "missing").exists()


def test_named_terms_in_python_mean_what_identify_means():
    m = mtacc.Machine("three-axis-vertical", errors={})
    low, high = next(a for a in m.axes if a["name"] == "X")["travel"]
    # A term the errors do not define: the power over half the travel about its middle, so EZX.c1
    # is the error at the end of travel. X carries the workpiece: the TCP moves the other way.
    m.errors["EZX.c1"] = "3 um"
    dz = m.tcp_errors([[high, 0, 0], [0.5 * (low + high), 0, 0], [low, 0, 0]])[:, 2]
    assert dz == pytest.approx([-3.0, 0.0, 3.0], abs=1e-9)
    with pytest.raises(mtacc.InputError, match="two parts"):
        m.errors["EZX.h1"] = "1 um"


def test_check_warns_of_a_head_without_its_spindle(cli, tmp_path):
    text = (ROOT / "data/machines/swivel-head-table.yaml").read_text()
    assert "t-(C)-B-Z-Y-b-X-C-w" in text
    without = tmp_path / "no-spindle.yaml"
    without.write_text(text.replace("t-(C)-B-Z-Y-b-X-C-w", "t-B-Z-Y-b-X-C-w"))
    warned = json.loads(run(cli, "check", without, "--json"))
    assert len(warned["warnings"]) == 1 and "pivot length Z0C1" in warned["warnings"][0]
    assert "Z0C1" not in warned["parameters"]
    ok = json.loads(run(cli, "check", "swivel-head-table", "--json"))
    assert ok["warnings"] == [] and "Z0C1" in ok["parameters"]
    # Seed 003's Maho: a C head turning a horizontal spindle (along Y), modelled without it.
    assert "pivot length Y0C1" in json.loads(run(cli, "check", "maho", "--json"))["warnings"][0]
    # A rotary axis along the tool has no pivot length to miss.
    along = tmp_path / "c-along-the-tool.yaml"
    along.write_text("name: C head along the tool\nstructure: t-C-Z-Y-b-X-w\naxes:\n"
                     "  X: {direction: [1, 0, 0], travel: [-500 mm, 500 mm]}\n"
                     "  Y: {direction: [0, 1, 0], travel: [-350 mm, 350 mm]}\n"
                     "  Z: {direction: [0, 0, 1], travel: [-200 mm, 600 mm]}\n"
                     "  C: {direction: [0, 0, 1], location: [0 mm, 0 mm, 0 mm], travel: continuous}\n")
    assert json.loads(run(cli, "check", along, "--json"))["warnings"] == []


def test_degrees_of_freedom_and_sigma_on_a_small_problem(tmp_path):
    # Issue 52: with readings ~ 2 x unknowns the degrees of freedom (readings less unknowns) and
    # sigma (the residuals' sum of squares over them) show. 6 poses x 3 directions = 18 readings;
    # 4 parameters and the sphere's 3 set-up unknowns.
    import numpy as np
    (tmp_path / "small.yaml").write_text(
        "name: one sphere, six C positions\nparameters: [X0C, Y0C, A0C, B0C]\nruns:\n"
        "  - name: c\n    sphere: {axis: C, from: 0 deg, to: 300 deg, points: 6, spheres: [[120 mm, 0 mm, 60 mm]]}\n"
        "    estimate: [xW, yW, zW]\n")
    m = mtacc.Machine("tilting-table")
    m.simulate(tmp_path / "small.yaml", noise="0.5 um", seed=3, output=tmp_path / "runs")
    r = m.identify(sorted((tmp_path / "runs").glob("*.csv")), plan=tmp_path / "small.yaml")
    assert r["readings"] == 18 and len(r["estimates"]) == 7
    assert r["degrees_of_freedom"] == 11
    squares = sum(float(np.sum(np.square(run["residuals_um"]))) for run in r["run_residuals"])
    assert r["sigma_um"] == pytest.approx(np.sqrt(squares / 11), rel=1e-9)
    assert r["quality"]["chi_square"] == pytest.approx(squares / 0.5 ** 2, rel=1e-9)
