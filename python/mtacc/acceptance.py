"""The acceptance report: one self-contained HTML file with the summary of every test first, then
each test's result, uncertainty budget, tolerance, verdict and figure.

    python3 -m mtacc.acceptance MACHINE --tests FILE --html REPORT.html    (or: mtacc acceptance ... --html)
"""
import datetime
import html
import sys

from . import plots
from .report import _write_atomically, figure, html_page, report_command, table

STANDARDS = {"ISO 230-2": "accuracy and repeatability of positioning", "ISO 10791-6": "rotary axes with the linear axes (K tests)",
             "ISO 230-1": "geometric accuracy from direct measurements", "ISO 230-4": "circular tests (ballbar)",
             "ISO 230-3": "thermal drift"}


def _verdict(v):
    return f'<b style="color:{plots.VERDICT_COLOURS[v]}">{html.escape(v)}</b>'


def _test_section(test):
    unit = test["unit"]
    c = test["conformance"]
    out = (f"<h2>{html.escape(test['name'])}: {html.escape(test['standard'])}</h2>"
           f"<p>{html.escape(STANDARDS.get(test['standard'], ''))}; data {html.escape(test['data'])}; instrument "
           f"{html.escape(test['instrument'])}. Verdict: {_verdict(c['overall'])}.</p>")
    out += figure(plots.conformance_chart(test), "Each result with its expanded uncertainty U (k = 2) and its tolerance")
    if test["type"] == "positioning":
        out += figure(plots.positioning_chart(test["detail"]), "ISO 230-2: the deviations of every cycle, the means and ±2 s bands")
    elif test["type"] == "rotary":
        out += figure(plots.rotary_test_deviations(test), "ISO 10791-6: the deviations over the rotary axis's positions")
    elif test["type"] == "drift":
        out += figure(plots.drift_test_curves(test["detail"]), "ISO 230-3: the drift of each direction over the test")
    elif test["type"] == "circular":
        out += figure(plots.circular_test(test), "ISO 230-4: the ballbar's length deviation over the circle, each direction")
    else:
        out += figure(plots.geometric_test(test), "ISO 230-1: the mean of the runs and its deviations from the reference lines")
    rows = [[v["quantity"], f"{v['value']:.3f}", f"{v['U']:.3f}", f"{v['tolerance']:.3f}", v["tolerance_text"], v["verdict"]]
            for v in c["verdicts"]]
    out += table(["quantity", f"result [{unit}]", f"U, k = 2 [{unit}]", f"tolerance [{unit}]", "as written", "verdict"], rows)
    budget = test["uncertainty"]
    rows = [[k["symbol"], f"{k['u']:.4f}", k["source"] + (" (default)" if k["defaulted"] else ""), ", ".join(k["quantities"])]
            for k in budget["contributors"]]
    out += "<p>Uncertainty contributors (ISO/TR 230-9), standard uncertainties:</p>"
    out += table(["contributor", f"u [{unit}]", "from", "enters"], rows, left=1)
    if test["defaulted"]:
        out += f"<p class='meta'>Taken from the documented defaults: {html.escape(', '.join(test['defaulted']))}.</p>"
    out += f"<p class='meta'>Decision rule: {html.escape(c['decision_rule_text'])}. Tolerances: {html.escape(c['tolerance_file'])}.</p>"
    return out


def build(machine, result):
    """The report's HTML from `Machine.acceptance`'s result."""
    rows = [[s["test"], s["standard"], s["quantity"], f"{s['value']:.3f} {s['unit']}", f"{s['U']:.3f}", f"{s['tolerance']:.3f}",
             s["verdict"]] for s in result["summary"]]
    rules = sorted({t["conformance"]["decision_rule_text"] for t in result["tests"]})
    parts = [f"<h1>{html.escape(result['title'])}</h1>",
             f"<p class='meta'>{html.escape(machine.name)}; tests {html.escape(result['file'])}; "
             f"{datetime.date.today().isoformat()}; mtacc.</p>",
             f"<p class='key'>Overall verdict: {_verdict(result['overall'])} ({len(result['tests'])} tests, "
             f"{len(result['summary'])} toleranced results).</p>",
             "<h2>Summary</h2>",
             table(["test", "standard", "quantity", "result", "U (k = 2)", "tolerance", "verdict"], rows, left=3),
             "<p>Decision rule: " + "; ".join(html.escape(r) for r in rules) + ". Uncertainties after ISO/TR 230-9 "
             "(docs/conventions.md \"Measurement uncertainty and conformance\"), U = 2 u_c.</p>"]
    parts += [_test_section(t) for t in result["tests"]]
    return html_page(result["title"], parts)

def write_report(machine, result, path):
    """Writes the report to `path` (whole or not at all)."""
    _write_atomically(str(path), build(machine, result))
    return str(path)


def main(argv=None):
    return report_command(argv, "mtacc acceptance", "Write the HTML acceptance report.", [("--tests", "the acceptance tests file (YAML)")],
                          lambda machine, args: machine.acceptance(args.tests, html=args.html))

if __name__ == "__main__":
    sys.exit(main())
