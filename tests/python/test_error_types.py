"""Every workflow refuses an invalid option with mtacc.InputError, never a bare ValueError,
RuntimeError or AttributeError: the one exception a caller has to catch for bad input. Each
case reaches the check that refuses it in a different layer (the binding, the workflow, or the
domain code under it, whose errors the workflow does not relocate)."""
import pathlib

import pytest

import mtacc

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"
PROGRAM = str(DATA / "programs" / "seed004-capball.nc")


def three_axis():
    return mtacc.Machine("three-axis-vertical")


def tilting():
    return mtacc.Machine("tilting-table")


def arm():
    return mtacc.Structure(str(DATA / "structures" / "tzyx-arm-x.yaml"))


CASES = {
    "budget samples": lambda: three_axis().budget(samples=1),
    "working volume samples": lambda: three_axis().working_volume_grid(samples=1),
    "cone angle": lambda: tilting().cone(alpha=95),
    "cubic grid": lambda: tilting().cubic(grid=0),
    "stiffness without load": lambda: mtacc.Machine(str(DATA / "machines" / "maho.yaml")).stiffness(samples=2),
    "tables nodes": lambda: three_axis().compensation_tables(nodes=(1, 1, 1)),
    "tables pose of another type": lambda: tilting().compensation_tables(pose=["B", 0]),
    "tables pose not a number": lambda: tilting().compensation_tables(pose={"B": "ten"}),
    "tables pose text": lambda: tilting().compensation_tables(pose="B=0,Q=1"),
    "ik near": lambda: tilting().ik([0, 0, 100], near=3),
    "thermal points": lambda: mtacc.thermal_state("three-axis-vertical", str(DATA / "thermal" / "three-axis-vertical-warm.yaml"),
                                                  points=1),
    "drift folds": lambda: mtacc.drift_test(str(DATA / "thermal" / "z-axis-drift.csv"), folds=1),
    "positioning of another file": lambda: mtacc.positioning(str(DATA / "machines" / "maho.yaml")),
    "deviation step": lambda: three_axis().deviation(PROGRAM, step=0),
    "simulate noise": lambda: tilting().simulate(str(DATA / "plans" / "tilting-table-rtest.yaml"), noise="-1 um"),
    "identify without data": lambda: tilting().identify([]),
    "ik path lengths": lambda: tilting().ik_path([[0, 0, 0]], [[0, 0, 1], [0, 0, 1]]),
    "sensitivity epsilon": lambda: tilting().sensitivity_coefficient([0] * 5, "X0Y", 0, (1, 0, 0)),
    "motion feed": lambda: three_axis().simulate_motion(PROGRAM, "unused.csv", feeds=[-1]),
    "frf frequency": lambda: arm().frf([-5.0]),
    "map grid": lambda: arm().map(grid=(1, 1)),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_invalid_option_raises_input_error(case, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(Exception) as info:
        CASES[case]()
    assert isinstance(info.value, mtacc.InputError), f"{type(info.value).__name__}: {info.value}"
    assert str(info.value), "the error says what is wrong"
    assert list(tmp_path.iterdir()) == [], "nothing is written when the input is refused"
