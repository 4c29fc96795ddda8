"""Every number of every command's --json says its unit, by the convention of docs/file-formats.md
("JSON output"): a unit suffix on its key or on an enclosing key, a "unit" member (or a "units"
list) of its object or of an enclosing one, or its key listed here as an axis position, as
dimensionless or as in the identified parameters' units."""
import json
import pathlib
import re
import subprocess

import pytest

import mtacc

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "data"

UNIT_SUFFIX = re.compile(r"_(mm|um|deg|rad|urad|arcsec|hz|s|ms|kg|C|per_K|percent|ppm"
                         r"|min|mm_per_min|um_per_mm|um_per_m|urad_per_mm|um_per_n|um_per_g|n_per_um|um_urad)$")

# Counts, indices, ratios, signs, statistics of no unit, and unit vectors (directions).
DIMENSIONLESS = {
    "alignment_rms_misfit", "axis_direction", "axis_in_workpiece", "beyond_bound", "bins", "candidates", "criterion_value", "exchanges", "filled_cells", "contouring_orthogonal_undefined_samples", "cells", "chi_square", "column", "columns", "condition",
    "correlation", "coverage_factor", "cutter_moves", "cutting_samples", "damping_coupling", "damping_ratio", "degree", "degrees_of_freedom", "dimension", "direction",
    "exponent", "features", "first_problem_line", "first_sample_used", "fit_significance", "instant_blocks",
    "instrument_samples", "iterations", "largest_relative_misfit", "line", "lines", "location_parameter_count",
    "moves", "nodes", "non_zero_errors", "normals", "normals_machine", "not_converged", "p_value",
    "parameter_count", "parameters", "points", "poses", "rank", "readings", "reference_samples_left_out", "row",
    "rotary_class", "rows", "runs", "runs_each_way", "samples", "samples_per_axis", "samples_used", "seed", "sense", "shape",
    "sigma_over_probe_noise", "sign", "singular", "singular_values", "singular_vectors", "stiffness_changes",
    "stride", "tool_direction", "tool_vector", "tools", "u", "v", "vertical_direction", "volume_poses", "workpiece_axes", "worst_blocks", "written_points"}

# Positions of the machine's axes, each in mm for a linear axis and deg for a rotary one: an
# object keyed by axis name, an array in the machine's axis order, or the positions along one axis.
AXIS_POSITIONS = {"axes", "breaks", "grid", "nominal_pose", "pose", "position", "positions", "q", "target", "travel",
                  "worst_pose"}

# In the units of the parameters as "estimates" gives them (um, urad, ...), entry by entry.
PARAMETER_UNITS = {"covariance"}


def leaf(value):
    """A number, or a list (of lists) of numbers, null allowed beside them."""
    if isinstance(value, bool):
        return False
    if isinstance(value, (int, float)):
        return True
    return isinstance(value, list) and all(leaf(v) or v is None for v in value) and any(leaf(v) for v in value)


def numbers(value):
    """A leaf, or an object of numbers only (an axis-keyed pose)."""
    return leaf(value) or isinstance(value, dict) and bool(value) and all(numbers(v) for v in value.values())


def unitless_keys(node, path="", said=False, found=None):
    """The paths of the numbers whose unit is not said: by their key's suffix, by an enclosing
    key's suffix, by a "unit" member (or a "units" list, entry by entry) of their object or of an
    enclosing one, or by the lists above
    (which cover numbers only, so that an object listed by mistake hides nothing else)."""
    found = set() if found is None else found
    if isinstance(node, dict):
        said = said or isinstance(node.get("unit"), str) or isinstance(node.get("units"), list)
        for key, value in node.items():
            listed = key in DIMENSIONLESS | AXIS_POSITIONS | PARAMETER_UNITS and numbers(value)
            here = said or bool(UNIT_SUFFIX.search(key)) or listed
            if leaf(value):
                if not here:
                    found.add(re.sub(r"\[\d+\]", "[]", f"{path}.{key}"))
            else:
                unitless_keys(value, f"{path}.{key}", here, found)
    elif isinstance(node, list):
        for k, value in enumerate(node):
            unitless_keys(value, f"{path}[{k}]", said, found)
    return found


