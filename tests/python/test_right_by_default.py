"""Issue 43: the Python API behaves as numpy's neighbours do and answers right by default: the
Jacobian of a batch, the errors as a mapping, copies and pickles, the exception types, the
FRF's method and the Monte Carlo's drawn values."""
import copy
import math
import pickle

import numpy as np
import pytest

import mtacc
from mtacc import plots

POSES = np.array([[0, 0, 0, 0, 0], [100, -50, 120, -30, 45], [-200, 80, 50, -60, 200]], float)


def test_jacobian_of_a_batch_is_one_per_pose():
    m = mtacc.Machine("tilting-table")
    names, J = m.jacobian(POSES)
    assert J.shape == (3, 6, len(names))
    for k, q in enumerate(POSES):
        single_names, single = m.jacobian(q)
        assert single_names == names and single.shape == (6, len(names))
        assert np.array_equal(single, J[k])
    with pytest.raises(mtacc.InputError, match="beyond travel"):
        m.jacobian([900, 0, 0, 0, 0])


def test_errors_honour_the_mapping_contract():
    m = mtacc.Machine("tilting-table")
    e = m.errors
    assert "X0Q" not in e and e.get("X0Q") is None and e.get("X0Q", 1.5) == 1.5
    with pytest.raises(KeyError):
        e["X0Q"]
    assert "X0B" in e and e["X0B"] == pytest.approx(6e-3)
    del e["X0B"]
    assert "X0B" not in e and e["X0B"] == 0.0 and e.get("X0B") is None
    assert len(e) == len(list(e)) == len(dict(e)) == len(e.keys())
    assert all(name in e for name in e) and all(e[name] != 0.0 for name in e)
    e["X0B"] = "6 um"
    assert "X0B" in e and e["X0B"] == pytest.approx(6e-3)
    # One rule for bare numbers: the unit the value reads back in (mm here), a string its own.
    e["Y0C"] = 0.004
    assert e["Y0C"] == pytest.approx(0.004) and e.unit("Y0C") == "mm"
    with pytest.raises(mtacc.InputError):
        e["Y0C"] = "4"


def test_machines_copy_and_pickle_independently(tmp_path):
    m = mtacc.Machine("tilting-table")
    m.errors["X0C"] = "7 um"
    for other in (copy.copy(m), copy.deepcopy(m), pickle.loads(pickle.dumps(m))):
        assert dict(other.errors) == pytest.approx(dict(m.errors))
        assert np.array_equal(other.tcp_errors(POSES), m.tcp_errors(POSES))
        other.errors["X0C"] = "1 um"
        assert m.errors["X0C"] == pytest.approx(7e-3)
    shown = repr(mtacc.Machine("tilting-table", errors={"X0C": "7 um", "A0B": "20 urad"}))
    assert "Tilting rotary table" in shown and "2 non-zero errors" in shown and "X0C=7 um" in shown and "A0B=20 urad" in shown
    # errors= takes a dict as well as a file: the same machine either way.
    path = tmp_path / "e.yaml"
    path.write_text("errors:\n  X0C: 7 um\n  A0B: 20 urad\n")
    from_file = mtacc.Machine("tilting-table", errors=path)
    from_dict = mtacc.Machine("tilting-table", errors={"X0C": "7 um", "A0B": 20e-6})
    assert np.array_equal(from_file.tcp_errors(POSES), from_dict.tcp_errors(POSES))


def test_exception_types():
    m = mtacc.Machine("tilting-table")
    with pytest.raises(mtacc.UnreachablePose, match="no rotary axis"):
        mtacc.Machine("three-axis-vertical").ik([0, 0, 100], tool=(1, 0, 0))
    assert issubclass(mtacc.UnreachablePose, mtacc.InputError)
    with pytest.raises(mtacc.InputError, match="direction"):
        m.sensitivity_coefficient(POSES[1], "X0C", "1 um", (0, 0, 0))
    with pytest.raises(mtacc.InputError, match="one pose"):
        m.sensitivity_coefficient(POSES, "X0C", "1 um", (0, 0, 1))
    s = mtacc.Structure("tzyx-arm-x")
    for bad in ([float("nan")], [-5.0]):
        with pytest.raises(mtacc.InputError, match="frequencies"):
            s.frf(bad)


def test_frf_default_is_the_exact_solve_where_the_damping_couples_the_modes():
    s = mtacc.Structure("tzyx-arm-x")
    f = np.arange(1.0, 201.0)
    at = {"Y": 400, "Z": -300}
    assert s.frf_method(at)[0] == "direct"
    assert np.array_equal(s.frf(f, at=at), s.frf(f, at=at, method="direct"))
    peak_modal = np.abs(s.frf(f, at=at, method="modal")[:, 0, 0]).max()
    assert peak_modal < 0.8 * np.abs(s.frf(f, at=at)[:, 0, 0]).max()


