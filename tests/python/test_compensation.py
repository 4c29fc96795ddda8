"""`mtacc compensate` and `Machine.compensate_program`: CLI and API alike, the compensated program
leaving a small share of the program's deviation on the machine with its errors, G43 tool lengths,
and bad G-code located."""
import json
import subprocess

import pytest

import mtacc

CIRCLE = "G21 G90 G17\nG0 X400 Y200 Z250\nG2 X400 Y200 I-100 F1000\nM30\n"


def test_cli_json_equals_api_and_the_written_program(cli, tmp_path):
    program, out = tmp_path / "circle.nc", tmp_path / "compensated.nc"
    program.write_text(CIRCLE)
    run = subprocess.run([cli, "compensate", "three-axis-vertical", "--program", str(program), "--gcode", str(out), "--json"],
                         capture_output=True, text=True, check=True)
    api = mtacc.Machine("three-axis-vertical").compensate_program(program)
    assert out.read_text() == api.pop("gcode")
    assert json.loads(run.stdout) == api


def test_the_compensated_circle_deviates_far_less(tmp_path):
    program = tmp_path / "circle.nc"
    program.write_text(CIRCLE)
    r = mtacc.Machine("three-axis-vertical").compensate_program(program)
    before, after = r["deviation_before"]["max_position_um"], r["deviation_after"]["max_position_um"]
    assert before > 5 and after <= 0.05 * before
    assert r["not_converged"] == 0 and r["written_points"] > 1000  # the circle as chords within 0.1 um


def test_tool_lengths_and_tolerances(tmp_path):
    program = tmp_path / "tool.nc"
    program.write_text("G43 H2\nG0 X0 Y10 Z100\nG1 X500 F500\n")
    machine = mtacc.Machine("three-axis-vertical")
    with pytest.raises(mtacc.InputError, match=r"tool.nc:1: .*length of tool 2"):
        machine.compensate_program(program)
    short, long = (machine.compensate_program(program, tool_length={2: length}) for length in (0.0, 100.0))
    # The pitch of X (EBX, 12.5 urad at X = 500) over a 100 mm longer tool: 1.25 um more correction of X.
    assert abs(long["largest_correction_um_urad"]["X"] - short["largest_correction_um_urad"]["X"]) == pytest.approx(1.25, abs=1e-3)
    with pytest.raises(mtacc.InputError, match="tolerance"):
        machine.compensate_program(program, tool_length={2: 0.0}, tolerance=float("nan"))


def test_bad_gcode_is_located(tmp_path):
    program = tmp_path / "bad.nc"
    program.write_text("G0 X0 Y0 Z50\nG2 X10 Y0 I4 F100\n")
    with pytest.raises(mtacc.InputError, match=r"bad.nc:2: .*inconsistent arc"):
        mtacc.Machine("three-axis-vertical").compensate_program(program)



def test_tables_cli_equals_api_and_the_files_are_written(cli, tmp_path):
    run = subprocess.run([cli, "compensate", "maho", "--tables", str(tmp_path), "--nodes", "6,5,5", "--pose", "B=10", "--functions", "4",
                          "--json"], capture_output=True, text=True, check=True)
    api = mtacc.Machine("maho").compensation_tables(nodes=(6, 5, 5), pose={"B": 10}, functions=4)
    contents = api.pop("contents")
    assert json.loads(run.stdout) == api
    assert sorted(contents) == sorted(api["files"]) == ["etalon-exchange.txt", "grid.csv", "heidenhain-X.com", "heidenhain-Y.com", "heidenhain-Z.com",
                                                     "heidenhain.cma", "isg-volcomp.csv", "isg-volcomp.lis", "linuxcnc-B.comp", "linuxcnc-C.comp",
                                                     "linuxcnc-X.comp", "linuxcnc-Y.comp", "linuxcnc-Z.comp", "one-axis.csv", "siemens-cec.ini",
                                                     "siemens-lec.ini"]
    for name, text in contents.items():
        assert (tmp_path / name).read_text() == text
    tables = {t["format"]: t for t in api["tables"]}
    assert len(tables["one-axis"]["functions"]) == 4
    # The grid carries the most; each reduction leaves more, and every table leaves less than nothing would.
    before = tables["grid"]["residual"]["before_max_um"]
    assert tables["grid"]["residual"]["after_max_um"] < tables["one-axis"]["residual"]["after_max_um"] < before
    assert tables["linuxcnc"]["residual"]["after_max_um"] < before
    # The controller holding the model leaves only the interpolation between its records.
    assert tables["isg-volumetric"]["residual"]["after_max_um"] < tables["grid"]["residual"]["after_max_um"]
    assert tables["isg-volumetric"]["chain"] == "BXYZC" and api["isg_volumetric"] == {"applicable": True}
    assert api["linuxcnc_kins"]["applicable"] is False
    assert "LinuxCNC's 5-axis kinematics need a table tilting about B that carries the C table" in api["linuxcnc_kins"]["reason"]


