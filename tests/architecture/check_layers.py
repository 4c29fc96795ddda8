#!/usr/bin/env python3
"""Fails when a folder of the library includes a folder of a higher layer (docs/architecture.md).

Layers, lowest first: core; the domain folders in their own order (machine, errors, kinematics,
measurement, identification, procedures, virtual_controller, compensation; dynamics and thermal need only core); io; workflows; the front ends (apps/,
python/bindings/, fuzz/). A file may include headers of its own folder and of lower layers only, so
that the layers point one way and no two folders include each other. The CLI and the Python
bindings go through the workflows: they include workflows/ and core/ only (the fuzzers, which
drive the readers themselves, may include any folder).
"""
import pathlib
import re
import sys

RANK = {"core": 0, "machine": 1, "dynamics": 1, "thermal": 1, "errors": 2, "kinematics": 3, "measurement": 4, "identification": 5,
        "procedures": 6, "virtual_controller": 7, "compensation": 8, "io": 9, "workflows": 10, "frontend": 11, "fuzz": 11}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


FRONT_END_MAY_INCLUDE = {"core", "workflows"}


def folder_of(path, root):
    parts = path.relative_to(root).parts
    if parts[0] in ("apps", "python"):
        return "frontend"
    if parts[0] == "fuzz":
        return "fuzz"
    if parts[0] == "include":
        return parts[2]
    return parts[1]  # src/<folder>/...


def included_folder(name, path):
    if name.startswith("mtacc/"):
        return name.split("/")[1]
    if name.startswith("../"):
        return pathlib.PurePosixPath(name).parts[1]
    return None  # a header of the same folder


def violations(root):
    files = [p for d in ("include", "src", "apps", "python/bindings", "fuzz") for p in (root / d).rglob("*")
             if p.suffix in (".hpp", ".cpp", ".h")]
    for path in sorted(files):
        here = folder_of(path, root)
        if here not in RANK:
            yield f"{path.relative_to(root)}: folder '{here}' has no layer in tests/architecture/check_layers.py"
            continue
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            there = included_folder(m.group(1), path)
            if there is None or there == here:
                continue
            if there not in RANK:
                yield f"{path.relative_to(root)}:{number}: includes unknown folder '{there}'"
            elif RANK[there] >= RANK[here]:
                yield f"{path.relative_to(root)}:{number}: {here} includes {m.group(1)} ({there} is not below {here})"
            elif here == "frontend" and there not in FRONT_END_MAY_INCLUDE:
                yield f"{path.relative_to(root)}:{number}: a front end includes {m.group(1)} (only workflows/ and core/: reach {there}/ through a workflow)"


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    found = list(violations(root))
    for v in found:
        print(v)
    print(f"layers: {len(found)} include(s) pointing up or sideways")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
