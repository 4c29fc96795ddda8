"""Issue 45, part 1: a program evaluated on any error model (`mtacc deviation`, Python
Machine.deviation) and a compensation checked against a model other than the one that made it
(`compensate --check-errors`)."""
import json
import re
import subprocess

import numpy as np
import pytest

import mtacc

ERRORS = """errors:
  X0C: 6 um
  Y0C: -4 um
  A0C: 25 urad
  B0C: -15 urad
  Z0B: 8 um
  C0B: 20 urad
  EXX: {linear: {over: 200 mm, value: 4 um}}
  EYB: {linear: {over: 90 deg, value: 3 um}}
"""


def run(cli, *args):
    return json.loads(subprocess.run([cli, *args, "--json"], check=True, capture_output=True, text=True).stdout)




def axis_program(path):
    """Each G1 line's axis positions (mm, deg) from a program that writes every axis on every line."""
    rows = []
    for line in path.read_text().splitlines():
        words = dict(re.findall(r"([XYZBC])(-?[\d.]+)", line))
        if re.search(r"\bG0?1\b", line) and len(words) == 5:
            rows.append([float(words[a]) for a in "XYZBC"])
    return np.array(rows)


def test_a_program_on_a_model_is_what_the_python_model_gives_block_by_block(cli, tmp_path):
    # The cone program on the tilting table with errors, against its own nominal path: each
    # block's largest TCP deviation is the largest of the Python module's TCP errors at the same
    # places (a step of 100 mm takes 4 samples a block, at 1/8, 3/8, 5/8, 7/8 of it), with the
    # axes' directions of motion for the reversal errors.
    (tmp_path / "errors.yaml").write_text(ERRORS)
    subprocess.run([cli, "cone", "tilting-table", "--gcode", str(tmp_path / "cone.nc")], check=True, capture_output=True)
    result = run(cli, "deviation", "tilting-table", "--program", str(tmp_path / "cone.nc"), "--errors", str(tmp_path / "errors.yaml"),
                 "--step", "100")
    machine = mtacc.Machine("tilting-table", errors=tmp_path / "errors.yaml")
    assert machine.deviation(tmp_path / "cone.nc", step=100) == result
    q = axis_program(tmp_path / "cone.nc")
    blocks = {b["line"]: b for b in result["blocks"]}
    lines = [i + 1 for i, line in enumerate((tmp_path / "cone.nc").read_text().splitlines()) if re.search(r"\bG0?1\b", line)]
    held = np.sign(q[1] - q[0]).astype(int)
    names = list(machine.axis_names)
    order = [names.index(a) for a in "XYZBC"]
    compared = 0
    for k in range(1, len(q)):
        step = q[k] - q[k - 1]
        held = np.where(np.abs(step) > 0, np.sign(step), held).astype(int)
        s = np.array([0.125, 0.375, 0.625, 0.875])[:, None]
        poses = np.zeros((4, len(names)))
        poses[:, order] = q[k - 1] + s * step
        directions = np.zeros((4, len(names)), dtype=int)
        directions[:, order] = held
        error = np.linalg.norm(machine.tcp_errors(poses, directions=directions)[:, :3], axis=1)
        assert blocks[lines[k]]["max_position_um"] == pytest.approx(error.max(), rel=1e-9, abs=1e-9)
        compared += 1
    assert compared == len(q) - 1 and result["samples"] == 4 * len(result["blocks"])
    assert result["max_position_um"] > 5


def test_a_compensation_is_checked_on_the_machine_it_runs_on(cli, tmp_path):
    # The program compensated with a model that misses the truth's EXX and Z0B, checked on the
    # truth two ways: compensate --check-errors (the written points at their place on each move)
    # and deviation --intended (the compensated program's path against the program's, at the
    # closest point). Both see what the model missed; on the model itself almost nothing is left.
    (tmp_path / "truth.yaml").write_text(ERRORS)
    (tmp_path / "model.yaml").write_text("\n".join(line for line in ERRORS.splitlines() if "EXX" not in line and "Z0B" not in line) + "\n")
    subprocess.run([cli, "cone", "tilting-table", "--gcode", str(tmp_path / "cone.nc")], check=True, capture_output=True)
    compensated = run(cli, "compensate", "tilting-table", "--errors", str(tmp_path / "model.yaml"), "--program", str(tmp_path / "cone.nc"),
                      "--gcode", str(tmp_path / "compensated.nc"), "--check-errors", str(tmp_path / "truth.yaml"))
    check = compensated["check"]
    assert check["errors"] == str(tmp_path / "truth.yaml")
    assert compensated["deviation_after"]["max_position_um"] < 0.01
    assert check["deviation_after"]["max_position_um"] > 2  # the missed EXX and Z0B
    on_truth = run(cli, "deviation", "tilting-table", "--errors", str(tmp_path / "truth.yaml"), "--program", str(tmp_path / "compensated.nc"),
                   "--intended", str(tmp_path / "cone.nc"))
    on_model = run(cli, "deviation", "tilting-table", "--errors", str(tmp_path / "model.yaml"), "--program", str(tmp_path / "compensated.nc"),
                   "--intended", str(tmp_path / "cone.nc"))
    # The closest point is never farther than the same place on the move; the written program's
    # 10 nm and 1e-5 deg rounding adds a few hundredths of a micrometre.
    assert on_truth["max_position_um"] <= check["deviation_after"]["max_position_um"] + 0.05
    assert on_truth["max_position_um"] > 0.5 * check["deviation_after"]["max_position_um"]
    assert on_model["max_position_um"] < 0.05
    assert on_model["instant_blocks"] == on_truth["instant_blocks"]
    # The missed errors' own effect: the uncompensated program on a machine with only them.
    (tmp_path / "missed.yaml").write_text("errors:\n  Z0B: 8 um\n  EXX: {linear: {over: 200 mm, value: 4 um}}\n")
    missed = run(cli, "deviation", "tilting-table", "--errors", str(tmp_path / "missed.yaml"), "--program", str(tmp_path / "cone.nc"))
    assert on_truth["max_position_um"] == pytest.approx(missed["max_position_um"], rel=0.1)


