"""One version everywhere: the CLI, the module and what pip installed (CMake's project version)."""
import os
import re
import subprocess

import mtacc


def test_cli_and_module_report_one_version(cli):
    out = subprocess.run([cli, "--version"], capture_output=True, text=True, check=True).stdout.strip()
    assert re.fullmatch(r"\d+\.\d+\.\d+", mtacc.__version__)
    assert out == f"mtacc {mtacc.__version__}"


def test_pip_lists_the_installed_package_at_that_version():
    # Outside the build tree: the package the set-up installed with pip (scripts/install-python.sh).
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "MTACC_DATA_DIR")}
    shown = subprocess.run(["/usr/bin/python3", "-m", "pip", "show", "mtacc"], capture_output=True, text=True, env=env)
    assert shown.returncode == 0, "mtacc is not installed with pip: run scripts/build.sh"
    fields = dict(line.split(": ", 1) for line in shown.stdout.splitlines() if ": " in line)
    assert fields["Name"] == "mtacc"
    assert fields["Version"] == mtacc.__version__
    imported = subprocess.run(["/usr/bin/python3", "-c", "import mtacc; print(mtacc.__version__); print(mtacc.__file__)"],
                              capture_output=True, text=True, env=env, cwd="/", check=True).stdout.split()
    assert imported[0] == mtacc.__version__
    assert imported[1].startswith(fields["Location"])
