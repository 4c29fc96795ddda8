"""The bad-input corpus: every case in cases/ is run against the CLI and must fail cleanly.

A case is one small file, cases/NNN-what.case:

    # What a careless user did (free text).
    run: check {machine.yaml} -o {out}
    expect: {machine.yaml}:3: axes.X: travel: lower limit above upper
    located: file                     # file (file:line:), option --name, argument NAME, or none: <why>
    --- machine.yaml
    <the input file's text>
    --- poses.csv                     # further inputs, as many as the case needs
    ...

Placeholders in `run` and `expect`: {name} is the path of the case's input file `name` (all
in {indir}), {out} an output file in an output folder ({outdir}), {data} the bundled data folder;
in the input files {data} alone (a file that names bundled files, e.g. an acceptance tests file).
Every case runs twice: with no output file, and with an existing output file that must stay
unchanged. The checks: a non-zero exit within the time limit, and not the status 1 of an internal
failure (an exception the front end did not map), nothing on stdout, exactly one
line on stderr equal to `mtacc: error: ` + expect, no file created or changed, the inputs
untouched. At least 98 % of the cases must be located (file:line:, the option or the argument).

Usage: run_corpus.py CLI [--bless] [--without-report | --report-only]
  --bless           print each case's actual message instead of checking it
  --without-report  leave out the `report` cases, for a build without the Python module that
                    the report runs on (the count left out is printed)
  --report-only     only the `report` cases: the rest run in the sanitizer build
"""
import concurrent.futures
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
DATA = HERE.parents[1] / "data"
TIME_LIMIT_S = 120
SENTINEL = "an earlier result that a failing run must not touch\n"
LOCATED_SHARE = 0.98


class Case:
    def __init__(self, path):
        self.path = path
        self.name = path.stem
        self.files = {}
        self.run = self.expect = self.located = None
        header, *parts = re.split(r"^--- (\S+)\n", path.read_text(), flags=re.M)
        for name, text in zip(parts[0::2], parts[1::2]):
            self.files[name] = text
        for line in header.splitlines():
            key, _, value = line.partition(": ")
            if key in ("run", "expect", "located"):
                setattr(self, key, value.strip())
        if not self.run or self.expect is None or not self.located:
            raise ValueError(f"{path}: a case needs run:, expect: and located: lines")
        kinds = ("option -", "argument ", "none: ")
        if not (self.located == "file" or self.located.startswith(kinds)):
            raise ValueError(f"{path}: located: must be file, option -NAME, argument NAME or none: REASON")
        if self.expect == "?":
            return
        if self.located == "file" and not re.match(r"^\S+:\d+: ", self.expect):
            raise ValueError(f"{path}: located: file, but the expected message does not start with file:line:")
        if self.located.startswith(("option", "argument")) and self.located.split()[1] not in self.expect:
            raise ValueError(f"{path}: located: {self.located}, but the expected message does not name it")


def substitute(text, folder):
    values = {"out": str(folder / "out" / "result.csv"), "outdir": str(folder / "out"), "indir": str(folder / "in"),
              "data": str(DATA)}
    return re.sub(r"\{([^{}\s]+)\}", lambda m: values.get(m.group(1), str(folder / "in" / m.group(1))), text)


def unsubstitute(message, case, folder):
    message = message.removeprefix("mtacc: error: ")
    for name in sorted(case.files, key=len, reverse=True):
        message = message.replace(str(folder / "in" / name), "{" + name + "}")
    return (message.replace(str(folder / "out" / "result.csv"), "{out}").replace(str(folder / "out"), "{outdir}")
            .replace(str(folder / "in"), "{indir}").replace(str(DATA), "{data}"))


def snapshot(folder):
    return {p.relative_to(folder): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def run_once(cli, case, existing_output):
    with tempfile.TemporaryDirectory(prefix="mtacc-bad-input-") as tmp:
        folder = pathlib.Path(tmp)
        (folder / "in").mkdir()
        (folder / "out").mkdir()
        for name, text in case.files.items():
            (folder / "in" / name).write_text(text.replace("{data}", str(DATA)))
        if existing_output:
            (folder / "out" / "result.csv").write_text(SENTINEL)
        before = snapshot(folder)
        args = [cli] + [substitute(a, folder) for a in shlex.split(case.run)]
        try:
            r = subprocess.run(args, capture_output=True, text=True, timeout=TIME_LIMIT_S, cwd=folder / "out",
                               errors="replace")
        except subprocess.TimeoutExpired:
            return [f"no answer within {TIME_LIMIT_S} s"], ""
        expected = "mtacc: error: " + substitute(case.expect, folder)
        problems = []
        if r.returncode == 0:
            problems.append("exit status 0")
        if r.returncode == 1:
            problems.append("exit status 1, the status of an internal failure: bad input exits 2 (3 for an unreachable pose)")
        if r.returncode < 0 or r.returncode > 125:
            problems.append(f"killed or crashed (status {r.returncode})")
        if r.stdout:
            problems.append(f"stdout not empty: {r.stdout[:200]!r}")
        if r.stderr.count("\n") != 1:
            problems.append(f"{r.stderr.count(chr(10))} lines on stderr: {r.stderr[:2000]!r}")
        actual = r.stderr.split("\n", 1)[0]
        if actual != expected:
            problems.append(f"message\n      got:      {actual}\n      expected: {expected}")
        after = snapshot(folder)
        if after != before:
            changed = sorted(str(p) for p in set(after) ^ set(before) | {p for p in before if after.get(p) != before[p]})
            problems.append(f"files created or changed: {changed}")
        return problems, unsubstitute(actual, case, folder)


def check(cli, case):
    problems = []
    start = time.monotonic()
    for existing_output in (False, True):
        found, message = run_once(cli, case, existing_output)
        problems += [f"({'existing output' if existing_output else 'no output'}) {p}" for p in found]
    return case, problems, message, time.monotonic() - start


def main():
    cli, options = sys.argv[1], sys.argv[2:]
    bless = "--bless" in options
    corpus = cases = [Case(p) for p in sorted((HERE / "cases").glob("*.case"))]
    if "--without-report" in options:
        left_out = [c for c in cases if c.run.split()[0] == "report"]
        cases = [c for c in cases if c not in left_out]
        print(f"{len(left_out)} report cases left out: this build has no Python module")
    elif "--report-only" in options:
        cases = [c for c in cases if c.run.split()[0] == "report"]
        print(f"{len(cases)} report cases only: the others run in the sanitizer build")
    workers = max(1, min(4, os.cpu_count() or 1))
    with concurrent.futures.ThreadPoolExecutor(workers) as pool:
        results = list(pool.map(lambda c: check(cli, c), cases))
    failures = 0
    for case, problems, message, seconds in results:
        if bless:
            print(f"{case.name} ({seconds:.1f} s)\n  {message}")
        elif problems:
            failures += 1
            print(f"FAIL {case.path.name}")
            for p in problems:
                print(f"    {p}")
    unlocated = [c for c in corpus if c.located.startswith("none")]
    share = 1 - len(unlocated) / len(corpus) if corpus else 0
    print(f"{len(cases)} cases, {len(cases) - failures} clean failures as expected; "
          f"{100 * share:.1f} % of the corpus located (file and line, the option or the argument)")
    for c in unlocated:
        print(f"  not located: {c.name}: {c.located[len('none: '):]}")
    if share < LOCATED_SHARE:
        print(f"fewer than {100 * LOCATED_SHARE:.0f} % of the cases are located")
        return 1
    return 1 if failures or bless else 0


if __name__ == "__main__":
    sys.exit(main())