def test_a_machine_without_reversal_errors_gets_no_steps(cli, tmp_path):
    # Issue 45, part 5: a step is written where an axis reverses only when the reversal errors
    # move the commands; without them the compensated program has one line per block, each with
    # its N number and its own end point, and no block of no length.
    (tmp_path / "location.yaml").write_text("errors:\n  X0C: 6 um\n  Y0C: -4 um\n  A0C: 25 urad\n")
    (tmp_path / "reversal.yaml").write_text("errors:\n  X0C: 6 um\n  EXX: {reversal: 3 um}\n")
    subprocess.run([cli, "cone", "tilting-table", "--gcode", str(tmp_path / "cone.nc")], check=True, capture_output=True)
    motion = lambda path: [line for line in path.read_text().splitlines() if re.search(r"\bG0?1\b", line)]
    for errors, steps in (("location", False), ("reversal", True)):
        out = tmp_path / f"{errors}.nc"
        subprocess.run([cli, "compensate", "tilting-table", "--errors", str(tmp_path / f"{errors}.yaml"), "--program", str(tmp_path / "cone.nc"),
                        "--gcode", str(out)], check=True, capture_output=True)
        written = motion(out)
        axes = [re.sub(r"^N\d+ |F\d+", "", line).strip() for line in written]
        assert all(a != b for a, b in zip(axes, axes[1:]))  # no block of no length
        numbers = [line.split()[0] for line in written if line.startswith("N")]
        assert numbers == [line.split()[0] for line in motion(tmp_path / "cone.nc")]
        assert (len(written) > len(numbers)) == steps


SWIVEL_PLAN = """name: Swivel head and table, R-test while C turns (B = 0 and 45 deg) and while B swings (C = 0 and 90 deg)
parameters: [X0B, A0B, C0B, A0C, B0C, C0Y, EZC.h2]
runs:
  - name: rtest-C-B0
    sphere: {axis: C, from: -180 deg, to: 150 deg, points: 12, spheres: [[150 mm, 0 mm, 0 mm]]}
    estimate: [xW, yW, zW]
  - name: rtest-C-B45
    sphere: {axis: C, from: -180 deg, to: 150 deg, points: 12, spheres: [[150 mm, 0 mm, 0 mm]], pose: {B: 45 deg}}
    estimate: [xW, yW, zW]
  - name: rtest-B
    sphere: {axis: B, from: -90 deg, to: 90 deg, points: 13, spheres: [[0 mm, 0 mm, 100 mm]]}
    estimate: [xW, yW, zW]
  - name: rtest-B-C90
    sphere: {axis: B, from: -90 deg, to: 90 deg, points: 13, spheres: [[0 mm, 0 mm, 100 mm]], pose: {C: 90 deg}}
    estimate: [xW, yW, zW]
"""


