"""The front ends stay thin (docs/architecture.md): a CLI command file parses, calls one workflow
and formats, in at most 150 lines; a binding file exposes one family in at most 250."""
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
LIMITS = [("apps/mtacc", "cmd_*.cpp", 150), ("python/bindings", "*.cpp", 250)]


@pytest.mark.parametrize("folder, pattern, limit", LIMITS)
def test_no_front_end_file_is_longer_than_its_limit(folder, pattern, limit):
    files = sorted((ROOT / folder).glob(pattern))
    assert files, f"no {pattern} in {folder}"
    too_long = {f.name: n for f in files if (n := len(f.read_text(encoding="utf-8").splitlines())) > limit}
    assert too_long == {}, f"over {limit} lines: {too_long}"
