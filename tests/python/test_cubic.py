"""`mtacc cubic` and `Machine.cubic`: the same numbers from the CLI and the API, the files other
software opens (NPY, PLY, STL, PNG, SVG, G-code), and the round trip simulate -> zone results ->
identify."""
import json
import struct
import subprocess

import numpy as np
import pytest

import mtacc
from mtacc import plots

TABLE5 = ("errors:\n  dxBY: 14.6 um\n  dyBY: -8.9 um\n  dzBY: -14.2 um\n  alphaBY: -0.0023 deg\n  betaBY: 0.0029 deg\n"
          "  gammaBY: -0.00002 deg\n  alphaCB: -0.00017 deg\n  dxCB: 9.4 um\n")


@pytest.fixture(scope="module")
def table5(tmp_path_factory):
    path = tmp_path_factory.mktemp("cubic") / "table5.yaml"
    path.write_text(TABLE5)
    return str(path)


def test_cli_and_api_alike_and_files_open(cli, table5, tmp_path):
    files = {k: tmp_path / f"cubic.{k}" for k in ["nc", "csv", "npy", "ply", "stl", "png", "svg"]}
    zones = tmp_path / "zones.csv"
    out = subprocess.run([cli, "cubic", "tilting-table", "--errors", table5, "--alignment", "machine", "--grid", "0.05",
                          "--gcode", str(files["nc"]), "--cl", str(files["csv"]), "--heights", str(files["npy"]),
                          "--surface", str(files["ply"]), "--map", str(files["svg"]), "--zones-out", str(zones), "--json"],
                         check=True, capture_output=True, text=True)
    data = json.loads(out.stdout)
    api = mtacc.Machine("tilting-table", table5, alignment="machine").cubic(grid=0.05)
    for a, b in zip(data["zones"], api["zones"]):
        assert a["name"] == b["name"] and a["measured"]["mean_um"] == pytest.approx(b["measured"]["mean_um"], abs=1e-12)
    # Seed 001 §9.1 (extraction): zone II-1 of Table 5 with M_WC, -5.398 um.
    assert data["zones"][1]["deviation"]["mean_um"] == pytest.approx(-5.398, abs=0.005)
    heights = np.load(files["npy"])
    assert heights.dtype == np.float32 and heights.shape == (960, 960)
    assert np.allclose(heights * 1e3, api["heights_um"], atol=1e-6)
    ply = files["ply"].read_bytes()
    assert ply.startswith(b"ply\nformat binary_little_endian 1.0\n") and b"element vertex 921600\n" in ply
    assert files["svg"].read_text().startswith("<svg") and "data:image/png;base64," in files["svg"].read_text()
    subprocess.run([cli, "cubic", "tilting-table", "--grid", "0.5", "--surface", str(files["stl"]), "--map", str(files["png"])],
                   check=True, capture_output=True)
    stl = files["stl"].read_bytes()
    triangles = struct.unpack("<I", stl[80:84])[0]
    assert triangles == 2 * 95 * 95 and len(stl) == 84 + 50 * triangles
    assert files["png"].read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    program = files["nc"].read_text()
    assert program.count("; zone ") == 9 and "B30.0000 C225.0000" in program and program.rstrip().endswith("M30")
    assert files["csv"].read_text().startswith("zone,x,y,z,i,j,k\nI,")
    fit = json.loads(subprocess.run([cli, "cubic-identify", "tilting-table", "--errors", table5, "--zones", str(zones),
                                     "--params", "dxBY,betaBY", "--json"], check=True, capture_output=True, text=True).stdout)
    # Table 5's dxBY and betaBY back, as ISO values (X0B = -dxBY, B0B = -betaBY = -50.61 urad), within
    # what the 50 um cells' scallop sampling (0.07 um of height) allows.
    values = {e["parameter"]: e["value"] for e in fit["estimates"]}
    assert values["X0B"] == pytest.approx(-14.6, abs=0.15) and values["B0B"] == pytest.approx(-50.61, abs=1.0)
    # Python reads the same options through the same schema: the same estimates, and a key it does
    # not know is refused by name.
    machine = mtacc.Machine("tilting-table", table5)
    api_fit = machine.cubic_identify(zones, "dxBY,betaBY", threads=1)
    assert api_fit["estimates"] == fit["estimates"] and api_fit["quality"] == fit["quality"]
    with pytest.raises(mtacc.InputError, match="noise: must be from 1 nm to 1 mm"):
        machine.cubic_identify(zones, ["dxBY"], noise="5 mm")


def test_sensitivities_and_plots():
    m = mtacc.Machine("tilting-table", alignment="machine")
    r = m.cubic(grid=0.1, sensitivities=True, sensitivity_parameters=["dxBY", "betaBY"], sensitivity_grid=0.1)
    k = {s["parameter"]: s for s in r["sensitivities"]}
    # Seed 001 extraction §7.2: dxBY gives -0.5 mm/mm in every tilted zone, with or without M_WC.
    assert [z["k"] for z in k["dxBY"]["with_alignment"][1:]] == pytest.approx([-0.5] * 8, abs=0.02)
    assert r["sensitivity_maps"]["betaBY"]["on_table"].shape == (480, 480)
    on_table = mtacc.Machine("tilting-table", alignment="table").cubic(grid=0.1)
    for fig in [plots.cubic_layout(r), plots.cubic_surface_map(r), plots.cubic_zone_bars(r, on_table),
                plots.cubic_sensitivity_maps(r)]:
        assert fig.axes
        plots.plt.close(fig)


def test_bad_input_writes_nothing(cli, tmp_path):
    nc = tmp_path / "cubic.nc"
    out = subprocess.run([cli, "cubic", "three-axis-vertical", "--gcode", str(nc)], capture_output=True, text=True)
    assert out.returncode != 0 and "cannot be machined" in out.stderr and not nc.exists()
    with pytest.raises(mtacc.InputError, match="grid"):
        mtacc.Machine("tilting-table").cubic(grid=0)


def test_python_writes_the_files_the_command_writes(cli, tmp_path):
    # One schema for both front ends: the same keys name the same files, with the same contents.
    names = {"gcode": "cubic.nc", "cl": "cl.csv", "zones_out": "zones.csv", "heights": "heights.csv"}
    by_cli, by_python = tmp_path / "cli", tmp_path / "python"
    by_cli.mkdir(), by_python.mkdir()
    flags = [arg for key, name in names.items() for arg in ("--" + key.replace("_", "-"), str(by_cli / name))]
    subprocess.run([cli, "cubic", "tilting-table", "--grid", "0.5", "--chord-tolerance", "1e-5", *flags], check=True, capture_output=True)
    mtacc.Machine("tilting-table").cubic(grid=0.5, chord_tolerance=1e-5, **{key: by_python / name for key, name in names.items()})
    for name in names.values():
        assert (by_python / name).read_text() == (by_cli / name).read_text(), name
    with pytest.raises(mtacc.InputError, match=r"map: '.*x\.txt': expected a file ending in \.svg, \.png"):
        mtacc.Machine("tilting-table").cubic(grid=0.5, map=tmp_path / "x.txt")
