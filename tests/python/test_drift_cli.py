"""`mtacc drift` and `mtacc.drift_test` on the bundled spindle drift test (ISO 230-3, seed 003),
and its report section."""
import json
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
TEST = ROOT / "data" / "thermal" / "maho-spindle-drift.csv"


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
    assert whole["hysteresis_sensor"] == "head" and heads.max() - heads[0] > 20


def test_the_report_section_plots_the_curves_and_the_hysteresis():
    import mtacc
    from mtacc import report
    section = report.drift_section(mtacc.drift_test(TEST, series_points=report.DRIFT_SERIES_POINTS))
    assert section.count("<svg") == 2
    assert "Spindle drift test: maho-spindle-drift.csv" in section
    assert all(f"<td class=\"l\">{d}</td>" in section for d in "XYZAB")
