"""Measured artefacts and test pieces: `mtacc artefact` and `Machine.evaluate_artefact` alike, an
artefact simulated with the machine's own errors leaving only the probe noise, the measured cone
through `cone --measured` and `Machine.cone(measured=...)`, and their figure."""
import json
import pathlib
import subprocess

import numpy as np

import mtacc
from mtacc import plots

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"


def test_artefact_cli_json_equals_api(cli):
    path = DATA / "artefacts" / "maho-ball-plate-tilted.csv"
    out = subprocess.run([cli, "artefact", "maho", str(path), "--json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == mtacc.Machine("maho").evaluate_artefact(str(path))


def test_artefact_figures():
    m = mtacc.Machine("maho")
    plate = plots.artefact_deviations(m.evaluate_artefact(str(DATA / "artefacts" / "maho-ball-plate-tilted.csv")))
    assert len(plate.axes) == 3  # the in-plane vectors, the out-of-plane colours and their colour bar
    gauge = plots.artefact_deviations(m.evaluate_artefact(str(DATA / "artefacts" / "maho-step-gauge-diagonal.csv")))
    assert len(gauge.axes[0].lines) == 6  # measured and model along u, v and w


def test_simulated_gauge_leaves_the_probe_noise(tmp_path):
    # 0.5 um on each coordinate of the App. D machine, aligned by least squares (5 of the 33
    # readings' degrees of freedom): against the same model the residual is that noise, RMS
    # 0.5 sqrt(28/33) = 0.46 um (its estimate within +-13 %, 0.2-0.8 is beyond 4 of those); against
    # the error-free machine it is the model's deviations (tens of um along the diagonal).
    m = mtacc.Machine("maho")
    layout = tmp_path / "layout.csv"
    layout.write_text((DATA / "artefacts" / "step-gauge-diagonal.csv").read_text().replace("# alignment: three-point S0, S10",
                                                                                            "# alignment: least-squares"))
    out = tmp_path / "gauge.csv"
    m.simulate_artefact(str(layout), str(out), noise="0.5 um", seed=9)
    same = m.evaluate_artefact(str(out))
    assert same["alignment"]["method"] == "least-squares"
    residual = np.array([f["residual_um"] for f in same["features"]])
    assert 0.2 < np.sqrt(np.mean(residual ** 2)) < 0.8
    nominal = mtacc.Machine("maho", errors={}).evaluate_artefact(str(out))
    assert max(abs(d["range_um"]) for d in nominal["directions"]) > 10
    assert np.max(np.abs([f["residual_um"] for f in nominal["features"]])) > 10


def test_measured_cone_through_the_api_and_its_figure():
    cone = mtacc.Machine("tilting-table").cone(preset="tilting-table", points=360,
                                               measured=str(DATA / "test-pieces" / "tilting-table-cone-measured.csv"))
    measured = cone["measured"]
    assert [s["name"] for s in measured["cone_sections"]] == ["h-5", "h+0", "h+5"]
    assert measured["comparison"]["section"] == "h+0"
    # The file's 0.3 um probing noise (0.21 um normal to a 45 degree cone) is all that separates
    # the measured form from the simulated one.
    assert measured["comparison"]["rms_difference_um"] < 0.3
    for s in measured["cone_sections"]:
        assert s["circularity_minimum_zone_um"] <= s["circularity_least_squares_um"]
    fig = plots.measured_cone_form(cone)
    assert len(fig.axes[0].lines) == 5  # the reference, two limits, measured, simulated


def test_scanned_face_goes_on_to_cubic_identify(cli, tmp_path):
    # The face `cubic --surface` writes, read back as a scan: its zones are the simulated ones
    # (to the PLY's single precision and the cells the two grids cut differently along the zone
    # edges), and the zone results it writes identify what the simulated zones identify, within a
    # tenth of the estimates' uncertainty.
    face, simulated, scanned = tmp_path / "face.ply", tmp_path / "simulated.csv", tmp_path / "scanned.csv"
    subprocess.run([cli, "cubic", "tilting-table", "--grid", "0.05", "--surface", str(face)], check=True, capture_output=True)
    out = subprocess.run([cli, "cubic", "tilting-table", "--grid", "0.05", "--scan", str(face), "--scan-zones-out", str(scanned),
                          "--zones-out", str(simulated), "--json"], check=True, capture_output=True, text=True)
    scan = json.loads(out.stdout)["scan"]
    assert scan["points"] == 960 * 960  # a vertex per cell of the 48 mm block
    assert max(abs(z["difference_um"]) for z in scan["zones"]) < 0.05
    assert max(abs(z["simulated_mean_um"]) for z in scan["zones"]) > 1

    def identified(zones):
        run = subprocess.run([cli, "cubic-identify", "tilting-table", "--zones", str(zones), "--params", "X0B,B0B", "--json"],
                             check=True, capture_output=True, text=True)
        return {e["parameter"]: e for e in json.loads(run.stdout)["estimates"]}
    from_scan, from_simulation = identified(scanned), identified(simulated)
    for name in ("X0B", "B0B"):
        assert abs(from_scan[name]["value"] - from_simulation[name]["value"]) < 0.1 * from_simulation[name]["standard_uncertainty"]
