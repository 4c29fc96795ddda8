#!/usr/bin/python3
"""docs/reference-results.md from the reference tests' own output.

Every number a source document prints that a Seed* test compares with mtacc is recorded by
tests/reference_values.cpp as a test property; this script runs those tests and writes the
table of them, so the document cannot drift from what the tests check.

  reference_results.py TEST_BINARY OUTPUT           write OUTPUT
  reference_results.py TEST_BINARY OUTPUT --check   fail when OUTPUT is not what the tests give
"""
import argparse
import collections
import difflib
import json
import os
import re
import subprocess
import sys
import tempfile

SEEDS = {
    "000": ("Seed 000: Bossoni, ETH thesis (cone-frustum test piece, rigid-body dynamics)",
            "seed000_part1_cone_test_piece.md, seed000_part2_rigid_body_dynamics.md"),
    "001": ("Seed 001: Li, Sato et al., the cubic machining test", "seed001_cubic_machining_test.md"),
    "002": ("Seed 002: ballbar identification on a multi-tasking machine", "seed002_ballbar_multitasking.md"),
    "003": ("Seed 003: error model, direct measurements and hole plate", "seed003_error_model_holeplate.md"),
    "004": ("Seed 004: decomposition of measured TCP errors", "seed004_error_decomposition.md"),
}
# Seeds whose printed numbers need a capability that is not built yet.
PENDING = {
    "001": "Its printed numbers are the test piece's Tables 1-2: the zones' tool vectors and B/C angles, "
           "written back through mtacc's NC program (input echoed below). The machined and simulated zone "
           "heights of Figs 16 and 17 are not in the text (only the colour limits of ±0.01 mm); the "
           "extraction's predictions from Table 5 (§9.1) and the intentional errors of Section 5.3 (§9.2) "
           "are checked by Seed001CubicTest.*, its equations by Seed001WorkpieceFrame.*.",
    "003": "Its App. D tables are bundled as the Maho machine's errors; the seed prints only their "
           "coefficients (L5139), so the values the extraction computed from them (§8.3) check the data "
           "entry (input echoed below), as does the extraction's derived error grid (§13 item 12, "
           "Seed003AppendixD.DerivedGridOfSection13Item12). App. B.5's squareness and §5.3's residual "
           "bounds are reproduced from their procedures (with 2S_sim = 6.3 um as the report's input). The "
           "plate predictions of §5.3-5.4 and 2S_sim itself are listed below as not computed: the stiffness "
           "model is built (Stiffness.*) and the bundled data/stiffness/maho-260kg.yaml holds illustrative "
           "values. Its Appendix A transforms are checked by Seed003AppendixA.*.",
    "004": "Its Tables 1-4 are measurements of the authors' machine, not reproducible without their "
           "signals (extraction §15). The feed ladder is the rule the seed states (input echoed below); the "
           "power laws of Table 4 under reading A are fitted by mtacc (Seed004Statistics.R6, against the "
           "extraction's fits: the paper prints no kappa or N). The extraction's arithmetic on the paper's "
           "own tables (R2-R4: Table 1's row sums, which show that it used the five-norm denominator, "
           "erratum E1, and its stated shares; R7: Table 4's RMS against Table 3's maxima) calls no mtacc "
           "code and stays in the extraction. The method's identities V1-V4, V12, V13 are "
           "Seed004Decomposition.*; the 18 ms delay in NC cycles and instrument samples (R8) is "
           "Seed004Alignment.R8*, the linear-interpolation bound a*T^2/8 (R9) UniformSpline.Seed004R9*. "
           "On the virtual machine (own constants, wcayfxzt-compact structure) the clock offset, link "
           "errors, quasi-static, drift and dynamic errors are recovered within V5, V7-V10 (self-consistent "
           "below); V6, V11 and both negative controls of V14 hold (Seed004VirtualMachine.*).",
}
CATEGORIES = ["reproduced", "input echoed", "self-consistent", "known difference", "not computed"]
FIELDS = ["seed", "where", "quantity", "printed", "mtacc", "difference", "unit", "verdict"]


def fail(message):
    print(f"reference_results.py: {message}", file=sys.stderr)
    sys.exit(1)


