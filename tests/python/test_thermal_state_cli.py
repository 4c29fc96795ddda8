"""`--thermal FILE`: a machine command evaluated at a thermal state (the temperatures along a
scale, the spindle's), here the forward kinematics and the compensation tables written cold and warm."""
import json
import pathlib
import subprocess

import numpy as np
import pytest

THERMAL = pathlib.Path(__file__).resolve().parents[2] / "data" / "thermal"
STATE = """scales:
  X: {sensors: [0 mm, 337 mm, 600 mm], temperatures: [21.5, 26.0, 22.0], reference: 100 mm}
"""


def expansion(x):
    """alpha * integral from the reference (100 mm) to x of T(u) - 20 degC, T linear between the sensors, mm."""
    u = np.linspace(100.0, x, 200001)
    excess = np.interp(u, [0.0, 337.0, 600.0], [21.5, 26.0, 22.0]) - 20.0
    return 11.5e-6 * np.trapz(excess, u)


def run(cli, *args):
    return json.loads(subprocess.run([cli, *args, "--json"], check=True, capture_output=True, text=True).stdout)


def test_the_warm_machine_puts_the_tool_the_expansion_further(cli, tmp_path):
    state = tmp_path / "state.yaml"
    state.write_text(STATE)
    for x in (0.0, 250.0, 600.0):
        pose = f"X={x},Y=100,Z=50"
        cold = run(cli, "fk", "three-axis-vertical", "--pose", pose)["poses"][0]["tcp_mm"]
        warm = run(cli, "fk", "three-axis-vertical", "--pose", pose, "--thermal", str(state))["poses"][0]["tcp_mm"]
        # The table's own errors turn the expansion's direction by micro-radians: a second-order change.
        assert np.subtract(warm, cold) == pytest.approx([expansion(x), 0, 0], abs=1e-6)


def test_tables_written_at_two_states_differ_by_the_expansion(cli, tmp_path):
    state = tmp_path / "state.yaml"
    state.write_text(STATE)
    cold = run(cli, "compensate", "three-axis-vertical", "--tables", str(tmp_path / "cold"), "--nodes", "11,5,5")
    warm = run(cli, "compensate", "three-axis-vertical", "--tables", str(tmp_path / "warm"), "--nodes", "11,5,5", "--thermal", str(state))
    grid = {name: np.genfromtxt(tmp_path / name / "grid.csv", delimiter=",", skip_header=4, names=True) for name in ("cold", "warm")}
    for row_cold, row_warm in zip(grid["cold"], grid["warm"]):
        assert row_warm["dx_mm"] - row_cold["dx_mm"] == pytest.approx(-expansion(row_cold["x_mm"]), abs=2e-6)
        assert row_warm["dy_mm"] - row_cold["dy_mm"] == pytest.approx(0, abs=2e-6)
    residual = {name: r["tables"][0]["residual"] for name, r in (("cold", cold), ("warm", warm))}
    # Written warm, the grid leaves what it leaves cold (both reported), though the warm machine's
    # error before correction is another (the expansion partly offsets X's own positioning error).
    assert residual["warm"]["after_max_um"] < residual["cold"]["after_max_um"] + 0.1
    assert abs(residual["warm"]["before_max_um"] - residual["cold"]["before_max_um"]) > 5


def test_the_python_machine_takes_the_same_state(tmp_path):
    import mtacc
    state = tmp_path / "state.yaml"
    state.write_text(STATE)
    cold, warm = mtacc.Machine("three-axis-vertical"), mtacc.Machine("three-axis-vertical", thermal=state)
    moved = warm.fk([600, 0, 0])[0][0] - cold.fk([600, 0, 0])[0][0]
    assert moved == pytest.approx([expansion(600.0), 0, 0], abs=1e-6)


