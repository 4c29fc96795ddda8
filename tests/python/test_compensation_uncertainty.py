"""Issue 45, part 4: the compensated machine's uncertainty. An identified model's covariance,
carried to the TCP by the parameter Jacobian (Machine.tcp_uncertainty, deviation's k = 2 column),
bounds what compensating with the model leaves on the true machine: over noise draws of the
measurement, the true residual lies within the k = 2 bound at 95 % of the positions."""
import numpy as np
import pytest

import mtacc

NOISE = "0.3 um"
DRAWS = 200
CASES = {
    "tilting-table": "tilting-table-rtest",
    "double-pivot-head": "double-pivot-rtest",
}


def poses_within_travel(machine, count, seed):
    rng = np.random.default_rng(seed)
    travel = {a["name"]: a["travel"] or [-180, 180] for a in machine.axes}
    return np.array([rng.uniform(*travel[name], count) for name in machine.axis_names]).T


@pytest.mark.parametrize("name", CASES)
def test_the_k2_bound_holds_the_residual_at_95_percent_of_the_positions(tmp_path, name):
    plan = CASES[name]
    estimates = mtacc.Machine(name, errors={}).observability(plan, noise=NOISE)["prediction"]["estimates"]
    parameters = [e["parameter"] for e in estimates if not e["setup"]]
    rng = np.random.default_rng(5)
    length = lambda p: p[0] in "XYZ" or p[:2] in ("EX", "EY", "EZ")
    truth = {p: f"{rng.uniform(-10, 10):.3f} {'um' if length(p) else 'urad'}" for p in parameters}
    machine = mtacc.Machine(name, errors=truth)
    q = poses_within_travel(machine, 40, 7)
    true_errors = machine.tcp_errors(q)[:, :3]
    inside = []
    for seed in range(1, DRAWS + 1):
        folder = tmp_path / f"draw{seed}"
        machine.simulate(plan, noise=NOISE, seed=seed, output=folder)
        model_file = folder / "identified.yaml"
        machine.identify(sorted(folder.glob("*.csv")), plan=plan, errors_out=model_file)
        model = mtacc.Machine(name, errors=model_file)
        residual = true_errors - model.tcp_errors(q)[:, :3]  # what compensating with the model leaves, first order
        inside.append(np.abs(residual) <= 2 * model.tcp_uncertainty(q))
    fraction = np.mean(inside)
    # A Gaussian's k = 2 interval holds 95.45 %; the pooled fraction's scatter over 200 draws is
    # about 0.5 % (the positions of one draw share its parameter errors).
    assert fraction == pytest.approx(0.9545, abs=0.02), f"{name}: {100 * fraction:.1f} % within the k = 2 bound"


def test_the_report_maps_the_uncertainty_of_an_identified_model(cli, tmp_path):
    import subprocess
    machine = mtacc.Machine("tilting-table")
    machine.simulate("tilting-table-rtest", noise=NOISE, seed=1, output=tmp_path / "runs")
    model = tmp_path / "identified.yaml"
    machine.identify(sorted((tmp_path / "runs").glob("*.csv")), plan="tilting-table-rtest", errors_out=model)
    for errors, shown in ((model, True), (None, False)):
        out = tmp_path / ("with" if shown else "without")
        args = [cli, "report", "tilting-table", "-o", str(out), "--samples", "3"] + (["--errors", str(model)] if errors else [])
        subprocess.run(args, check=True, capture_output=True)
        html = (out / "tilting-table-report.html").read_text()
        assert ("What the identified model does not know" in html) == shown
    with pytest.raises(mtacc.InputError, match="no covariance"):
        mtacc.Machine("tilting-table").tcp_uncertainty([0, 0, 0, 0, 0])
