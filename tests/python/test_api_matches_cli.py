"""The Python API and the CLI's --json give identical numbers for the same inputs."""
import json
import pathlib
import subprocess

import numpy as np
import pytest

import mtacc

POSES = np.array([[10.0, 20.0, 30.0, -15.0, 45.0], [-120.0, 80.0, -40.0, 60.0, -170.0], [300.0, -250.0, 350.0, -110.0, 10.0]])


def run_json(cli, *args):
    out = subprocess.run([cli, *args, "--json"], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


@pytest.fixture()
def poses_csv(tmp_path):
    path = tmp_path / "poses.csv"
    path.write_text("X,Y,Z,B,C\n" + "\n".join(",".join(repr(v) for v in row) for row in POSES) + "\n")
    return str(path)


def test_fk_and_errors(cli, poses_csv):
    machine = mtacc.Machine("tilting-table")
    pos, tool = machine.fk(POSES)
    err = machine.tcp_errors(POSES)
    data = run_json(cli, "fk", "tilting-table", "--poses", poses_csv)
    assert len(data["poses"]) == len(POSES)
    for k, row in enumerate(data["poses"]):
        assert row["tcp_mm"] == pos[k].tolist()
        assert row["tool_direction"] == tool[k].tolist()
        assert row["position_error_um"] == err[k, :3].tolist()
        assert row["orientation_error_urad"] == err[k, 3:].tolist()


def test_ik(cli):
    machine = mtacc.Machine("inclined-a-table")
    py = machine.ik([10, 20, 30], [0.3, 0.2, 0.9], all=True)
    data = run_json(cli, "ik", "inclined-a-table", "--tcp", "10,20,30", "--tool", "0.3,0.2,0.9", "--all")
    assert data["solutions"] == py


def test_ik_with_errors(cli):
    # The inverse error model: the same commands from both, and with them the machine with its
    # errors puts the TCP where it was asked (fk of the actual machine), where the nominal
    # commands miss by the machine's error there.
    machine = mtacc.Machine("maho")
    py = machine.ik([100, -300, 50], [0.3, -1, 0], with_errors=True)
    data = run_json(cli, "ik", "maho", "--tcp", "100,-300,50", "--tool", "0.3,-1,0", "--with-errors")
    assert data["solutions"] == py
    s = py[0]
    assert s["converged"] and not s["singular"] and s["direction_controlled"]
    names = machine.axis_names
    q = np.array([[s["pose"][n] for n in names], [s["nominal_pose"][n] for n in names]])
    tcp, tool = machine.fk(q)
    np.testing.assert_allclose(tcp[0], [100, -300, 50], atol=1e-9)
    np.testing.assert_allclose(tool[0], np.array([0.3, -1, 0]) / np.linalg.norm([0.3, -1, 0]), atol=1e-12)
    assert np.linalg.norm(tcp[1] - [100, -300, 50]) > 1e-3
    path = machine.ik_path([[100, -300, 50], [110, -300, 50]], [[0.3, -1, 0], [0.3, -1, 0]], with_errors=True)
    np.testing.assert_allclose(path[0], q[0], atol=1e-12)


def test_budget(cli):
    machine = mtacc.Machine("tilting-table")
    py = machine.budget(samples=4)
    data = run_json(cli, "budget", "tilting-table", "--samples", "4")
    assert data == py


def test_errors_set_through_python_equal_an_errors_file(cli, tmp_path):
    errors = tmp_path / "errors.yaml"
    errors.write_text("errors:\n  X0C: 7 um\n  A0B: 20 urad\n  EXX: {reversal: 3 um}\n")
    from_file = mtacc.Machine("tilting-table", errors=errors)
    by_name = mtacc.Machine("tilting-table", errors=errors)
    for name in list(by_name.errors):
        del by_name.errors[name]
    assert len(by_name.errors) == 0
    by_name.errors["X0C"] = "7 um"
    by_name.errors["A0B"] = 20e-6
    by_name.errors["EXX.rev"] = "3 um"
    assert np.array_equal(from_file.tcp_errors(POSES), by_name.tcp_errors(POSES))
    assert by_name.errors.unit("A0B") == "rad" and by_name.errors.unit("X0C") == "mm"
    # Aliases read through the same names (seed 001: dxBY = -X0B).
    by_name.errors["δxBY"] = "10 um"
    assert by_name.errors["X0B"] == pytest.approx(-0.010)
    data = run_json(cli, "errors", "tilting-table", "--errors", str(errors), "--pose", "X=10,Y=20,Z=30,B=-15,C=45")
    assert data["poses"][0]["position_error_um"] == from_file.tcp_errors(POSES[:1])[0, :3].tolist()


def test_sensitivity_coefficient(cli):
    machine = mtacc.Machine("tilting-table")
    q = "X=0,Y=0,Z=100,B=-30,C=0"
    data = run_json(cli, "sensitivity", "tilting-table", "--pose", q, "--params", "X0C,A0B", "--direction", "-0.5,0,0.866")
    n = np.array([-0.5, 0, 0.866])
    n = n / np.linalg.norm(n)
    k_x0c = machine.sensitivity_coefficient([0, 0, 100, -30, 0], "X0C", "10 um", n)
    k_a0b = machine.sensitivity_coefficient([0, 0, 100, -30, 0], "A0B", "30 urad", n)
    assert data["parameters"][0]["k_exact"] == k_x0c           # um/um
    assert data["parameters"][1]["k_exact"] == k_a0b * 1e-3    # um/urad from mm/rad
    assert machine.sensitivity({"X": 0, "Y": 0, "Z": 100, "B": -30, "C": 0}, direction=(-0.5, 0, 0.866), parameters=["X0C", "A0B"]) == data


def test_check_and_cone(cli, as_json):
    machine = mtacc.Machine("swivel-head-table")
    assert run_json(cli, "check", "swivel-head-table") == machine.check()
    cone = machine.cone(preset="swivel-head", single_errors=True)
    n = len(cone["path"]["phi_deg"])
    assert cone["path"]["q"].shape == (n, 5) and cone["path"]["points_mm"].shape == (n, 3)
    with_errors = mtacc.Machine("tilting-table").cone(single_errors=True, points=90)
    assert with_errors["deviation_um"].shape == with_errors["single_errors"][0]["deviation_um"].shape == (90,)
    assert run_json(cli, "cone", "swivel-head-table", "--preset", "swivel-head", "--single-errors") == as_json(cone)


def test_check_lists_every_parameter_on_request(cli):
    out = subprocess.run([cli, "check", "tilting-table", "--parameters"], check=True, capture_output=True, text=True).stdout
    listed = {}
    for line in out.split("Every parameter")[1].splitlines()[1:]:
        if not line.startswith("  "):
            break
        axis, *names = line.split()
        listed[axis] = names
    assert sorted(name for names in listed.values() for name in names) == sorted(mtacc.Machine("tilting-table").check()["parameters"])
    assert listed["C1"] == ["X0C1", "Y0C1", "Z0C1", "A0C1", "B0C1", "C0C1"]  # the spindle's location errors by their own name


def test_observability(cli, as_json):
    machine = mtacc.Machine("tilting-table")
    assert run_json(cli, "observability", "tilting-table", "--plan", "tilting-table-rtest") == \
        as_json(machine.observability("tilting-table-rtest"))


def test_ik_near_a_pose_and_poses_without_rounding_noise(cli):
    # The double pivot head reaches a tilted tool four ways (B = -30 or 30, C a half turn apart,
    # and each C a turn further); --near / near= picks the one closest to a pose.
    args = ["ik", "double-pivot-head", "--tcp", "10,20,30", "--tool", "0,0.5,0.8660254037844386"]
    machine = mtacc.Machine("double-pivot-head")
    for near, expected in (({"C": -80}, {"B": -30.0, "C": -90.0}), ({"C": 80, "B": 30}, {"B": 30.0, "C": 90.0}),
                           ({"C": 260}, {"B": -30.0, "C": 270.0})):
        text = ",".join(f"{k}={v}" for k, v in near.items())
        data = run_json(cli, *args, "--near", text)
        assert data["solutions"] == machine.ik([10, 20, 30], [0, 0.5, 0.8660254037844386], near=near)
        pose = data["solutions"][0]["pose"]
        assert {axis: pose[axis] for axis in expected} == expected  # exactly: 30.0, not 29.99999999999999
    with pytest.raises(mtacc.InputError, match="near"):
        machine.ik([10, 20, 30], near={"Q": 1})


def test_check_names_zero_offsets_and_location_errors_acting_alike(cli):
    # docs/examples/inclined-head.yaml: B along (0, 1, 1)/sqrt(2) in the head, C in the table.
    example = str(pathlib.Path(__file__).parents[2] / "docs" / "examples" / "inclined-head.yaml")
    data = run_json(cli, "check", example)
    assert data["zero_offsets"] == ["B.zero = 0.707107 B0B + 0.707107 C0B", "C.zero = -C0C"]
    alike = data["location_errors_acting_alike"]
    # A shift of the head's line and the opposite shift of the table's act alike (conventions.md).
    assert "X0X, X0B and X0C act alike (X0X = X0B = -X0C in effect)" in alike
    out = subprocess.run([cli, "check", example, "--parameters"], check=True, capture_output=True, text=True).stdout
    assert "  B.zero = 0.707107 B0B + 0.707107 C0B\n" in out
    assert "Warning: location errors that no measurement on this machine separates" in out
    assert mtacc.Machine(example).check()["location_errors_acting_alike"] == alike


def test_errors_with_tcp_prints_the_fk_columns(cli, tmp_path):
    pose = ["--pose", "X=10,Y=20,Z=30,B=-15,C=45"]
    subprocess.run([cli, "fk", "tilting-table", *pose, "-o", str(tmp_path / "fk.csv")], check=True, capture_output=True)
    subprocess.run([cli, "errors", "tilting-table", *pose, "--with-tcp", "-o", str(tmp_path / "errors.csv")], check=True,
                   capture_output=True)
    subprocess.run([cli, "errors", "tilting-table", *pose, "-o", str(tmp_path / "plain.csv")], check=True, capture_output=True)
    assert (tmp_path / "errors.csv").read_text() == (tmp_path / "fk.csv").read_text()
    assert "x,y,z,i,j,k" in (tmp_path / "errors.csv").read_text() and "x,y,z" not in (tmp_path / "plain.csv").read_text()


def test_single_pose_calls_follow_a_changed_error():
    # fk keeps the compiled model between calls; changing an error must drop it.
    machine = mtacc.Machine("tilting-table")
    before = machine.tcp_errors(POSES[0])
    machine.errors["X0C"] = "30 um"
    fresh = mtacc.Machine("tilting-table")
    fresh.errors["X0C"] = "30 um"
    assert not np.allclose(machine.tcp_errors(POSES[0]), before)
    assert np.array_equal(machine.tcp_errors(POSES[0]), fresh.tcp_errors(POSES[0]))
    assert np.array_equal(machine.fk(POSES), fresh.fk(POSES))


def test_simulated_runs(cli, tmp_path):
    # The same keys through both front ends, the same runs (files and summary alike).
    machine = mtacc.Machine("tilting-table")
    py = machine.simulate_ballbar(output=tmp_path / "py.csv", plane="YZ", radius="150 mm", points=90, pose={"B": -30}, noise="0.3 um",
                                  seed=4, lag="Y=1ms", setup={"xW": "10 um"})
    data = run_json(cli, "simulate", "ballbar", "tilting-table", "-o", str(tmp_path / "cli.csv"), "--plane", "YZ", "--radius", "150mm",
                    "--points", "90", "--pose", "B=-30", "--noise", "0.3um", "--seed", "4", "--lag", "Y=1ms", "--setup", "xW=10um")
    assert (tmp_path / "py.csv").read_text() == (tmp_path / "cli.csv").read_text()
    assert [r.pop("file") for r in py["runs"]] == [str(tmp_path / "py.csv")] and [r.pop("file") for r in data["runs"]] == [str(tmp_path / "cli.csv")]
    assert py == data
    py = machine.simulate_rtest((100, 50, 80), axis="B", from_="-60 deg", to="60 deg", points=5, probe=True)
    data = run_json(cli, "simulate", "rtest", "tilting-table", "-o", str(tmp_path / "r.csv"), "--sphere", "100,50,80", "--axis", "B",
                    "--from", "-60deg", "--to", "60deg", "--points", "5", "--probe")
    assert [r.pop("file") for r in py["runs"]] == [None] and [r.pop("file") for r in data["runs"]] == [str(tmp_path / "r.csv")]
    assert py == data