@pytest.mark.parametrize("name", ["swivel-head-table", "double-pivot-head"])
def test_a_compensation_from_an_identified_model_holds_on_the_truth(cli, tmp_path, name):
    # Issue 45's acceptance: a truth with location and component errors, the plan simulated with
    # noise, the model identified and written, the cone program compensated with it and run on the
    # truth. What is left is within 3 x the model's k = 2 uncertainty along the program plus the
    # effect of the truth's error that the plan does not identify (EXX), which the check names.
    if name == "swivel-head-table":
        (tmp_path / "plan.yaml").write_text(SWIVEL_PLAN)
        plan = str(tmp_path / "plan.yaml")
    else:
        plan = "double-pivot-rtest"
    machine = mtacc.Machine(name, errors={})
    estimates = machine.observability(plan, noise="0.3 um")["prediction"]["estimates"]
    parameters = [e["parameter"] for e in estimates if not e["setup"]]
    rng = np.random.default_rng(11)
    lines = [f"  {p}: {rng.uniform(-12, 12):.3f} {'um' if p[0] in 'XYZ' or p[:2] in ('EX', 'EY', 'EZ') else 'urad'}" for p in parameters]
    unmodelled = "  EXX: {linear: {over: 400 mm, value: 3 um}}"
    (tmp_path / "truth.yaml").write_text("errors:\n" + "\n".join(lines + [unmodelled]) + "\n")
    (tmp_path / "unmodelled.yaml").write_text("errors:\n" + unmodelled + "\n")
    truth = mtacc.Machine(name, errors=tmp_path / "truth.yaml")
    truth.simulate(plan, noise="0.3 um", seed=4, output=tmp_path / "runs")
    identified = tmp_path / "identified.yaml"
    truth.identify(sorted((tmp_path / "runs").glob("*.csv")), plan=plan, errors_out=identified, from_nominal=True)
    subprocess.run([cli, "cone", name, "--gcode", str(tmp_path / "cone.nc")], check=True, capture_output=True)
    compensated = run(cli, "compensate", name, "--errors", str(identified), "--program", str(tmp_path / "cone.nc"), "--gcode",
                      str(tmp_path / "compensated.nc"), "--check-errors", str(tmp_path / "truth.yaml"))
    check = compensated["check"]
    assert check["not_in_model"] == ["EXX.c1"]  # the linear term of EXX, named as the model would name it
    left = check["deviation_after"]["max_position_um"]
    known = run(cli, "deviation", name, "--errors", str(identified), "--program", str(tmp_path / "compensated.nc"))
    k2 = np.linalg.norm(known["uncertainty_k2_max_um"])
    missed = run(cli, "deviation", name, "--errors", str(tmp_path / "unmodelled.yaml"), "--program", str(tmp_path / "cone.nc"))
    assert left <= 3 * k2 + missed["max_position_um"], (left, k2, missed["max_position_um"])
    # Measured: 0.87 um left of 15.9 (k = 2 0.72 um, EXX 0.52 um) on the swivel head, 1.20 of 26.9 (0.98, 0.70) on the
    # double pivot head.
    assert left < 0.1 * check["deviation_before"]["max_position_um"]


def test_what_a_controller_table_cannot_carry_is_named_where_its_residual_is_shown(cli, tmp_path):
    # Issue 45: the TwinCAT/ISG model's chain ends at the last commanded axis: the spindle's offsets
    # (the pivot length Z0C1) go to the tool's kinematic offsets, its tilt (B0C1) is left, said in
    # the CLI table, the JSON and the report, not only inside isg-volcomp.csv. The tilt turns the
    # tool about its tip here (the spindle's line passes through it): it leaves the direction, which
    # ISG does not correct, and no position error.
    from mtacc import report
    (tmp_path / "head.yaml").write_text("errors:\n  X0B: 8 um\n  Z0C1: 15 um\n  A0B: 20 urad\n  B0C1: 30 urad\n")
    out = subprocess.run([cli, "compensate", "swivel-head-table", "--errors", str(tmp_path / "head.yaml"), "--tables", str(tmp_path / "t")],
                         check=True, capture_output=True, text=True).stdout
    assert "not carried: the errors of the spindle C1 (B0C1)" in out
    assert "add (0.0000000, 0.0000000, 0.0150000) mm to the tool's kinematic offsets" in (tmp_path / "t" / "isg-volcomp.csv").read_text()
    tables = mtacc.Machine("swivel-head-table", errors=tmp_path / "head.yaml").compensation_tables(nodes=(5, 5, 5))
    isg = next(t for t in tables["tables"] if t["format"] == "isg-volumetric")
    assert [left.split(" (")[0] for left in isg["not_carried"]] == ["the tool direction", "the errors of the spindle C1"]
    assert isg["tool_offset_mm"] == pytest.approx([0.0, 0.0, 0.015], abs=1e-12)
    assert isg["residual"]["after_max_um"] < 0.01 < 10.0 < isg["residual"]["before_max_um"]
    section = report.compensation_section(tables)
    assert "the errors of the spindle C1 (B0C1)" in section
    # LinuxCNC's maxkins carries the pivot length and the head's offset; the B line's tilt it names.
    # The kinematics' figures are of the tool tip's position: the spindle's tilt about it is none.
    kins = tables["linuxcnc_kins"]
    assert kins["kins"] == "maxkins" and [left.split(" (")[0] for left in kins["not_carried"]] == ["A0B"]
    assert "LinuxCNC maxkins pins" in section and "A0B (leaves" in section
    # SINUMERIK's toolholder data set holds the B line's direction too.
    carr = tables["siemens_toolholder"]
    assert carr["type"] == "M" and carr["axes"] == ["B", "C"] and carr["not_carried"] == []
    assert carr["residual"]["after_max_um"] < 0.01 < carr["residual"]["before_max_um"]
    assert "SINUMERIK $TC_CARR type M" in section
    assert "SINUMERIK toolholder $TC_CARR, type M (and the 5-axis transformation's MD) in siemens-toolholder.spf, siemens-trafo5.ini" in out
