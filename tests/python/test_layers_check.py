"""The layer check (tests/architecture/check_layers.py) refuses what it is there to refuse: a front
end reaching past the workflows, and a folder including one above it. Each planted file in a
small tree must be reported, and the includes that are allowed must not be."""
import importlib.util
import pathlib

import pytest

CHECK = pathlib.Path(__file__).resolve().parents[1] / "architecture" / "check_layers.py"
spec = importlib.util.spec_from_file_location("check_layers", CHECK)
check_layers = importlib.util.module_from_spec(spec)
spec.loader.exec_module(check_layers)


def violations(tmp_path, files):
    for name, include in files.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(f'#include "{include}"\n')
    return list(check_layers.violations(tmp_path))


@pytest.mark.parametrize("name, include", [
    ("apps/mtacc/cmd_x.cpp", "mtacc/io/csv.hpp"),
    ("apps/mtacc/cmd_x.cpp", "mtacc/kinematics/jacobian.hpp"),
    ("python/bindings/expose_x.cpp", "mtacc/errors/aliases.hpp"),
    ("python/bindings/expose_x.cpp", "mtacc/io/measurement_csv.hpp"),
    ("src/io/x.cpp", "mtacc/workflows/budget.hpp"),
    ("src/kinematics/x.cpp", "mtacc/measurement/plates.hpp"),
])
def test_a_forbidden_include_is_reported(tmp_path, name, include):
    found = violations(tmp_path, {name: include})
    assert len(found) == 1 and name in found[0] and include in found[0]


@pytest.mark.parametrize("name, include", [
    ("apps/mtacc/cmd_x.cpp", "mtacc/workflows/budget.hpp"),
    ("apps/mtacc/cmd_x.cpp", "mtacc/core/text_file.hpp"),
    ("apps/mtacc/cmd_x.cpp", "cli_common.hpp"),
    ("python/bindings/expose_x.cpp", "mtacc/core/units.hpp"),
    ("fuzz/x_fuzzer.cpp", "mtacc/io/csv.hpp"),
    ("src/workflows/x.cpp", "mtacc/io/csv.hpp"),
])
def test_an_allowed_include_passes(tmp_path, name, include):
    assert violations(tmp_path, {name: include}) == []


def test_the_project_itself_passes():
    assert list(check_layers.violations(CHECK.parents[2])) == []
