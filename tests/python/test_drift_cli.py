"""`mtacc drift` and `mtacc.drift_test` on the bundled drift tests (ISO 230-3, seed 003): the
spindle's, the environmental variation's and a Z axis's; and the report section."""
import json
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEST = ROOT / "data" / "thermal" / "maho-spindle-drift.csv"
ENVIRONMENT = ROOT / "data" / "thermal" / "maho-environmental-variation.csv"
Z_AXIS = ROOT / "data" / "thermal" / "z-axis-drift.csv"


def test_the_module_gives_what_the_command_gives(cli):
    import mtacc
    from_cli = json.loads(subprocess.run([cli, "drift", str(TEST), "--json"], check=True, capture_output=True, text=True).stdout)
    assert mtacc.drift_test(TEST) == from_cli
    y = from_cli["directions"][1]
    assert y["direction"] == "Y" and y["unit"] == "um"
    assert sorted(s["sensor"] for s in y["model"]["sensors"]) == ["column", "head"]
    assert y["model"]["best_single_sensor_rms"] > 10 * y["model"]["cross_validated_rms"]


def test_the_series_are_every_kth_sample_and_the_prediction_is_the_model(cli):
    import mtacc
    whole = mtacc.drift_test(TEST, series_points=10 ** 6)
    sampled = mtacc.drift_test(TEST, series_points=500)
    assert whole["series"]["stride"] == 1 and len(whole["series"]["time_s"]) == whole["samples"]
    assert sampled["series"]["time_s"] == whole["series"]["time_s"][::sampled["series"]["stride"]]
    heads = np.array(whole["series"]["temperatures_C"]["head"])
    for d in whole["directions"]:
        drift = np.array(d["series"])
        assert drift[0] == 0 and np.max(np.abs(drift)) == pytest.approx(abs(d["largest"]), rel=1e-12)
        assert np.ptp(drift) == pytest.approx(d["range"], rel=1e-12)
        # The prediction is offset + sum of coefficient x (T - T at the start) over the chosen sensors.
        model = d["model"]
        predicted = model["offset"] + sum(s["coefficient_per_K"] * (np.array(whole["series"]["temperatures_C"][s["sensor"]]) - s["reference_C"])
                                          for s in model["sensors"])
        assert np.allclose(d["predicted"], predicted, rtol=0, atol=1e-9 * np.max(np.abs(predicted)))
        assert np.sqrt(np.mean((drift - d["predicted"]) ** 2)) == pytest.approx(model["residual_rms"], rel=1e-9)
        # One standard deviation of a new reading: the residual's and the fit's, the fit's small
        # beside it over 1680 samples; about 95 % of the readings lie within two.
        sigma = np.array(d["predicted_sigma"])
        assert np.all(sigma >= model["residual_sigma"]) and np.all(sigma < 1.2 * model["residual_sigma"])
        assert 0.93 < np.mean(np.abs(drift - d["predicted"]) <= 2 * sigma) < 0.97
    assert whole["hysteresis_sensor"] == "head" and heads.max() - heads[0] > 20


def test_the_report_section_plots_the_curves_and_the_hysteresis():
    import mtacc
    from mtacc import report
    section = report.drift_section(mtacc.drift_test(TEST, series_points=report.DRIFT_SERIES_POINTS))
    assert section.count("<svg") == 2
    assert "Drift test: maho-spindle-drift.csv</h2><p>Spindle thermal drift (ISO 230-3)" in section
    assert all(f"<td class=\"l\">{d}</td>" in section for d in "XYZAB")


def test_a_drift_read_along_an_axis_is_predicted_with_coefficients_linear_in_its_position(cli):
    import mtacc
    from_cli = json.loads(subprocess.run([cli, "drift", str(Z_AXIS), "--json", "--position", "Z"], check=True, capture_output=True,
                                         text=True).stdout)
    assert mtacc.drift_test(Z_AXIS) == from_cli  # Z, the one axis that moves, by default
    assert from_cli["test"] == "linear axis thermal drift (ISO 230-3)" and from_cli["position_axis"] == "Z"
    whole = mtacc.drift_test(Z_AXIS, series_points=10 ** 6)
    z = np.array(whole["series"]["position_mm"])
    assert sorted(set(z)) == [-400, -200, 0]
    for d in whole["directions"]:
        m = d["model"]
        predicted = m["offset"] + m["offset_per_mm"] * z + sum(
            (s["coefficient_per_K"] + s["coefficient_per_K_per_mm"] * z) * (np.array(whole["series"]["temperatures_C"][s["sensor"]]) - s["reference_C"])
            for s in m["sensors"])
        assert np.allclose(d["predicted"], predicted, rtol=0, atol=1e-9 * np.max(np.abs(predicted)))
    head = next(s for s in whole["directions"][1]["model"]["sensors"] if s["sensor"] == "head")
    assert abs(head["coefficient_per_K_per_mm"] - 0.005) < 3 * head["standard_error_per_K_per_mm"]  # um/K per mm, as injected


def test_the_machine_at_rest_is_the_environmental_variation_test(cli):
    import mtacc
    from mtacc import report
    out = subprocess.run([cli, "drift", str(ENVIRONMENT)], check=True, capture_output=True, text=True).stdout
    assert "environmental temperature variation (ISO 230-3 ETVE), the machine at rest" in out
    assert "ETVE: the range of each direction's drift over the test" in out
    section = report.drift_section(mtacc.drift_test(ENVIRONMENT, series_points=report.DRIFT_SERIES_POINTS))
    assert "range (ETVE)" in section and "its environmental temperature variation error (ETVE)" in section
