#!/usr/bin/python3
"""The curated mutation run of scripts/mutate.sh (issue 52).

Copies the tracked tree to build-mutate/tree, builds it once (Release, no benchmarks, through
the compiler cache) and runs ctest on it, which must pass. Then each mutant of tests/mutants.txt
alone: its text replaced, the tree rebuilt incrementally, its `tests` regex run first and, if
nothing failed, the whole suite with --stop-on-failure; the file restored. A mutant is killed
when a test fails, survives when none does; one that does not compile, or compiles to the same
object file, is marked so and left out of the score, as is one that survives where its record
argues (`equivalent:`) that no output can show it. Prints the table and the score and writes
them to build-mutate/report.md.
"""
import hashlib
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
WORK = ROOT / "build-mutate"
TREE = WORK / "tree"
BUILD = TREE / "build"
CTEST_TIMEOUT = 2400


def read_mutants(path):
    mutants, record = [], {}
    for number, line in enumerate(path.read_text().splitlines(), 1):
        if line.startswith("#"):
            continue
        if not line.strip():
            if record:
                mutants.append(record)
            record = {}
            continue
        key, sep, value = line.partition(": ")
        if not sep or key not in ("id", "file", "find", "replace", "why", "tests", "equivalent"):
            sys.exit(f"{path}:{number}: expected 'key: value' with key id, file, find, replace, why, tests or equivalent")
        record[key] = value
        record.setdefault("line", number)
    if record:
        mutants.append(record)
    for m in mutants:
        missing = [k for k in ("id", "file", "find", "replace", "why") if k not in m]
        if missing:
            sys.exit(f"{path}:{m['line']}: mutant without {', '.join(missing)}")
    return mutants


def shell(command, log=None, timeout=None):
    """Runs a bash command in the tree with the compiler cache's environment."""
    with open(log, "w") if log else open(os.devnull, "w") as out:
        return subprocess.run(["bash", "-c", f"source scripts/ccache-env.sh > /dev/null && {command}"], cwd=TREE, stdout=out,
                              stderr=subprocess.STDOUT, timeout=timeout).returncode


def sync_tree():
    """The tracked files of the checkout into the tree, rewriting only those that differ."""
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, check=True).stdout.split(b"\0")
    for name in filter(None, files):
        source, target = ROOT / name.decode(), TREE / name.decode()
        if not source.is_file():
            continue
        if not target.exists() or target.read_bytes() != source.read_bytes():
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target)


def object_of(source):
    return BUILD / "CMakeFiles" / "mtacc.dir" / (source + ".o")


def digest(path):
    return hashlib.sha256(path.read_bytes()).hexdigest() if path.exists() else None


def build(log):
    return shell("cmake --build build -j\"$(nproc)\"", log) == 0


def failed_tests(log):
    text = Path(log).read_text(errors="replace")
    return re.findall(r"^\s*\d+ - (\S+) \(", text.split("The following tests FAILED:")[-1], re.M) if "tests FAILED" in text else []


def ctest(arguments, log):
    try:
        code = shell(f"cd build && ctest -j\"$(nproc)\" --output-on-failure {arguments}", log, CTEST_TIMEOUT)
    except subprocess.TimeoutExpired:
        return ["(timed out)"]
    return failed_tests(log) or (["(ctest failed)"] if code != 0 else [])


def main():
    mutants = read_mutants(ROOT / "tests" / "mutants.txt")
    chosen = sys.argv[1:]
    unknown = set(chosen) - {m["id"] for m in mutants}
    if unknown:
        sys.exit(f"mutate.sh: no mutant {', '.join(sorted(unknown))}")
    if chosen:
        mutants = [m for m in mutants if m["id"] in chosen]
    for m in mutants:
        count = (ROOT / m["file"]).read_text().count(m["find"])
        if count != 1:
            sys.exit(f"tests/mutants.txt:{m['line']}: {m['id']}: the text occurs {count} times in {m['file']} (once needed)")
    TREE.mkdir(parents=True, exist_ok=True)
    sync_tree()
    logs = WORK / "logs"
    logs.mkdir(exist_ok=True)
    print(f"mutate: {len(mutants)} mutants; building the unmutated tree in {BUILD} ...", flush=True)
    if shell("cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMTACC_BUILD_BENCH=OFF \"${ccache_launcher[@]}\"", logs / "configure.log") != 0 \
            or not build(logs / "build.log"):
        sys.exit(f"mutate: the unmutated tree does not build ({logs}/build.log)")
    baseline = ctest("", logs / "ctest.log")
    if baseline:
        sys.exit(f"mutate: the unmutated tree fails {', '.join(baseline)} ({logs}/ctest.log): fix that first")
    rows = []
    for k, m in enumerate(mutants, 1):
        started = time.time()
        path = TREE / m["file"]
        original = path.read_text()
        before = digest(object_of(m["file"]))
        path.write_text(original.replace(m["find"], m["replace"], 1))
        try:
            if not build(logs / f"{m['id']}-build.log"):
                outcome, by = "does not compile", f"logs/{m['id']}-build.log"
            elif before is not None and digest(object_of(m["file"])) == before:
                outcome, by = "equivalent", "compiles to the same object"
            else:
                failed = ctest(f"-R '{m['tests']}'", logs / f"{m['id']}-hint.log") if m.get("tests") else []
                if not failed:
                    failed = ctest("--stop-on-failure", logs / f"{m['id']}-ctest.log")
                if failed:
                    outcome, by = "killed", failed[0]
                elif m.get("equivalent"):
                    outcome, by = "equivalent", "argued: " + m["equivalent"]
                else:
                    outcome, by = "survived", ""
        finally:
            path.write_text(original)
        rows.append((m, outcome, by, time.time() - started))
        print(f"[{k}/{len(mutants)}] {m['id']}: {outcome}{' by ' + by if by else ''} ({time.time() - started:.0f} s)", flush=True)
    build(logs / "restore-build.log")
    killed = sum(1 for _, o, _, _ in rows if o == "killed")
    scored = sum(1 for _, o, _, _ in rows if o in ("killed", "survived"))
    lines = ["| mutant | folder | outcome | caught by | why plausible |", "|---|---|---|---|---|"]
    for m, outcome, by, _ in rows:
        folder = str(Path(m["file"]).parent).removeprefix("src/")
        lines.append(f"| {m['id']} | {folder} | {outcome} | {by} | {m['why']} |")
    score = 100.0 * killed / scored if scored else 0.0
    lines.append("")
    lines.append(f"score: {killed} killed of {scored} that compile to different code ({score:.1f} %); "
                 f"{len(rows) - scored} left out (not compiling or equivalent)")
    report = "\n".join(lines) + "\n"
    (WORK / "report.md").write_text(report)
    print("\n" + report)
    return 0 if score >= 90.0 else 1


if __name__ == "__main__":
    sys.exit(main())
