"""A workflow whose options are declared in a schema has the same options at both front ends:
the schema's keys, the CLI command's flags (--key, '_' written '-') and the Python method's
keyword arguments are one set, besides what a front end adds of its own (listed with why)."""
import inspect
import re
import subprocess

import pytest

import mtacc
from mtacc import _mtacc, report

# Besides the schema's keys, each front end has a few of its own:
# - The machine and its set-up are the Python Machine's constructor, a structure model the
#   Structure's; --json, -o, --strict and --rows (of the printed table) shape the CLI's output.
# - errors_out is a file either front end writes; series_points adds curves to Python's result,
#   for the report's plots.
CLI_ONLY = {"help", "machine", "model", "errors", "alignment", "load", "thermal", "json", "output", "strict", "rows"}
BOTH_FRONT_ENDS = {"errors_out"}
PYTHON_ONLY = {"series_points"}
# And a workflow's own:
# - Python returns the compensated program's text ("gcode") and the tables' files ("contents")
#   instead of writing them; the periodic rewrite of the tables runs until it is stopped.
# - Python gives poses, targets and frequencies as arrays (fk's and errors' q and directions,
#   ik_path's tcps and tools, frf's frequencies) where the CLI reads text, a file or a grid.
# - What the CLI prints (check's parameter list, errors' TCP columns) is always in Python's result;
#   Python maps a second structure with that Structure's own map.
# - build_report is a function: the machine is its first argument; progress tells a caller each step.
CLI_ONLY_OF = {"compensate": {"gcode", "tables", "every", "updates"}, "dynamics frf": {"from", "to", "step"}, "dynamics map": {"compare"},
               "fk": {"pose", "poses"}, "errors": {"pose", "poses", "with_tcp"}, "ik": {"targets"}, "check": {"parameters"}}
PYTHON_ONLY_OF = {"report": {"machine", "progress"}, "dynamics frf": {"frequencies"}, "fk": {"q", "directions"},
                  "errors": {"q", "directions"}, "ik": {"tcps", "tools"}}
METHODS = {"compensate": (mtacc.Machine.compensate_program, mtacc.Machine.compensation_tables), "deviation": mtacc.Machine.deviation,
           "decompose": mtacc.Machine.decompose, "simulate motion": mtacc.Machine.simulate_motion,
           "evaluate": (mtacc.Machine.evaluate_ballbar, mtacc.Machine.evaluate_rtest), "plate": mtacc.Machine.compare_plate,
           "artefact": mtacc.Machine.evaluate_artefact, "simulate artefact": mtacc.Machine.simulate_artefact,
           "positioning": mtacc.positioning, "dynamics modes": mtacc.Structure.modes, "dynamics frf": mtacc.Structure.frf,
           "dynamics accel": mtacc.Structure.acceleration_response, "dynamics map": mtacc.Structure.map,
           "simulate ballbar": mtacc.Machine.simulate_ballbar, "simulate rtest": mtacc.Machine.simulate_rtest,
           "simulate plan": mtacc.Machine.simulate, "simulate plate": mtacc.Machine.simulate_plate,
           "simulate component": mtacc.Machine.simulate_component, "sensitivity": mtacc.Machine.sensitivity,
           "check": mtacc.Machine.check, "fk": mtacc.Machine.fk, "errors": mtacc.Machine.tcp_errors,
           "ik": (mtacc.Machine.ik, mtacc.Machine.ik_path), "report": report.build_report,
           "budget": mtacc.Machine.budget, "stiffness": mtacc.Machine.stiffness, "identify": mtacc.Machine.identify, "observability": mtacc.Machine.observability, "drift": mtacc.drift_test,
           "cubic-identify": mtacc.Machine.cubic_identify, "cone": mtacc.Machine.cone,
           "cubic": mtacc.Machine.cubic, "fit": mtacc.Machine.fit_component,
           "plate-identify": mtacc.Machine.identify_plates, "squareness": mtacc.squareness, "yry": mtacc.yry,
           "multitasking": mtacc.multitasking, "rotary-tests": mtacc.Machine.rotary_tests,
           "acceptance": mtacc.Machine.acceptance, "design": mtacc.Machine.design}


def cli_keys(cli, command):
    text = subprocess.run([cli, *command.split(), "--help"], capture_output=True, text=True, check=True).stdout
    keys = set()
    for line in text.splitlines():
        names = re.match(r"^  (-\S+)", line)
        if not names:
            continue
        longs = [n for n in names.group(1).split(",") if n.startswith("--")]
        if longs:
            keys.add(longs[0][2:].replace("-", "_"))
    positional = re.search(r"^Usage: \S+ " + re.escape(command) + r" \[OPTIONS\] (.*)$", text, flags=re.M)
    # "machine data", or "machine [files...]" for a positional that takes several
    keys |= {re.sub(r"[\[\]]|\.\.\.", "", word) for word in positional.group(1).split()} if positional else set()
    return keys


def test_every_schema_has_a_python_method():
    assert set(_mtacc.option_schema_workflows()) == set(METHODS)


def test_every_command_has_a_schema(cli):
    # Each command of `mtacc --help`, a command with subcommands by each of them.
    def commands(*path):
        text = subprocess.run([cli, *path, "--help"], capture_output=True, text=True, check=True).stdout
        if "Subcommands:" not in text:
            return [" ".join(path)]
        names = re.findall(r"^  ([a-z][a-z0-9-]*)", text.split("Subcommands:")[1], flags=re.M)
        return [c for name in names for c in commands(*path, name)]
    assert set(commands()) == set(_mtacc.option_schema_workflows())


@pytest.mark.parametrize("workflow", sorted(METHODS))
def test_cli_flags_python_keywords_and_schema_keys_agree(cli, workflow):
    schema = set(_mtacc.option_keys(workflow))
    assert cli_keys(cli, workflow) - (CLI_ONLY - schema) - BOTH_FRONT_ENDS == schema
    methods = METHODS[workflow] if isinstance(METHODS[workflow], tuple) else (METHODS[workflow],)
    # A key that is a Python keyword ("from") is written with a trailing underscore (PEP 8).
    python = {p.removesuffix("_") for m in methods for p in inspect.signature(m).parameters} - {"self"} - BOTH_FRONT_ENDS - PYTHON_ONLY
    python -= PYTHON_ONLY_OF.get(workflow, set())
    assert python == schema - CLI_ONLY_OF.get(workflow, set())


def test_cli_keys_are_read_from_the_help(cli):
    # The parser above must see flags, aliases and positionals, or the agreement is empty talk.
    keys = cli_keys(cli, "identify")
    assert {"machine", "parameters", "robust_scale", "from_nominal", "errors_out", "json", "output"} <= keys
    assert "params" not in keys
