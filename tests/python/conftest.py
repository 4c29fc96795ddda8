import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
if not os.environ.get("PYTHONPATH"):  # run outside ctest: the build tree's package
    sys.path.insert(0, str(ROOT / "build" / "python"))


@pytest.fixture(scope="session")
def cli():
    path = pathlib.Path(os.environ.get("MTACC_CLI", ROOT / "build" / "mtacc"))
    assert path.exists(), f"build the CLI first: {path}"
    return str(path)


@pytest.fixture(scope="session")
def artifacts():
    path = pathlib.Path(os.environ.get("MTACC_TEST_ARTIFACTS", ROOT / "build" / "test-artifacts"))
    path.mkdir(parents=True, exist_ok=True)
    return path


@pytest.fixture(scope="session")
def as_json():
    """The Python result as the CLI's JSON has it (ndarrays as nested lists), to compare the two."""
    import mtacc
    return mtacc.as_json