# X's scale error is in no module. On the trunnion the tool's offsets are the work offset's; on the
# heads the spindle's offset across its axis turns with the head.
@pytest.mark.parametrize("machine, kins, named", [("tilting-table", "xyzbc-trt-kins", ["EXX.c1"]),
                                                  ("double-pivot-head", "5axiskins", ["X0C1", "EXX.c1"]),
                                                  ("swivel-head-table", "maxkins", ["X0C1", "EXX.c1"])])
def test_linuxcnc_kinematics_parameters(cli, tmp_path, machine, kins, named):
    errors = tmp_path / "errors.yaml"
    errors.write_text("errors: {Z0C1: 6 um, X0C1: 4 um, EXX: {linear: {value: 3 um, over: 800 mm}, reversal: 2 um}}\n")
    run = subprocess.run([cli, "compensate", machine, "--errors", str(errors), "--tables", str(tmp_path / "out"), "--nodes", "3,3,3"],
                         capture_output=True, text=True, check=True)
    assert f"LinuxCNC {kins} parameters in linuxcnc-kins.hal" in run.stdout
    r = mtacc.Machine(machine, errors=str(errors)).compensation_tables(nodes=(3, 3, 3))["linuxcnc_kins"]
    assert r["applicable"] and r["kins"] == kins and r["file"] == "linuxcnc-kins.hal"
    setp = [line.split() for line in (tmp_path / "out" / "linuxcnc-kins.hal").read_text().splitlines() if not line.startswith("#")]
    assert {pin.removeprefix(kins + "."): float(value) for _, pin, value in setp} == pytest.approx(r["pins_mm"], abs=1e-7)
    # What the pins cannot carry and the reversal are named, in the CLI's table as in the JSON.
    assert [left.split(" (")[0] for left in r["not_carried"][:-1]] == named
    assert r["not_carried"][-1] == "the reversal terms of EXX (the kinematics have no direction of motion)"
    for left in r["not_carried"]:
        assert f"not carried: {left}" in run.stdout
    assert r["residual"]["after_rms_um"] < r["residual"]["before_rms_um"]


def test_tables_along_a_test_path(tmp_path):
    program = tmp_path / "circle.nc"
    program.write_text(CIRCLE)
    r = mtacc.Machine("three-axis-vertical").compensation_tables(nodes=(24, 22, 22), check_program=program)
    assert r["check_program"] == str(program)
    along = {t["format"]: t["along_program"] for t in r["tables"]}
    assert along["grid"]["after_max_um"] <= 0.05 * along["grid"]["before_max_um"]
    # SINUMERIK's CEC and HEIDENHAIN's tables hold the same functions and trims, as SINUMERIK's LEC
    # (with its reversal tables) and LinuxCNC's files do; standing, the trims do nothing.
    assert along["siemens-cec"] == along["heidenhain"] and along["siemens-lec"] == along["linuxcnc"]
    standing = ("after_max_um", "after_rms_um", "before_max_um")
    assert [along["heidenhain"][k] for k in standing] == [along["one-axis"][k] for k in standing]
    # Moving as the circles move (issue 46) the reversals act: the grid and the one-axis functions
    # leave them, the trims take them out.
    for standing_only in ("grid", "one-axis"):
        assert along[standing_only]["moving_as_programmed_max_um"] > along[standing_only]["after_max_um"] + 0.5
    for carrying in ("siemens-cec", "siemens-lec", "linuxcnc", "heidenhain", "isg-volumetric"):
        assert along[carrying]["moving_as_programmed_max_um"] < along[carrying]["after_max_um"] + 0.01, carrying


def test_tables_refuse_a_bad_request():
    with pytest.raises(mtacc.InputError, match="nodes"):
        mtacc.Machine("maho").compensation_tables(nodes=(1, 5, 5))
    with pytest.raises(mtacc.InputError, match="at most 256"):
        mtacc.Machine("three-axis-vertical").compensation_tables(nodes=(300, 2, 2))


def test_five_axis_outputs_along_a_test_path(tmp_path):
    # Issue 45, item 3: every output's residual along the user's 5-axis path, in the JSON and the
    # report's table; the rotary axes' own positioning in the LEC and LinuxCNC files.
    from mtacc import report
    program = tmp_path / "path.nc"
    program.write_text("G1 X100 Y50 Z100 B0 C0 F1000\nG1 X-50 Y20 Z80 B40 C90\nG1 X20 Y-60 Z120 B-60 C-135\n")
    r = mtacc.Machine("tilting-table").compensation_tables(nodes=(5, 5, 5), check_program=program)
    assert all("along_program" in t for t in r["tables"])
    assert "along_program" in r["linuxcnc_kins"] and "along_program" in r["siemens_toolholder"]
    along = {t["format"]: t["along_program"]["after_max_um"] for t in r["tables"]}
    # The tables hold one pose of B and C; the toolholder data set turns with them.
    assert r["siemens_toolholder"]["along_program"]["after_max_um"] < along["grid"] < along["grid"] + 1
    assert [(x["axis"], x["modulo"]) for x in r["rotary_positioning"]] == [("B", False), ("C", True)]
    assert r["rotary_positioning"][0]["largest_reversal_urad"] > 0
    assert "linuxcnc-B.comp" in r["files"] and "linuxcnc-C.comp" in r["files"]
    section = report.compensation_section(r)
    assert f"along {program}, largest [µm]" in section and "The rotary axes' own positioning in the LEC and LinuxCNC files: B:" in section


