"""`mtacc cone`: seed 000 Table 3.6 (L4202-4222) through the command, and its bad input."""
import json
import subprocess

import pytest

import mtacc


def cone(cli, *args):
    out = subprocess.run([cli, "cone", "tilting-table", "--points", "3600", *args, "--json"], check=True,
                         capture_output=True, text=True)
    return {a["axis"]: a for a in json.loads(out.stdout)["axes"]}


@pytest.mark.parametrize("centre, radius, expected", [
    ("-65,0,150", "40", {"X": 185.7, "Y": 90.0, "Z": 185.7, "B": 60.0, "C": 360.0}),    # proposed
    ("48.9,0,66.1", "44.8", {"X": 36.0, "Y": 142.6, "Z": 13.2, "B": 60.0, "C": 360.0}),  # comparison
])
def test_table_3_6(cli, centre, radius, expected):
    axes = cone(cli, "--alpha", "45", "--beta", "30", "--centre", centre, "--radius", radius)
    for name, value in expected.items():
        assert axes[name]["range"] == pytest.approx(value, abs=0.05), name  # printed to 0.1


def test_near_singular_setup_warns(cli):
    out = subprocess.run([cli, "cone", "tilting-table", "--alpha", "45", "--beta", "44.5", "--json"], check=True,
                         capture_output=True, text=True)
    data = json.loads(out.stdout)
    assert "near-singular" in data["warnings"][0]
    assert all(a["max_speed_per_s"] == a["max_speed_per_s"] for a in data["axes"])  # no NaN


def test_bad_input_and_gcode(cli, tmp_path):
    gcode = tmp_path / "cone.nc"
    out = subprocess.run([cli, "cone", "tilting-table", "--points", "3", "--gcode", str(gcode)], capture_output=True, text=True)
    assert out.returncode != 0 and "points: must be between 8 and 1000000" in out.stderr and not gcode.exists()
    out = subprocess.run([cli, "cone", "three-axis-vertical", "--gcode", str(gcode)], capture_output=True, text=True)
    assert out.returncode != 0 and "cannot be reached" in out.stderr and not gcode.exists()
    cl = tmp_path / "cone.csv"
    subprocess.run([cli, "cone", "swivel-head-table", "--preset", "swivel-head", "--gcode", str(gcode), "--cl", str(cl)],
                   check=True, capture_output=True)
    assert cl.read_text().splitlines()[0] == "phi_deg,x,y,z,i,j,k,nx,ny,nz" and len(cl.read_text().splitlines()) == 721
    lines = gcode.read_text().splitlines()
    assert lines[3].startswith("N10 G01 X") and " B" in lines[3] and " C" in lines[3] and lines[-1] == "M30"


def test_python_takes_the_same_options_and_writes_the_same_files(cli, tmp_path):
    # One schema: the CLI's flags and Python's keywords read alike, "family" and the chord
    # tolerance included (Python had neither), and the same NC program and CL data come out.
    files = {name: tmp_path / name for name in ("cli.nc", "cli.csv", "py.nc", "py.csv")}
    out = subprocess.run([cli, "cone", "swivel-head-table", "--preset", "family", "--chord-tolerance", "0.001", "--json",
                          "--gcode", str(files["cli.nc"]), "--cl", str(files["cli.csv"])], check=True, capture_output=True, text=True)
    by_cli = json.loads(out.stdout)
    by_python = mtacc.as_json(mtacc.Machine("swivel-head-table").cone(preset="family", chord_tolerance=0.001, gcode=files["py.nc"],
                                                                        cl=files["py.csv"]))
    assert by_python["cone"] == by_cli["cone"] and by_python["axes"] == by_cli["axes"]
    assert files["py.nc"].read_text() == files["cli.nc"].read_text() and files["py.csv"].read_text() == files["cli.csv"].read_text()
    with pytest.raises(mtacc.InputError, match="points: must be between 8 and 1000000"):
        mtacc.Machine("tilting-table").cone(points=3)