def run_json(cli, *args):
    out = subprocess.run([cli, *args, "--json"], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, f"{args}: {out.stderr}"
    return json.loads(out.stdout)


@pytest.fixture(scope="module")
def outputs(cli, tmp_path_factory):
    """Each command's JSON on the bundled examples (and on the files the simulations write)."""
    tmp = tmp_path_factory.mktemp("json-units")
    poses = tmp / "poses.csv"
    poses.write_text("X,Y,Z,B,C\n10,20,30,-15,45\n-120,80,-40,60,-170\n")
    zones = tmp / "zones.csv"
    out = {}
    out["check"] = run_json(cli, "check", "tilting-table")
    out["fk"] = run_json(cli, "fk", "tilting-table", "--poses", str(poses))
    out["errors"] = run_json(cli, "errors", "tilting-table", "--poses", str(poses))
    out["ik"] = run_json(cli, "ik", "maho", "--tcp", "100,-300,50", "--tool", "0.3,-1,0", "--with-errors")
    out["sensitivity"] = run_json(cli, "sensitivity", "tilting-table", "--pose", "X=10,Y=0,Z=5,B=-15,C=30")
    out["budget"] = run_json(cli, "budget", "tilting-table", "--samples", "3")
    out["cone"] = run_json(cli, "cone", "tilting-table", "--points", "360", "--single-errors", "--monte-carlo", "20",
                           "--measured", str(DATA / "test-pieces" / "tilting-table-cone-measured.csv"))
    out["cubic"] = run_json(cli, "cubic", "tilting-table", "--grid", "0.5", "--zones-out", str(zones), "--sensitivities",
                            "--sensitivity-parameters", "X0B,B0B", "--sensitivity-grid", "0.5")
    out["cubic-identify"] = run_json(cli, "cubic-identify", "tilting-table", "--zones", str(zones), "--params", "X0B,B0B")
    face = tmp / "face.ply"
    subprocess.run([cli, "cubic", "tilting-table", "--grid", "0.1", "--surface", str(face)], check=True, capture_output=True)
    out["cubic scan"] = run_json(cli, "cubic", "tilting-table", "--grid", "0.5", "--scan", str(face), "--scan-grid", "1")
    trace = tmp / "servo.csv"
    trace.write_text("time_s,X,Y,Z,B,C\n" + "".join(f"{0.001 * k:.3f},{-8 + 0.5 * k},-8,50.1,0,0\n" for k in range(33)))
    out["cubic trace"] = run_json(cli, "cubic", "tilting-table", "--grid", "0.5", "--trace", str(trace))
    ballbar = tmp / "ballbar.csv"
    out["simulate ballbar"] = run_json(cli, "simulate", "ballbar", "tilting-table", "--points", "90", "--noise", "0.3um",
                                       "-o", str(ballbar))
    rtest = tmp / "rtest.csv"
    out["simulate rtest"] = run_json(cli, "simulate", "rtest", "tilting-table", "--sphere", "100,50,80", "-o", str(rtest))
    plan = tmp / "plan"
    out["simulate plan"] = run_json(cli, "simulate", "plan", "tilting-table", "--plan", "tilting-table-rtest", "--noise", "0.3um",
                                    "-o", str(plan))
    out["simulate plate"] = run_json(cli, "simulate", "plate", "maho", "--origin", "-350,-455,-160mm", "-o", str(tmp / "plate.csv"))
    out["simulate component"] = run_json(cli, "simulate", "component", "maho", "--component", "ztz", "--runs", "3",
                                         "-o", str(tmp / "ztz.csv"))
    motion = tmp / "motion"
    out["simulate motion"] = run_json(cli, "simulate", "motion", "inclined-a-table", "--program", str(DATA / "programs" / "seed004-capball.nc"),
                                      "--feeds", "1000,3240", "--structure", "wcayfxzt-compact", "--noise", "0.2um", "-o", str(motion))
    out["decompose"] = run_json(cli, "decompose", "inclined-a-table", out["simulate motion"]["set"], "--series", "50")
    out["evaluate ballbar"] = run_json(cli, "evaluate", "tilting-table", str(ballbar))
    out["evaluate rtest"] = run_json(cli, "evaluate", "tilting-table", str(rtest))
    out["identify"] = run_json(cli, "identify", "tilting-table", "--plan", "tilting-table-rtest", "--robust", "--noise", "0.3um",
                               "--data", ",".join(str(p) for p in sorted(plan.glob("*.csv"))))
    out["observability"] = run_json(cli, "observability", "tilting-table", "--plan", "tilting-table-rtest")
    out["positioning"] = run_json(cli, "positioning", str(DATA / "positioning" / "rotary-table.csv"))
    out["acceptance"] = run_json(cli, "acceptance", "tilting-table", "--tests", str(DATA / "acceptance" / "tilting-table-acceptance.yaml"))
    out["rotary-tests"] = run_json(cli, "rotary-tests", "tilting-table", "--positions", "12", "--points", "72")
    out["design"] = run_json(cli, "design", "tilting-table", "--plan", "tilting-table-rtest", "--time", "30min")
    stage = DATA / "positioning" / "ecmc-motion-stage"
    out["positioning-conformance"] = run_json(cli, "positioning", f"{stage}.dat", "--conditions", f"{stage}-conditions.yaml",
                                              "--tolerances", f"{stage}-tolerances.yaml")
    out["squareness"] = run_json(cli, "squareness", "--aligned-to", "x", "--alpha", "0.7", "--beta", "2.1", "--block", "1.7")
    out["yry"] = run_json(cli, "yry", "--y", "0,250", "--ytz1", "1,2", "--ytz2", "0,-1", "--xrx", "0.5", "--x1", "0", "--x2", "552.691")
    out["multitasking"] = run_json(cli, "multitasking", str(DATA / "ballbar" / "seed002-table6.yaml"))
    out["fit"] = run_json(cli, "fit", "maho", str(DATA / "direct-measurements" / "maho-xtx.csv"))
    out["plate"] = run_json(cli, "plate", "maho", str(DATA / "plates" / "maho-xy-z292.csv"))
    out["plate-identify"] = run_json(cli, "plate-identify", "maho", str(DATA / "plates" / "maho-xy-z292.csv"), "--piece", "100")
    out["simulate artefact"] = run_json(cli, "simulate", "artefact", "maho", "--layout", str(DATA / "artefacts" / "step-gauge-diagonal.csv"),
                                        "-o", str(tmp / "gauge.csv"))
    out["artefact"] = run_json(cli, "artefact", "maho", str(DATA / "artefacts" / "maho-ball-plate-tilted.csv"))
    out["stiffness"] = run_json(cli, "stiffness", "maho", "--errors", str(DATA / "stiffness" / "maho-260kg.yaml"), "--samples", "3")
    program = DATA / "programs" / "seed004-capball.nc"
    truth = tmp / "truth.yaml"
    truth.write_text("errors:\n  X0C: 7 um\n  A0B: 20 urad\n")
    subprocess.run([cli, "cone", "tilting-table", "--gcode", str(tmp / "cone.nc")], check=True, capture_output=True)
    out["compensate program"] = run_json(cli, "compensate", "tilting-table", "--program", str(tmp / "cone.nc"), "--gcode", str(tmp / "c.nc"),
                                         "--check-errors", str(truth))
    out["compensate tables"] = run_json(cli, "compensate", "tilting-table", "--tables", str(tmp / "tables"), "--nodes", "5,5,5")
    out["deviation"] = run_json(cli, "deviation", "inclined-a-table", "--program", str(program))
    for what in ("modes", "frf", "accel", "map"):
        out[f"dynamics {what}"] = run_json(cli, "dynamics", what, "tzyx-arm-x")
    out["drift"] = run_json(cli, "drift", str(DATA / "thermal" / "z-axis-drift.csv"), "--position", "Z")
    out["python thermal_state"] = mtacc.as_json(mtacc.thermal_state("three-axis-vertical", DATA / "thermal" / "three-axis-vertical-warm.yaml"))
    return out


def test_every_command_with_json_is_walked(cli, outputs):
    text = subprocess.run([cli, "--help"], capture_output=True, text=True, check=True).stdout
    commands = set(re.findall(r"^  ([a-z][a-z0-9-]*)", text.split("Subcommands:")[1], flags=re.M)) - {"report"}
    assert commands <= {name.split()[0] for name in outputs}


def test_every_number_says_its_unit(outputs):
    missing = {name: sorted(unitless_keys(j)) for name, j in outputs.items()}
    missing = {name: keys for name, keys in missing.items() if keys}
    assert not missing, json.dumps(missing, indent=1)


def test_the_walk_finds_a_number_without_its_unit():
    # The rules above, each once, and a number each should not excuse.
    j = {"radius": 3.0, "radius_mm": 3.0, "poses": 4, "pose": {"X": 1.0, "B": 2.0},
         "shares_percent": {"link": 1.0}, "estimates": [{"unit": "urad", "value": 1.0}],
         "drawn": {"units": ["um"], "values": [[1.0]]},
         "axes": [{"name": "X", "offset": 2.0}], "poses_run": [{"poses": 3, "scale": 1.0}]}
    assert unitless_keys(j) == {".radius", ".axes[].offset", ".poses_run[].scale"}
