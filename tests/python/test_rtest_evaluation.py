"""Issue 44, part 5: a single R-test run evaluated about the axis that moves (ISO 10791-6): the
displacements along X, Y, Z and their radial, axial and tangential components, checked against
what an eccentric or tilted C table does to a sphere, worked out by hand."""
import json
import subprocess

import numpy as np
import pytest

import mtacc

PLAN = """runs:
  - name: rtest-C
    sphere: {axis: C, from: 0 deg, to: 345 deg, points: 24, spheres: [[100 mm, 0 mm, 50 mm]], pose: {B: 0 deg}}
"""


def evaluate(tmp_path, errors):
    plan = tmp_path / "plan.yaml"
    plan.write_text(PLAN)
    m = mtacc.Machine("tilting-table", errors=errors)
    m.simulate(plan, output=tmp_path / "data")
    return m.evaluate_rtest(tmp_path / "data" / "rtest-C.csv")


def test_an_eccentric_table_moves_the_sphere_radially_and_tangentially(tmp_path):
    # The C line 5 um off along X: the table and the sphere shift by 5 um in the bed frame, the
    # same at every angle, so X, Y, Z do not vary while the radial and the tangential components
    # turn with the table: 5 cos and 5 sin of the angle, a range of 10 um each.
    r = evaluate(tmp_path, {"X0C": "5 um"})
    assert r["moving_axis"] == "C"
    assert np.allclose(r["range_um"], 0.0, atol=1e-6)
    about = r["about_the_axis"]
    assert about["radius_mm"] == pytest.approx(100.0, abs=1e-6)
    c = about["radial_axial_tangential_um"]
    assert about["range_um"]["radial"] == pytest.approx(10.0, rel=2e-3)
    assert about["range_um"]["tangential"] == pytest.approx(10.0, rel=2e-3)
    assert about["range_um"]["axial"] == pytest.approx(0.0, abs=1e-6)
    assert np.allclose(np.hypot(c[:, 0], c[:, 2]), 5.0, rtol=1e-6)


def test_a_tilted_table_moves_the_sphere_axially(tmp_path):
    # The C line tilted by 20 urad about X: the sphere 100 mm off the line rises and falls by
    # 100 mm x 20 urad = 2 um as the table turns (axial range 4 um); its height of 50 mm above the
    # tilt's pivot moves it by 1 um along Y, constant in the bed frame (radial and tangential
    # ranges 2 um).
    r = evaluate(tmp_path, {"A0C": "20 urad"})
    about = r["about_the_axis"]
    assert about["range_um"]["axial"] == pytest.approx(4.0, rel=2e-3)
    assert about["range_um"]["radial"] == pytest.approx(2.0, rel=2e-3)
    assert r["range_um"][2] == pytest.approx(4.0, rel=2e-3)


def test_the_command_line_evaluates_an_rtest_file(cli, tmp_path):
    r = evaluate(tmp_path, {"X0C": "5 um"})
    out = subprocess.run([cli, "evaluate", "tilting-table", str(tmp_path / "data" / "rtest-C.csv"), "--json"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["about_the_axis"]["range_um"] == pytest.approx(r["about_the_axis"]["range_um"])
