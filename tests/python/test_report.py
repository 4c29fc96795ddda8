"""The HTML report: self-contained, every figure rendered in headless Chromium, no errors."""
import pathlib
import re
import shutil
import subprocess

import pytest

import mtacc
from mtacc import plots, report

CHROMIUM = shutil.which("chromium") or "/usr/bin/chromium"
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--virtual-time-budget=10000"]


@pytest.fixture(scope="module")
def tilting_table_report(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    return pathlib.Path(report.build_report("tilting-table", str(out), plan="tilting-table-rtest", structure="tzyx-arm-x",
                                            compare="tzyx-arm-y"))


# The two tests of the full report share it: one worker builds it once (pytest-xdist's loadgroup).
@pytest.mark.xdist_group("tilting-table-report")
def test_report_is_self_contained(tilting_table_report):
    text = tilting_table_report.read_text()
    assert text.count('<figure class="plot">') >= 15
    assert "Cone-frustum test piece (Bossoni 2009)" in text and "Monte Carlo:" in text
    assert "Measurement and identification" in text and "Identified parameters" in text
    assert "<b>Simulated data:</b>" in text  # no --data: said plainly
    assert "Structural dynamics" in text and "First mode shape" in text
    assert "After compensation" in text and "TCP position error left by each table" in text
    assert not re.search(r'(src|href)\s*=\s*["\']?(https?:)?//', text)
    assert "<link" not in text and "@import" not in text and "url(http" not in text


def rendered_in_chromium(page, profile):
    """(figures expected, figures rendered, script errors) of the page in headless Chromium."""
    dom = subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--dump-dom", page.as_uri()],
                         capture_output=True, text=True, timeout=120).stdout
    body = re.search(r"<body([^>]*)>", dom).group(1)
    return (int(re.search(r'data-figures-expected="(\d+)"', body).group(1)),
            int(re.search(r'data-figures-rendered="(\d+)"', body).group(1)),
            re.search(r'data-errors="([^"]*)"', body).group(1))


@pytest.mark.xdist_group("tilting-table-report")
def test_report_renders_in_headless_chromium(tilting_table_report, tmp_path, artifacts):
    profile = tmp_path / "chromium-profile"
    url = tilting_table_report.as_uri()
    expected, rendered, errors = rendered_in_chromium(tilting_table_report, profile)
    assert expected >= 15
    assert rendered == expected
    assert errors == ""
    shot = artifacts / "report-tilting-table.png"
    subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", "--hide-scrollbars", "--window-size=1200,6000",
                    f"--screenshot={shot}", url], capture_output=True, timeout=120, check=True)
    assert shot.stat().st_size > 10000


def test_report_identifies_from_measured_files(tmp_path, artifacts):
    # Issue 44: files measured on a machine with an error the plan's parameters do not model (a
    # second-harmonic radial motion of B, seen only while B turns): the report identifies from
    # the files, the goodness of fit fails, and the residuals point at the runs that turn B.
    truth = mtacc.Machine("tilting-table")
    truth.errors["EXB.h2c"] = "10 um"
    truth.simulate("tilting-table-rtest", noise="0.5 um", seed=2, output=tmp_path / "data")
    files = sorted((tmp_path / "data").glob("*.csv"))
    page = pathlib.Path(report.build_report("tilting-table", str(tmp_path / "out"), samples=3, plan="tilting-table-rtest",
                                            data=files))
    text = page.read_text()
    assert "<b>Simulated data:</b>" not in text and f"{len(files)} measured runs" in text
    assert re.search(r"χ² = [\d.]+ for \d+ degrees of freedom, p = [\d.e-]+: <b>fails</b>", text)
    # The residual table: run, instrument, RMS, largest, stated noise.
    runs = re.findall(r'<tr><td class="l">([\w-]+)</td><td class="">(?:rtest|ballbar)</td><td class="">(\d+\.\d{3})</td>'
                      r'<td class="">\d+\.\d{3}</td><td class="">[^<]*</td></tr>', text)
    assert len(runs) == len(files)
    worst = sorted(runs, key=lambda r: -float(r[1]))[:2]
    assert {name for name, _ in worst} == {"rtest-B-1", "rtest-B-2"}
    assert "Residuals of each run" in text and "The plan</h3>" in text and "as the machine will move" in text
    model = tmp_path / "out" / "tilting-table-identified.yaml"
    assert "identification:" in model.read_text()
    assert mtacc.Machine("tilting-table", errors=model).errors  # reads back as an errors file
    expected, rendered, errors = rendered_in_chromium(page, tmp_path / "chromium-profile")
    assert rendered == expected and errors == ""
    with pytest.raises(mtacc.InputError, match="data: measured files need --plan"):
        report.build_report("tilting-table", str(tmp_path / "none"), data=files)


@pytest.mark.parametrize("name", ["three-axis-vertical", "maho", "inclined-a-table", "multitasking-b-c",
                                  "swivel-head-table", "double-pivot-head"])
def test_report_for_other_machines(tmp_path, name):
    # Every topology's sections build; the budget grid's density is not what is checked here.
    path = pathlib.Path(report.build_report(name, str(tmp_path), samples=3))
    assert path.exists() and path.stat().st_size > 10000


def test_plot_functions_return_figures():
    m = mtacc.Machine("swivel-head-table")
    figs = [plots.chain_schematic(m), plots.budget_bar_chart(m.budget(samples=3)),
            plots.volumetric_error_map(m, ("X", "Z"), samples=11),
            plots.polar_deviation([0, 90, 180, 270, 360], [1, -1, 2, 0, 1])]
    q = [[0, 0, 100, b, c] for b, c in zip(range(-30, 31, 10), range(0, 70, 10))]
    m.errors["X0C"] = "5 um"
    figs.append(plots.sensitivity_along_path(m, q, "X0C", direction=[1, 0, 0]))
    figs.append(plots.axis_positions_along_path(m, q))
    for fig in figs:
        assert fig.axes
        plots.plt.close(fig)


def test_bad_machine_writes_no_report(tmp_path):
    with pytest.raises(mtacc.InputError):
        report.build_report(str(tmp_path / "missing.yaml"), str(tmp_path / "out"))
    assert not (tmp_path / "out").exists()
