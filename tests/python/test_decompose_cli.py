"""`mtacc simulate motion` then `mtacc decompose`: seed 004's virtual machine written to signal
files and decomposed from them, as a user runs the two commands."""
import json
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
PROGRAM = ROOT / "data" / "programs" / "seed004-capball.nc"


def run(cli, *args):
    return json.loads(subprocess.run([cli, *args, "--json"], check=True, capture_output=True, text=True).stdout)


def test_the_recorded_virtual_machine_decomposes_into_what_was_injected(cli, tmp_path):
    simulated = run(cli, "simulate", "motion", "inclined-a-table", "--program", str(PROGRAM), "--feeds", "1000,3240,10498",
                    "--structure", "wcayfxzt-compact", "--noise", "0.2um", "--kv", "40", "--feed-forward", "0.99",
                    "-o", str(tmp_path))
    assert [f["feed_mm_min"] for f in simulated["feeds"]] == [1000, 3240, 10498]
    assert simulated["ball_mm"] == pytest.approx([70, 40, 60], abs=1e-9)
    assert all(f["dynamic_max_um"][0] > 0.5 for f in simulated["feeds"])
    decomposed = run(cli, "decompose", "inclined-a-table", simulated["set"])
    tests = decomposed["tests"]
    # The command clock is 18 ms off; a pure delay also takes the servo lag (1 - 0.99) / 40 s = 0.25 ms.
    for t in tests:
        assert t["clock_offset_estimated"]
        assert t["clock_offset_ms"] == pytest.approx(18.25, abs=0.05)
    # Test k carries k times (0.4, 0.25, 0.35) um of drift, plus the mean of its dynamic error.
    assert tests[0]["drift_um"] == [0, 0, 0]
    for k, t in enumerate(tests[1:], start=1):
        assert t["drift_um"] == pytest.approx([0.4 * k, 0.25 * k, 0.35 * k], abs=0.1)
    # The reference test's dynamic error is the instrument's noise; it grows with the feed.
    assert tests[0]["dynamic_rms_um"] == pytest.approx([0.2, 0.2, 0.2], abs=0.03)
    assert tests[2]["dynamic_rms_um"][0] > 3 * tests[0]["dynamic_rms_um"][0]
    for t in tests:
        shares = t["split_shares_percent"]
        assert sum(shares[k] for k in ("contouring", "link", "motion", "drift", "dynamic")) == pytest.approx(100, abs=1e-9)
    assert decomposed["dynamic_rms_power_law"]["x"]["exponent"] > 0


def test_the_python_module_gives_what_the_commands_give(cli, tmp_path):
    import mtacc
    machine = mtacc.Machine("inclined-a-table")
    simulated = machine.simulate_motion(PROGRAM, tmp_path / "py", feeds=[1000, 5832], structure="wcayfxzt-compact")
    decomposed = machine.decompose(simulated["set"])
    assert decomposed == run(cli, "decompose", "inclined-a-table", simulated["set"])
    assert [t["feed_mm_min"] for t in decomposed["tests"]] == [1000, 5832]


def test_the_report_section_shows_every_feed(tmp_path):
    import mtacc
    from mtacc import report
    machine = mtacc.Machine("inclined-a-table")
    simulated = machine.simulate_motion(PROGRAM, tmp_path, feeds=[1000, 3240, 10498], structure="wcayfxzt-compact")
    section = report.decomposition_section(machine.decompose(simulated["set"]))
    assert "<svg" in section and "Error decomposition (seed 004)" in section
    assert all(f">{feed}</td>" in section for feed in ("1000", "3240", "10498"))
