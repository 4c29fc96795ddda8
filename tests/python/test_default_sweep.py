"""No silent wrong answer: every workflow that runs from a machine alone, on every bundled machine,
plan, cone preset and structure, with its default options.

Each run either refuses cleanly (exit 2, one line on stderr) or succeeds; a crash (a signal, as the
R-test on a spindle once aborted with memory corruption) fails. Every number of a successful
run's JSON is finite, and every length result (a key ending in `_um`) is within a plausibility
bound: ten times the machine's combined TCP error over its working volume, or 1 mm if larger.
The blow-ups this sweep was written against were 1e10 um (a Monte Carlo dividing by the range of
an axis that does not move), 1e289 um (plate estimates of parameters without effect) and 4 mm
(one coefficient of a piecewise function budgeted alone, on a machine whose errors together make
86 um).
"""
import json
import math
import pathlib
import subprocess

import pytest

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"
MACHINES = sorted(p.stem for p in (DATA / "machines").glob("*.yaml"))
PLANS = sorted(p.stem for p in (DATA / "plans").glob("*.yaml"))
STRUCTURES = sorted(p.stem for p in (DATA / "structures").glob("*.yaml"))
CONE_PRESETS = ["tilting-table", "swivel-head", "double-pivot", "nas979"]
TIMEOUT_S = 300


def run(cli, *args):
    out = subprocess.run([cli, *args], capture_output=True, text=True, timeout=TIMEOUT_S)
    assert out.returncode in (0, 2), f"{' '.join(args)}: exit {out.returncode}\n{out.stderr[-2000:]}"
    if out.returncode == 2:
        assert out.stderr.count("\n") == 1 and out.stderr.startswith("mtacc: error: "), out.stderr
        return None
    return out


def numbers(node, key=""):
    """(key, value) of every number in a JSON document, the key of the innermost mapping."""
    if isinstance(node, dict):
        for k, v in node.items():
            yield from numbers(v, k)
    elif isinstance(node, list):
        for v in node:
            yield from numbers(v, key)
    elif isinstance(node, (int, float)) and not isinstance(node, bool):
        yield key, node


def expect_plausible(result, bound_um, what):
    assert result, what
    for key, value in numbers(result):
        assert math.isfinite(value), f"{what}: {key} = {value}"
        if key.endswith("_um"):
            assert abs(value) <= bound_um, f"{what}: {key} = {value} um beyond {bound_um:.0f} um"


def json_of(cli, *args):
    out = run(cli, *args, "--json")
    return None if out is None else json.loads(out.stdout)


@pytest.fixture(scope="module")
def bounds(cli):
    """Per machine: the plausibility bound (um) and the centre of each commanded axis's travel."""
    out = {}
    for m in MACHINES:
        budget = json_of(cli, "budget", m, "--samples", "3")
        check = json_of(cli, "check", m)
        centre = []
        for a in check["axes"]:
            if a["type"] == "spindle":
                continue
            travel = a.get("travel")
            middle = 0.0 if not isinstance(travel, list) else 0.5 * (travel[0] + travel[1])
            centre.append(f"{a['name']}={middle:g}")
        out[m] = (max(10.0 * budget["combined_max_position_error_um"], 1000.0), ",".join(centre), check)
    return out


@pytest.mark.parametrize("machine", MACHINES)
def test_machine_workflows(cli, bounds, machine, tmp_path):
    bound, centre, check = bounds[machine]
    expect_plausible(check, bound, f"check {machine}")
    expect_plausible(json_of(cli, "budget", machine, "--samples", "3"), bound, f"budget {machine}")
    expect_plausible(json_of(cli, "sensitivity", machine, "--pose", centre), float("inf"), f"sensitivity {machine}")
    expect_plausible(json_of(cli, "fk", machine, "--pose", centre), bound, f"fk {machine}")
    for args in (["cone"], ["cubic"]):
        result = json_of(cli, *args, machine)
        if result is not None:
            expect_plausible(result, bound, f"{args[0]} {machine}")
    ballbar = tmp_path / "ballbar.csv"
    if run(cli, "simulate", "ballbar", machine, "-o", str(ballbar)) is not None:
        expect_plausible(json_of(cli, "evaluate", machine, str(ballbar)), bound, f"evaluate {machine} ballbar")
    for a in check["axes"]:
        rtest = tmp_path / f"rtest-{a['name']}.csv"
        if a["type"] == "linear":
            continue
        if run(cli, "simulate", "rtest", machine, "--axis", a["name"], "--sphere", "100,0,50", "-o", str(rtest)) is not None:
            assert rtest.stat().st_size > 0


@pytest.mark.parametrize("machine", MACHINES)
@pytest.mark.parametrize("preset", CONE_PRESETS)
def test_cone_monte_carlo(cli, bounds, machine, preset):
    result = json_of(cli, "cone", machine, "--preset", preset, "--monte-carlo", "20")
    if result is not None:
        expect_plausible(result, bounds[machine][0], f"cone {machine} {preset} Monte Carlo")


@pytest.mark.parametrize("machine", MACHINES)
@pytest.mark.parametrize("plan", PLANS)
def test_plans(cli, bounds, machine, plan):
    result = json_of(cli, "observability", machine, "--plan", plan)
    if result is not None:
        expect_plausible(result, bounds[machine][0], f"observability {machine} {plan}")
    # Every location error at once: many exactly unobservable directions (this crashed Eigen's
    # divide-and-conquer SVD with a segmentation fault).
    every = ",".join(p for p in bounds[machine][2]["parameters"] if "." not in p)
    result = json_of(cli, "observability", machine, "--plan", plan, "--params", every)
    if result is not None:
        expect_plausible(result, bounds[machine][0], f"observability {machine} {plan} of every location error")


# The machine each bundled plan was written for (its header says so).
PLAN_MACHINES = {"double-pivot-rtest": "double-pivot-head", "seed001-cubic": "tilting-table", "seed002-six-runs": "multitasking-b-c",
                 "tilting-table-designed": "tilting-table", "tilting-table-rtest": "tilting-table"}


def test_every_bundled_plan_runs_on_its_own_machine(cli):
    # Refused there, a bundled plan is a broken example (seed002-six-runs left the X travel of
    # multitasking-b-c).
    assert sorted(PLAN_MACHINES) == PLANS
    for plan, machine in PLAN_MACHINES.items():
        out = subprocess.run([cli, "observability", machine, "--plan", plan, "--json"], capture_output=True, text=True,
                             timeout=TIMEOUT_S)
        assert out.returncode == 0, f"{plan} on {machine}: {out.stderr}"


@pytest.mark.parametrize("structure", STRUCTURES)
def test_structure_workflows(cli, structure):
    bound = 1e6  # um per N or per g: a blow-up of a near-singular solve is orders beyond
    for args in (["modes"], ["frf"], ["accel"], ["map"]):
        result = json_of(cli, "dynamics", *args, structure)
        expect_plausible(result, bound, f"dynamics {args[0]} {structure}")
        if args == ["frf"]:
            assert result["method"] in ("modal", "direct") and math.isfinite(result["damping_coupling"])
