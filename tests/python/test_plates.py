"""`mtacc plate`, `mtacc simulate plate`, `Machine.compare_plate` and `Machine.simulate_plate` (seed 003
hole plates): CLI and API alike, a plate simulated with the machine's own errors leaves only the
probe noise, one simulated with another model does not, and the plot and report section."""
import hashlib
import json
import pathlib
import subprocess

import numpy as np
import pytest

import mtacc
from mtacc import plots

DATA = pathlib.Path(__file__).resolve().parents[2] / "data" / "plates"


def test_cli_json_equals_api(cli):
    out = subprocess.run([cli, "plate", "maho", str(DATA / "maho-xy-z292.csv"), "--json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == mtacc.Machine("maho").compare_plate(DATA / "maho-xy-z292.csv")


def test_residual_is_the_probe_noise(tmp_path):
    # Simulated with 0.5 um noise on each coordinate of the App. D machine: against the same model
    # the residual's RMS is that noise (less the three misalignment terms), inside the k = 2 bound;
    # against the error-free model it is the App. D deviations, beyond it.
    m = mtacc.Machine("maho")
    path = tmp_path / "xz.csv"
    m.simulate_plate(path, origin=(-350, -400, -310), axes=((1, 0, 0), (0, 0, 1)), noise="0.5 um", probe=(0.63, 0.84),
                     simulation=6.3, seed=4)
    same = m.compare_plate(path)
    assert same["residual_rms_um"] == pytest.approx(0.5, rel=0.15)
    assert same["bound_um"] == pytest.approx(np.sqrt(6.3 ** 2 + 2 * (0.7 ** 2 + 0.63 ** 2 + 0.84 ** 2)))
    assert same["beyond_bound"] == 0
    free = tmp_path / "free.yaml"
    free.write_text("errors: {}\n")
    other = mtacc.Machine("maho", errors=free).compare_plate(path)
    assert other["residual_rms_um"] > 5 * same["residual_rms_um"]


def test_plot_and_report_section(cli, tmp_path):
    fig = plots.plate_vectors(mtacc.Machine("maho").compare_plate(DATA / "maho-xy-z292.csv"))
    assert len(fig.axes) == 2
    run = subprocess.run([cli, "report", "maho", "-o", str(tmp_path), "--samples", "3", "--plate", str(DATA / "maho-xy-z292.csv")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "Hole and ball plates (the 1991 BCR report)" in (tmp_path / "maho-report.html").read_text()


def test_figures_5_2_and_5_3_of_the_bundled_model():
    # Fig. 5.2 set-up (XZ plane at Y = 250, relative to X = Z = 0): the arrow at X = 700, Z = 0 is
    # the extraction's §13 item 12 value there, -26.63 um along x, i.e. +26.63 along X's direction
    # of motion (the table moves the workpiece, seed 003 §4.2); the figure's title states the largest.
    m = mtacc.Machine("maho")
    names = m.axis_names
    q = np.zeros((2, len(names)))
    q[:, names.index("Y")] = 250
    q[1, names.index("X")] = 700
    err = m.tcp_errors(q)
    assert err[1, 0] - err[0, 0] == pytest.approx(-26.63, abs=0.01)
    fig = plots.relative_error_vectors(m, ("X", "Z"), fixed={"Y": 250}, reference={"X": 0, "Z": 0})
    arrows = fig.axes[0].collections[0]
    grid = np.asarray(arrows.get_offsets())
    k = int(np.argmin(np.hypot(grid[:, 0] - 700, grid[:, 1] - 0)))
    assert arrows.U[k] / arrows.U.max() == pytest.approx(1.0, abs=0.5) and arrows.U[k] > 0
    surface = plots.error_component_surface(m, ("X", "Z"), "Y", fixed={"Y": 250}, reference={"X": 0, "Z": 0}, samples=9)
    assert surface.axes


def test_identify_from_plates(cli, tmp_path):
    # Six plates of the Maho machine (two per plane, the second level with a 60 mm stylus), with the
    # probes' noise: the weighted residual matches that noise, the YAML loads into the machine, and
    # what six plates cannot determine is named. CLI and API give the same numbers.
    m = mtacc.Machine("maho")
    files = []
    layouts = [((-350, -455, -160), ((1, 0, 0), (0, 1, 0)), (0, 0, 0), (1.1, 0.8)),
               ((-50, -355, 140), ((1, 0, 0), (0, 1, 0)), (0, 0, 60), (1.1, 0.8)),
               ((-350, -330, -310), ((1, 0, 0), (0, 0, 1)), (0, 0, 0), (0.63, 0.84)),
               ((-50, -130, -110), ((1, 0, 0), (0, 0, 1)), (0, 60, 0), (0.63, 0.84)),
               ((-175, -455, -310), ((0, 1, 0), (0, 0, 1)), (0, 0, 0), (1.4, 7.5)),
               ((175, -355, -110), ((0, 1, 0), (0, 0, 1)), (60, 0, 0), (1.4, 7.5))]
    for k, (origin, axes, stylus, probe) in enumerate(layouts):
        path = tmp_path / f"p{k}.csv"
        m.simulate_plate(path, origin=origin, axes=axes, stylus=stylus, noise=f"{probe[0] / 2} um", probe=probe, seed=k + 1)
        files.append(str(path))
    r = m.identify_plates(files, piece=175)
    assert r["weighted"] and r["readings"] == 6 * 81 * 2
    assert r["findings"]
    assert any(not e["determined"] for e in r["estimates"])
    by_cli, by_python = tmp_path / "cli.yaml", tmp_path / "python.yaml"
    out = subprocess.run([cli, "plate-identify", "maho", *files, "--piece", "175", "--json", "--errors-out", str(by_cli)],
                         capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == r
    # The identified model written by Python (which had no errors_out) is the command's.
    m.identify_plates(files, piece=175, errors_out=by_python)
    assert dict(mtacc.Machine("maho", errors=by_python).errors) == dict(mtacc.Machine("maho", errors=by_cli).errors)
    with pytest.raises(mtacc.InputError, match="piece: a piece length from 1 to 10000 mm"):
        m.identify_plates(files, piece=0.5)
    path = tmp_path / "identified.yaml"
    path.write_text(r["yaml"])
    assert mtacc.Machine("maho", errors=path).tcp_errors(np.zeros((1, 5))).shape == (1, 6)


def test_one_plate_leaves_what_it_cannot_see_at_zero(cli, tmp_path):
    # The README's flow with one plate in the XY plane: the Z axis's pitch and straightness terms
    # have no effect on it. They used to come back as 1e289 um (their zero columns scaled by their
    # norms) and the YAML written was then refused. Every estimate is finite and of the size of the
    # machine's errors, those without effect are held at 0 with no uncertainty, and the YAML loads.
    plate = tmp_path / "plate.csv"
    subprocess.run([cli, "simulate", "plate", "maho", "--origin=-350,-455,-18mm", "--noise", "0.5um", "-o", str(plate)],
                   check=True, capture_output=True)
    yaml = tmp_path / "identified.yaml"
    out = subprocess.run([cli, "plate-identify", "maho", str(plate), "--piece", "100", "--json", "--errors-out", str(yaml)],
                         capture_output=True, text=True, check=True)
    r = json.loads(out.stdout)
    values = np.array([e["value"] for e in r["estimates"]], float)
    assert np.all(np.isfinite(values)) and np.abs(values).max() < 1000.0
    no_effect = [f.split(" has no effect")[0] for f in r["findings"] if " has no effect" in f]
    assert no_effect
    for e in r["estimates"]:
        if e["name"] in no_effect:
            assert e["value"] == 0.0 and e["uncertainty"] is None and not e["determined"]
        if not e["determined"]:
            assert e["uncertainty"] is None
    check = subprocess.run([cli, "check", "maho", "--errors", str(yaml)], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr
    # The model written is the one identified, with its record: the plate's hash, the estimates
    # (undetermined ones without an uncertainty).
    text = yaml.read_text()
    assert hashlib.sha256(plate.read_bytes()).hexdigest() in text and 'by: "mtacc ' in text
    assert text.count("standard_uncertainty: null") == sum(not e["determined"] for e in r["estimates"])


def test_the_written_layout_reads_back_to_the_last_digit(tmp_path):
    # The header of a simulated plate states the layout it was simulated with; at 6 significant
    # digits a stylus of 60.0001234 mm came back as 60.0001.
    path = tmp_path / "plate.csv"
    mtacc.Machine("maho").simulate_plate(path, origin=(-300.1234567, -455, -160), stylus=(0.1234567, 0, 60.0001234))
    header = dict(line[2:].split(": ", 1) for line in path.read_text().splitlines() if line.startswith("# "))

    def numbers(key):
        return [float(x) for x in header[key].removesuffix(" mm").replace("/", ",").split(",")]

    assert numbers("stylus") == [0.1234567, 0.0, 60.0001234]
    assert numbers("origin") == [-300.1234567, -455.0, -160.0]
    assert numbers("axes") == [1.0, 0.0, 0.0, 0.0, 1.0, 0.0]


def test_cli_and_python_write_the_same_plate_with_a_pose(cli, tmp_path):
    # One layout reader behind both front ends: the same options give the same file, the pose of
    # the axes that stay included (Python had no `pose` before the two were read in one place).
    by_cli, by_python = tmp_path / "cli.csv", tmp_path / "python.csv"
    run = subprocess.run([cli, "simulate", "plate", "maho", "--origin=-350,-455,-160mm", "--pose", "C=10", "--probe", "1.1, 0.8 um",
                          "--noise", "0.5um", "--seed", "3", "--json", "-o", str(by_cli)], capture_output=True, text=True, check=True)
    assert json.loads(run.stdout) == {"output": str(by_cli), "features": 81}
    mtacc.Machine("maho").simulate_plate(by_python, origin=(-350, -455, -160), pose={"C": 10}, probe=(1.1, 0.8), noise="0.5 um", seed=3)
    assert by_cli.read_text() == by_python.read_text()
    assert "# pose: " in by_cli.read_text()
    with pytest.raises(mtacc.InputError, match="origin"):
        mtacc.Machine("maho").simulate_plate(tmp_path / "bad.csv", origin=(-350, "x", -160))
    bad = subprocess.run([cli, "simulate", "plate", "maho", "--origin=-350,x,-160mm", "-o", str(tmp_path / "bad.csv")],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.startswith("mtacc: error: --origin:")