def test_every_period_the_tables_follow_the_state_the_logger_wrote_last(cli, tmp_path):
    """--every: the state is read again each period and the tables rewritten for it; a stop
    signal ends the loop cleanly with no file left half written."""
    import os
    import signal
    state = tmp_path / "state.yaml"
    state.write_text("scales:\n  X: {sensors: [0 mm, 600 mm], temperatures: [20, 20], reference: 100 mm}\n")
    live = tmp_path / "live"
    job = subprocess.Popen([cli, "compensate", "three-axis-vertical", "--tables", str(live), "--nodes", "11,5,5", "--thermal", str(state),
                            "--every", "2", "--updates", "3"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    first = job.stderr.readline()
    assert first.startswith("mtacc: update 1 at ") and str(live) in first
    warm = tmp_path / "warm.yaml"
    warm.write_text(STATE)
    os.replace(warm, state)  # as a logger writes it: whole
    rest = job.stderr.read()
    assert job.wait(timeout=60) == 0
    lines = rest.splitlines()
    assert [line.split(" at ")[0] for line in lines] == ["mtacc: update 2", "mtacc: update 3"]
    moved = [float(line.split("up to ")[1].split(" um")[0]) for line in lines]
    assert moved[0] == pytest.approx(1e3 * abs(expansion(600.0)), rel=0.01) and moved[1] == 0  # the largest change is at X = 600 mm
    subprocess.run([cli, "compensate", "three-axis-vertical", "--tables", str(tmp_path / "once"), "--nodes", "11,5,5", "--thermal", str(state)],
                   check=True, capture_output=True)
    assert sorted(os.listdir(live)) == sorted(os.listdir(tmp_path / "once"))
    for name in os.listdir(live):
        assert (live / name).read_bytes() == (tmp_path / "once" / name).read_bytes(), name

    stopped = subprocess.Popen([cli, "compensate", "three-axis-vertical", "--tables", str(tmp_path / "stopped"), "--nodes", "11,5,5",
                                "--thermal", str(state), "--every", "60"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    assert stopped.stderr.readline().startswith("mtacc: update 1 at ")
    stopped.send_signal(signal.SIGTERM)
    assert stopped.wait(timeout=10) == 0
    assert sorted(os.listdir(tmp_path / "stopped")) == sorted(os.listdir(live))


def test_the_state_summary_and_its_report_section(cli, tmp_path):
    import mtacc
    from mtacc import report
    state = tmp_path / "state.yaml"
    state.write_text(STATE)
    summary = mtacc.thermal_state("three-axis-vertical", state, points=7)
    x = summary["scales"][0]
    assert x["axis"] == "X" and x["sensors_mm"] == [0, 337, 600] and x["temperatures_C"] == [21.5, 26.0, 22.0]
    assert x["position_mm"] == pytest.approx(np.linspace(0, 600, 7), abs=1e-12)
    assert x["expansion_um"] == pytest.approx([1e3 * expansion(p) for p in x["position_mm"]], abs=1e-6)
    assert x["largest_um"] == pytest.approx(1e3 * expansion(600.0), abs=1e-6)
    section = report.thermal_section(summary)
    assert section.count("<svg") == 1 and "Thermal state: state.yaml" in section and f"{x['largest_um']:.2f}" in section
    with pytest.raises(mtacc.InputError, match="points: give 2 to 10001"):
        mtacc.thermal_state("three-axis-vertical", state, points=1)
    out = tmp_path / "report"
    subprocess.run([cli, "report", "three-axis-vertical", "--thermal", str(state), "-o", str(out)], check=True, capture_output=True)
    page = (out / "three-axis-vertical-report.html").read_text()
    assert "at the thermal state state.yaml" in page and "Thermal state: state.yaml" in page


def test_the_spindle_drift_model_of_a_drift_test_moves_the_warm_spindle(cli, tmp_path):
    """`mtacc drift --save-model` (and drift_test(save_model=)) write the spindle's drift model; a
    state naming it with the spindle's temperatures moves the TCP by the drift it predicts there."""
    import mtacc
    from mtacc import report
    test = THERMAL / "maho-spindle-drift.csv"
    subprocess.run([cli, "drift", str(test), "--save-model", str(tmp_path / "model.yaml")], check=True, capture_output=True)
    mtacc.drift_test(test, save_model=tmp_path / "python-model.yaml")
    assert (tmp_path / "model.yaml").read_text() == (tmp_path / "python-model.yaml").read_text()
    state = tmp_path / "state.yaml"
    state.write_text("spindle:\n  model: model.yaml\n  temperatures: {head: 31.5, column: 24.0, bed: 21.0}\n  probe_above_tcp: 100 mm\n")
    summary = mtacc.thermal_state("three-axis-vertical", state)
    assert summary["scales"] == [] and [d["direction"] for d in summary["spindle"]["directions"]] == ["X", "Y", "Z", "A", "B"]
    y = summary["spindle"]["directions"][1]
    assert 20 < y["drift"] < 35 and 0.2 < y["sigma"] < 0.5, "tens of um of Y drift for an 11.5 K warmer head, to 0.3 um"
    for pose in ("X=0,Y=0,Z=0", "X=300,Y=200,Z=250"):
        cold = run(cli, "fk", "three-axis-vertical", "--pose", pose)["poses"][0]["tcp_mm"]
        warm = run(cli, "fk", "three-axis-vertical", "--pose", pose, "--thermal", str(state))["poses"][0]["tcp_mm"]
        # The machine's angular errors (up to 15 urad) turn the drift (under 30 um): below 0.5 nm.
        assert np.subtract(warm, cold) * 1e3 == pytest.approx(summary["spindle"]["at_tcp_um"], abs=5e-4)
    section = report.thermal_section(summary)
    assert "<svg" not in section and "The spindle's drift" in section and f"{y['drift']:.2f} um" in section
    with pytest.raises(mtacc.InputError, match="save-model"):
        mtacc.drift_test(THERMAL / "z-axis-drift.csv", save_model=tmp_path / "axis-model.yaml")
    assert not (tmp_path / "axis-model.yaml").exists()
