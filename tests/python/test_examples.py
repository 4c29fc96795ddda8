"""The README's example runs as written."""
import pathlib
import runpy


def test_quickstart_runs():
    path = pathlib.Path(__file__).resolve().parents[2] / "python" / "examples" / "quickstart.py"
    ns = runpy.run_path(str(path))
    assert ns["path"].shape == (72, 5)
    assert ns["err"].shape == (2, 6)
    assert ns["cone"]["form_error_um"] > 0