def recorded(binary):
    """The recorded rows, in the order the tests ran, each with its test's name."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "reference.json")
        run = subprocess.run([binary, "--gtest_filter=Seed*", f"--gtest_output=json:{out}", "--gtest_brief=1"],
                             capture_output=True, text=True)
        if run.returncode != 0:
            fail(f"the reference tests failed, so their numbers are not recorded:\n{run.stdout[-3000:]}")
        with open(out, encoding="utf-8") as f:
            report = json.load(f)
    rows = []
    for suite in report["testsuites"]:
        for case in suite["testsuite"]:
            for key, value in case.items():
                if not key.startswith("reference "):
                    continue
                # googletest escapes each byte of a property on its own.
                fields = value.encode("latin-1").decode("utf-8").split("\t")
                if len(fields) != len(FIELDS):
                    fail(f"{suite['name']}.{case['name']}: malformed record {value!r}")
                row = dict(zip(FIELDS, fields))
                row["test"] = f"{suite['name']}.{case['name']}"
                rows.append(row)
    if not rows:
        fail("no reference numbers were recorded")
    return rows


def first_line(where):
    """4202 for "L4202-4222": tables in the order of the source."""
    match = re.search(r"L(\d+)", where)
    return int(match.group(1)) if match else 0


def verdict_kind(verdict):
    return verdict.split(":")[0].split(" within")[0]


def document(rows):
    by_seed = collections.defaultdict(list)
    for row in rows:
        by_seed[row["seed"]].append(row)
    out = ["# Reference results", "",
           "Every number a source document prints that mtacc computes, next to mtacc's value. "
           "**Generated** by `scripts/reference_results.py` from the reference tests' own output "
           "(`tests/reference_values.cpp`); the test `ReferenceResults.DocumentIsCurrent` fails when this "
           "file is not what the tests give. Do not edit it by hand: change the tests and run",
           "", "    /usr/bin/python3 scripts/reference_results.py build/tests/mtacc_tests docs/reference-results.md", "",
           "Categories: **reproduced**: a computation of mtacc agrees, within the stated tolerance, with a number "
           "the seed prints, from inputs the seed gives; **input echoed**: a number mtacc reads (or derives by a rule "
           "the seed states) and writes back, checked so the data entry stays right but not a reproduction; "
           "**self-consistent**: a value the seed gives (or the test's own truth), simulated and recovered by mtacc "
           "itself, so the printed column holds the injected value; **known difference**: the reason found (today's "
           "value is pinned by the test, so a change is noticed; one that starts to agree fails until it is moved to "
           "reproduced); **not computed**: what input is missing and where the seed fails to give it, or what is not "
           "built. Difference = mtacc − printed. The extractions in `../shared/reference/` give the derivations "
           "behind each reason.", "",
           "| seed | " + " | ".join(CATEGORIES) + " |", "|---" * (len(CATEGORIES) + 1) + "|"]
    for seed in SEEDS:
        counts = collections.Counter(verdict_kind(r["verdict"]) for r in by_seed.get(seed, []))
        unknown = set(counts) - set(CATEGORIES)
        if unknown:
            fail(f"seed {seed}: verdicts of no category: {sorted(unknown)}")
        out.append(f"| {seed} | " + " | ".join(str(counts[c]) for c in CATEGORIES) + " |")
    for seed, (title, extraction) in SEEDS.items():
        out += ["", f"## {title}", "", f"Extraction: `{extraction}`."]
        if seed in PENDING:
            out += ["", PENDING[seed]]
        tables = collections.OrderedDict()
        for row in by_seed.get(seed, []):
            table, _, line = row["where"].partition(", ")
            tables.setdefault(table, []).append((line, row))
        for table, entries in sorted(tables.items(), key=lambda t: first_line(t[1][0][0])):
            out += ["", f"### {table}", "", "| line | quantity | printed | mtacc | difference | unit | verdict | test |",
                    "|---|---|---|---|---|---|---|---|"]
            for line, r in entries:
                cells = [line, r["quantity"], r["printed"], r["mtacc"] or "–", r["difference"] or "–", r["unit"],
                         r["verdict"], f"`{r['test']}`"]
                out.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("binary")
    parser.add_argument("output")
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    text = document(recorded(args.binary))
    if args.check:
        try:
            with open(args.output, encoding="utf-8") as f:
                current = f.read()
        except OSError as e:
            fail(f"{args.output}: {e.strerror}")
        if current != text:
            diff = difflib.unified_diff(current.splitlines(), text.splitlines(), args.output, "the tests' output", lineterm="")
            print("\n".join(list(diff)[:60]))
            fail(f"{args.output} is not what the tests give: run scripts/reference_results.py {args.binary} {args.output}")
        return
    folder = os.path.dirname(os.path.abspath(args.output))
    with tempfile.NamedTemporaryFile("w", encoding="utf-8", dir=folder, delete=False) as f:
        f.write(text)
    os.replace(f.name, args.output)


if __name__ == "__main__":
    main()
