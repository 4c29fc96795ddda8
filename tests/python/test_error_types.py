"""Every workflow refuses an invalid option with mtacc.InputError, never a bare ValueError,
RuntimeError or AttributeError: the one exception a caller has to catch for bad input. Each
case reaches the check that refuses it in a different layer (the binding, the workflow, or the
domain code under it, whose errors the workflow does not relocate)."""
import pathlib

import pytest

import mtacc
from mtacc import _mtacc, report

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"
PROGRAM = str(DATA / "programs" / "seed004-capball.nc")


def three_axis():
    return mtacc.Machine("three-axis-vertical")


def tilting():
    return mtacc.Machine("tilting-table")


def arm():
    return mtacc.Structure(str(DATA / "structures" / "tzyx-arm-x.yaml"))


def maho():
    return mtacc.Machine(str(DATA / "machines" / "maho.yaml"))


NOT_A_RUN = str(DATA / "machines" / "maho.yaml")

# One invalid option of each workflow, by the command's name.
WORKFLOWS = {
    "budget": lambda: three_axis().budget(samples=1),
    "check": lambda: _mtacc.read_options("check", {"parameters": ["maybe"]}),
    "compensate": lambda: three_axis().compensate_program(PROGRAM, tolerance=0),
    "cone": lambda: tilting().cone(alpha=95),
    "cubic": lambda: tilting().cubic(grid=0),
    "cubic-identify": lambda: tilting().cubic_identify("missing-zones.csv", ["X0B"]),
    "decompose": lambda: three_axis().decompose("missing-set.yaml", drift_frame="sideways"),
    "deviation": lambda: three_axis().deviation(PROGRAM, step=0),
    "drift": lambda: mtacc.drift_test(str(DATA / "thermal" / "z-axis-drift.csv"), folds=1),
    "dynamics accel": lambda: arm().acceleration_response(at={"Q": 1}),
    "dynamics frf": lambda: arm().frf([-5.0]),
    "dynamics map": lambda: arm().map(grid=(1, 1)),
    "dynamics modes": lambda: arm().modes(count=0),
    "errors": lambda: tilting().tcp_errors([0] * 5, threads=-1),
    "evaluate": lambda: maho().evaluate_ballbar(NOT_A_RUN),
    "fk": lambda: tilting().fk([0] * 5, threads=-1),
    "fit": lambda: maho().fit_component(str(DATA / "direct-measurements" / "maho-xtx.csv"), degree=3),
    "identify": lambda: tilting().identify([]),
    "ik": lambda: tilting().ik([0, 0, 100], near=3),
    "observability": lambda: tilting().observability("no-such-plan"),
    "plate": lambda: maho().compare_plate(NOT_A_RUN),
    "artefact": lambda: maho().evaluate_artefact(NOT_A_RUN),
    "simulate artefact": lambda: maho().simulate_artefact(NOT_A_RUN, "artefact.csv", noise="-1 um"),
    "plate-identify": lambda: maho().identify_plates([str(DATA / "plates" / "maho-xy-z292.csv")], piece=-1),
    "positioning": lambda: mtacc.positioning(NOT_A_RUN),
    "rotary-tests": lambda: tilting().rotary_tests(radius="-5 mm"),
    "acceptance": lambda: tilting().acceptance(NOT_A_RUN),
    "design": lambda: tilting().design(time="soon", parameters=["X0C"]),
    "multitasking": lambda: mtacc.multitasking(NOT_A_RUN),
    "squareness": lambda: mtacc.squareness("y", 0.7, 2.1),
    "yry": lambda: mtacc.yry([0, 100], [1, 2], [0], 0.5, 0, 550),
    "report": lambda: report.build_report("tilting-table", samples="many"),
    "sensitivity": lambda: tilting().sensitivity({"Q": 1}),
    "simulate ballbar": lambda: tilting().simulate_ballbar(points=0),
    "simulate component": lambda: maho().simulate_component("qqq", "runs.csv"),
    "simulate motion": lambda: three_axis().simulate_motion(PROGRAM, "unused", feeds=[-1]),
    "simulate plan": lambda: tilting().simulate(str(DATA / "plans" / "tilting-table-rtest.yaml"), noise="-1 um"),
    "simulate plate": lambda: maho().simulate_plate("plate.csv", origin=(0, "x", 0)),
    "simulate rtest": lambda: tilting().simulate_rtest((100, 0, 50), points=0),
    "stiffness": lambda: maho().stiffness(samples=2),
}

# Checks in other layers: the binding's conversions and the domain code under a workflow.
OTHERS = {
    "working volume samples": lambda: three_axis().working_volume_grid(samples=1),
    "tables nodes": lambda: three_axis().compensation_tables(nodes=(1, 1, 1)),
    "tables pose of another type": lambda: tilting().compensation_tables(pose=["B", 0]),
    "tables pose not a number": lambda: tilting().compensation_tables(pose={"B": "ten"}),
    "tables pose text": lambda: tilting().compensation_tables(pose="B=0,Q=1"),
    "thermal points": lambda: mtacc.thermal_state("three-axis-vertical", str(DATA / "thermal" / "three-axis-vertical-warm.yaml"),
                                                  points=1),
    "ik path lengths": lambda: tilting().ik_path([[0, 0, 0]], [[0, 0, 1], [0, 0, 1]]),
    "sensitivity epsilon": lambda: tilting().sensitivity_coefficient([0] * 5, "X0Y", 0, (1, 0, 0)),
}

CASES = {**WORKFLOWS, **OTHERS}


def test_every_workflow_has_a_case():
    assert set(WORKFLOWS) == set(_mtacc.option_schema_workflows())


@pytest.mark.parametrize("case", sorted(CASES))
def test_invalid_option_raises_input_error(case, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(Exception) as info:
        CASES[case]()
    assert isinstance(info.value, mtacc.InputError), f"{type(info.value).__name__}: {info.value}"
    assert str(info.value), "the error says what is wrong"
    assert list(tmp_path.iterdir()) == [], "nothing is written when the input is refused"
