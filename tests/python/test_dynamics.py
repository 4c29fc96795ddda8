"""Structural dynamics through the Python module and the CLI: the same numbers."""
import json
import os
import subprocess

import numpy as np
import pytest

import mtacc

CLI = os.environ.get("MTACC_CLI", "mtacc")


def cli_json(*args):
    return json.loads(subprocess.run([CLI, "dynamics", *args, "--json"], capture_output=True, text=True, check=True).stdout)


def test_acceleration_response_matches_cli():
    s = mtacc.Structure("tzyx-arm-y")
    api = s.acceleration_response(at={"Y": 400, "Z": -300})
    cli = cli_json("accel", "tzyx-arm-y", "--at", "Y=400,Z=-300")["response_um_per_g"]
    assert cli == api


def test_modes_and_frf_match_cli(as_json):
    s = mtacc.Structure("tzyx-arm-x")
    modes = s.modes(count=5)
    assert modes["modes"][0]["shape"].shape == (len(modes["dofs"]),) == (6 * len(s.bodies),)
    assert modes["dofs"][:2] == ["base.x", "base.y"]
    del modes["dofs"]
    assert cli_json("modes", "tzyx-arm-x", "--count", "5") == as_json(modes)
    f = np.arange(0.0, 201.0, 5.0)
    h = s.frf(f, method="direct")
    cli = cli_json("frf", "tzyx-arm-x", "--method", "direct", "--step", "5")
    assert [r["magnitude_um_per_n"]["Hxy"] for r in cli["frf"]] == pytest.approx(np.abs(h[:, 0, 1]), rel=1e-12)
    # At 0 Hz the FRF is the static compliance.
    assert np.allclose(h[0].real, np.array(cli["static_compliance_um_per_n"]), rtol=1e-9)


def test_bad_structure_raises(tmp_path):
    bad = tmp_path / "massless.yaml"
    bad.write_text("bodies:\n  - {name: b, inertia: [1, 1, 1, 0, 0, 0]}\nelements: []\ntcp: {body: b, point: [0 mm, 0 mm, 0 mm]}\n")
    with pytest.raises(mtacc.InputError, match=r"massless.yaml:2: bodies\[0\].mass: body 'b' has no mass"):
        mtacc.Structure(str(bad))