def test_each_table_moving_each_way_leaves_the_reversal_it_cannot_carry(cli, tmp_path):
    # Issue 46: a machine whose only errors are each axis's positioning error with a reversal. The
    # tables taken standing carry the positioning and leave the reversal moving (half of each width,
    # on all three axes: |(1, 1.5, 2)| um), named; LinuxCNC's trims, HEIDENHAIN's BACKLASH column,
    # SINUMERIK's CEC tables by direction (also beside the LEC) and ISG's bilateral leadscrew lists
    # carry it moving each way (ISG to its lists' 0.1 um: these reversals are whole multiples).
    from mtacc import report
    errors = tmp_path / "reversal.yaml"
    errors.write_text("errors:\n  EXX: {linear: {value: 6 um, over: 500 mm}, reversal: 2 um}\n  EYY: {reversal: 3 um}\n"
                      "  EZZ: {linear: {value: -4 um, over: 500 mm}, reversal: 4 um}\n")
    r = mtacc.Machine("three-axis-vertical", errors=str(errors)).compensation_tables(nodes=(6, 5, 5))
    half = (1.0 ** 2 + 1.5 ** 2 + 2.0 ** 2) ** 0.5
    carrying = {"linuxcnc", "heidenhain", "siemens-cec", "siemens-lec", "isg-volumetric"}
    assert carrying | {"grid", "one-axis"} == {t["format"] for t in r["tables"]}
    for t in r["tables"]:
        res = t["residual"]
        if t["format"] in carrying:
            assert max(res["after_max_um"], res["moving_forward_max_um"], res["moving_backward_max_um"]) < 0.01, t["format"]
            assert not any("reversal" in left for left in t.get("not_carried", [])), t["format"]
        else:
            assert res["after_max_um"] < 0.05, t["format"]
            assert res["moving_forward_max_um"] == pytest.approx(half, abs=0.05), t["format"]
            assert res["moving_backward_max_um"] == pytest.approx(half, abs=0.05), t["format"]
            assert any(left.startswith("the reversal terms of EXX, EYY, EZZ") for left in t["not_carried"]), t["format"]
    lec = next(t for t in r["tables"] if t["format"] == "siemens-lec")
    assert lec["files"] == "siemens-lec.ini, siemens-cec-reversal.ini"
    assert {"isg-lsec-X.lis", "isg-lsec-Y.lis", "isg-lsec-Z.lis", "siemens-cec-reversal.ini"} <= set(r["files"])
    out = subprocess.run([cli, "compensate", "three-axis-vertical", "--errors", str(errors), "--tables", str(tmp_path / "t"), "--nodes", "6,5,5"],
                         check=True, capture_output=True, text=True).stdout
    assert "largest moving forward / backward" in out and "not carried: the reversal terms of EXX, EYY, EZZ (the table is taken standing)" in out
    section = report.compensation_section(r)
    assert "moving forward / backward, largest [µm]" in section and "the reversal terms of EXX, EYY, EZZ (the table is taken standing)" in section
    com = (tmp_path / "t" / "heidenhain-X.com").read_text().splitlines()
    header = com[1].split()
    assert header[:3] == ["NR", "AXISPOS", "X"] and header[-1] == "BACKLASH"
    # The positive direction's values and the negative's differ by the reversal (2 um on X).
    x, backlash = header.index("X"), header.index("BACKLASH")
    assert all(abs(float(row.split()[x]) - float(row.split()[backlash]) - 0.002) < 2e-5 for row in com[2:-1])


def test_progress_on_a_terminal_only(cli, tmp_path):
    # Issue 47, item 3: a long program shows its progress (lines, rate, share, time left) on stderr
    # when stderr is a terminal, on one line ended before the summary; not in a pipe or a log.
    import os
    import pty
    program = tmp_path / "long.nc"
    program.write_text("G21 G90 G94 F1000\n" + "".join(f"G1 X{100 + (i % 400) * 0.5:.1f} Y{50 + (i % 300) * 0.3:.1f} Z200\n"
                                                      for i in range(70_000)))
    command = [cli, "compensate", "three-axis-vertical", "--program", str(program), "--gcode", str(tmp_path / "out.nc")]
    master, slave = pty.openpty()
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=slave, text=True)
    os.close(slave)
    shown = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # the terminal's other end is closed: all read
            break
        if not chunk:
            break
        shown += chunk
    os.close(master)
    assert run.returncode == 0
    text = shown.decode()
    assert "mtacc: 65536 lines," in text and "lines/s" in text and "s left" in text and text.endswith("\r\n")
    piped = subprocess.run(command, capture_output=True, text=True, check=True)
    assert piped.stderr == "" and "70001 lines, 70000 moves" in piped.stdout