def test_monte_carlo_returns_its_drawn_values(tmp_path):
    # One limit: the form error is linear in the drawn value, so the regression of the form
    # errors on the drawn values recovers the single-error sensitivity of that error.
    m = mtacc.Machine("tilting-table", errors={})
    mc = m.cone(monte_carlo=30, limits={"X0B": ("-10 um", "10 um")})["monte_carlo"]
    drawn = np.asarray(mc["drawn"]["values"])
    assert mc["drawn"]["names"] == ["X0B"] and mc["drawn"]["units"] == ["um"] and drawn.shape == (30, 1)
    assert np.all(np.abs(drawn) <= 10.0)
    form = np.asarray(mc["form_errors_um"])
    slope = np.sum(form * np.abs(drawn[:, 0])) / np.sum(drawn[:, 0] ** 2)
    m.errors["X0B"] = "10 um"
    single = m.cone(single_errors=True)["single_errors"][0]
    assert single["error"] == "X0B"
    assert slope == pytest.approx(single["form_error_um"] / 10.0, rel=0.1)
    # The same limits as a file give the same draws; a reversal goes by its parameter name.
    limits = tmp_path / "limits.yaml"
    limits.write_text("limits:\n  X0B: [-10 um, 10 um]\n")
    assert np.array_equal(m.cone(monte_carlo=30, limits=limits)["monte_carlo"]["drawn"]["values"], drawn)
    by_name = m.cone(monte_carlo=5, limits={"EXX.rev": ("0 um", "4 um")})["monte_carlo"]
    as_written = m.cone(monte_carlo=5, limits={"EXX.hyst": ("0 um", "4 um")})["monte_carlo"]
    assert np.array_equal(by_name["form_errors_um"], as_written["form_errors_um"])
    assert np.all(by_name["form_errors_um"] > 0)
    with pytest.raises(mtacc.InputError, match=r"limits\.X0B"):
        m.cone(monte_carlo=5, limits={"X0B": (-10, 10)})
    with pytest.raises(mtacc.InputError, match=r"limits\.EXX\.c1"):
        m.cone(monte_carlo=5, limits={"EXX.c1": ("-1 um", "1 um")})
    # The bundled table (every limit at once): finite, each sample's values within its limits.
    full = mtacc.Machine("tilting-table").cone(preset="nas979", monte_carlo=10)["monte_carlo"]
    assert all(math.isfinite(v) and v < 100 for v in full["form_errors_um"])
    assert np.asarray(full["drawn"]["values"]).shape == (10, len(full["drawn"]["names"]))
    assert any("Z does not move" in n for n in full["notes"])


def test_maps_return_ndarrays_in_a_documented_order():
    s = mtacc.Structure("tzyx-arm-x")
    r = s.map("Cxx", axes=("Y", "Z"), grid=(3, 4))
    assert r["values"].shape == (3, 4) and r["a_mm"].shape == (3,) and r["b_mm"].shape == (4,)
    # values[i, k] at a_mm[i], b_mm[k]: the corner is the compliance at those positions.
    corner = s.map("Cxx", axes=("Y", "Z"), grid=(2, 2), at={"X": 0})["values"][1, 0]
    assert r["values"][2, 0] == pytest.approx(corner, rel=1e-12)
    # The CLI's text is the same grid; a grid of fractional positions is refused, not rounded.
    assert np.array_equal(s.map("Cxx", axes=("Y", "Z"), grid="2x2", at={"X": 0})["values"], s.map("Cxx", axes=("Y", "Z"), grid=(2, 2), at={"X": 0})["values"])
    with pytest.raises(mtacc.InputError, match=r"grid: expected two whole numbers"):
        s.map(grid=(2.5, 3))
    m = mtacc.Machine("tilting-table")
    fig, data = plots.volumetric_error_map(m, ("X", "Y"), samples=5, return_data=True)
    assert data["errors"].shape == (5, 5, 6) and data["magnitude"].shape == (5, 5)
    assert np.allclose(data["magnitude"], np.linalg.norm(data["errors"][..., :3], axis=2))
    with pytest.raises(mtacc.InputError, match="'Q' is not an axis"):
        plots.volumetric_error_map(m, ("X", "Y"), fixed={"Q": 3})


def test_observability_returns_the_singular_vectors():
    r = mtacc.Machine("tilting-table").observability("tilting-table-rtest")
    p = len(r["names"])
    vh = r["singular_vectors"]
    assert r["singular_values"].shape == (p,) and vh.shape[1] == p
    assert np.allclose(vh @ vh.T, np.eye(vh.shape[0]), atol=1e-12)
    # A parameter the plan does not see has no share in any direction.
    blind = mtacc.Machine("tilting-table").observability("tilting-table-rtest", parameters=["X0B", "C0C1"])
    assert "C0C1 has no effect" in " ".join(blind["findings"])
    assert np.all(blind["singular_vectors"][:, blind["names"].index("C0C1")] == 0.0)


def test_results_serialise_as_the_command_line_prints_them():
    import json
    m = mtacc.Machine("tilting-table")
    cubic = m.cubic(grid=0.2)
    assert isinstance(cubic["heights_um"], np.ndarray)
    text = json.dumps(mtacc.as_json(cubic))
    assert json.loads(text)["heights_um"][0][0] == pytest.approx(cubic["heights_um"][0, 0])
    h = mtacc.Structure("tzyx-arm-x").frf([50.0])
    assert mtacc.as_json({"h": h})["h"][0][0][0] == [h[0, 0, 0].real, h[0, 0, 0].imag]
