"""Bad input through Python raises a Python exception with the CLI's message, never a crash."""
import pathlib
import subprocess

import numpy as np
import pytest

import mtacc

MACHINE = (pathlib.Path(__file__).resolve().parents[1] / "data" / "test-machine.yaml").read_text()

CASES = {
    "malformed": "name: x\naxes: [1, 2\n",
    "missing_unit": MACHINE + "errors:\n  X0C: 10\n",
    "unknown_error": MACHINE + "errors:\n  X0Q: 10 um\n",
    "zero_direction": MACHINE.replace("[1, 0, 0]", "[0, 0, 0]"),
    "unknown_axis": "name: x\nstructure: t-(C)-Z-Q-b-X-w\naxes: {}\n",
}


def cli_message(cli, *args):
    out = subprocess.run([cli, *args], capture_output=True, text=True)
    assert out.returncode != 0
    line = out.stderr.strip()
    assert line.count("\n") == 0
    assert line.startswith("mtacc: error: ")
    return line[len("mtacc: error: "):]


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_machine_file(cli, tmp_path, case):
    path = tmp_path / f"{case}.yaml"
    path.write_text(CASES[case])
    expected = cli_message(cli, "check", str(path))
    with pytest.raises(mtacc.InputError) as info:
        mtacc.Machine(str(path))
    assert str(info.value) == expected


def test_unreachable_pose(cli):
    expected = cli_message(cli, "ik", "tilting-table", "--tcp", "0,0,0", "--tool", "0,0,-1")
    with pytest.raises(mtacc.InputError) as info:
        mtacc.Machine("tilting-table").ik([0, 0, 0], [0, 0, -1])
    assert "--" + str(info.value) == expected  # the CLI names the option, Python the argument


def test_pose_beyond_travel(cli):
    expected = cli_message(cli, "fk", "tilting-table", "--pose", "X=500,Y=0,Z=0,B=0,C=0")
    with pytest.raises(mtacc.InputError) as info:
        mtacc.Machine("tilting-table").fk([500, 0, 0, 0, 0])
    assert "X=500 mm beyond travel [-400, 400] mm" in str(info.value)
    assert "X=500 mm beyond travel [-400, 400] mm" in expected


def test_bad_arrays_and_names_raise():
    m = mtacc.Machine("tilting-table")
    with pytest.raises(mtacc.InputError):
        m.fk([[1, 2, 3]])
    with pytest.raises(mtacc.InputError):
        m.tcp_errors([[np.nan, 0, 0, 0, 0]])
    with pytest.raises(mtacc.InputError):
        m.errors["X0Q"] = 1.0
    with pytest.raises(mtacc.InputError):
        m.errors["A0B"] = "10 um"
    for value in (None, float("nan"), 1e300, [1.0]):
        with pytest.raises(mtacc.InputError, match="X0B"):
            m.errors["X0B"] = value
    with pytest.raises(mtacc.InputError, match="threads"):
        m.fk([[0, 0, 0, 0, 0]], threads=-1)
    with pytest.raises(mtacc.InputError):
        m.ik([0, 0, 0], [0, 0, 1], branch="sideways")
