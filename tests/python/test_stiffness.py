"""`mtacc stiffness` and `Machine.stiffness` (seed 003 finite stiffness): CLI and API alike, the load
scaling the changes, the bundled 260 kg file adding to the machine's own errors, and the plot and the
report section."""
import json
import pathlib
import re
import subprocess

import numpy as np
import pytest

import mtacc
from mtacc import plots

LOAD_FILE = pathlib.Path(__file__).resolve().parents[2] / "data" / "stiffness" / "maho-260kg.yaml"


def test_cli_json_equals_api(cli):
    out = subprocess.run([cli, "stiffness", "maho", "--errors", str(LOAD_FILE), "--load", "130", "--samples", "3", "--json"],
                         capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == mtacc.Machine("maho", errors=LOAD_FILE, load=130).stiffness(samples=3)


def test_the_load_scales_the_changes_and_the_geometric_errors_stay():
    full = mtacc.Machine("maho", errors=LOAD_FILE).stiffness(samples=3)
    half = mtacc.Machine("maho", errors=LOAD_FILE, load=130).stiffness(samples=3)
    assert full["workpiece_load_kg"] == 260 and half["workpiece_load_kg"] == 130
    for a, b in zip(full["terms"], half["terms"]):
        assert a["load_factor"] == 1 and b["load_factor"] == 0.5
        np.testing.assert_allclose(np.asarray(b["values"]), 0.5 * np.asarray(a["values"]), rtol=1e-15)
    # The geometric errors are App. D's whatever the load; the changes' TCP error halves with the
    # load to first order (second order: (30 urad)^2 x 1 m, about 1 nm).
    app_d = mtacc.Machine("maho")
    grid = app_d.working_volume_grid(3)
    assert full["largest_tcp_error"]["geometric"]["position_error_um"] == pytest.approx(np.linalg.norm(app_d.tcp_errors(grid)[:, :3], axis=1).max())
    assert half["largest_tcp_error"]["geometric"] == full["largest_tcp_error"]["geometric"]
    assert half["largest_tcp_error"]["stiffness_alone"]["position_error_um"] == pytest.approx(0.5 * full["largest_tcp_error"]["stiffness_alone"]["position_error_um"],
                                                                               abs=2e-3)


def test_a_machine_without_changes_is_told_so(cli):
    # No --errors was given, so the message does not blame it, and the page it cites exists.
    run = subprocess.run([cli, "stiffness", "maho"], capture_output=True, text=True)
    assert run.returncode != 0 and "no stiffness changes" in run.stderr and run.stderr.count("\n") == 1
    assert "--errors" not in run.stderr
    cited = re.search(r"(docs/[\w-]+\.md)", run.stderr).group(1)
    assert (pathlib.Path(__file__).resolve().parents[2] / cited).exists(), cited


def test_plot_and_report_section(cli, tmp_path):
    result = mtacc.Machine("maho", errors=LOAD_FILE).stiffness(samples=3)
    fig = plots.stiffness_changes(result)
    assert len(fig.axes) == 2  # the X-axis and the Y-axis changes
    assert len(fig.axes[1].lines) == 2 * 3 + 1  # yrx and yrz at three X positions, and the zero line
    run = subprocess.run([cli, "report", "maho", "-o", str(tmp_path), "--samples", "3", "--errors", str(LOAD_FILE), "--load", "200"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    page = (tmp_path / "maho-report.html").read_text()
    assert "Finite stiffness (the 1991 BCR report)" in page and "<b>200 kg</b>" in page


def test_the_grid_is_checked_in_python_as_on_the_command_line():
    # One schema for both: Python took any integer, and samples=100 meant 100^5 poses.
    with pytest.raises(mtacc.InputError, match="samples: must be from 2 to 12"):
        mtacc.Machine("maho", errors=LOAD_FILE).stiffness(samples=100)
