"""The measurement design report: one self-contained HTML file for the operator with the designed
plan (runs in the order they are made, set-ups, where the spheres sit), its predicted uncertainties
beside those of the user's own plan, and the time it takes against what a longer or shorter one
would give.

    python3 -m mtacc.measurement_design MACHINE --options JSON --html REPORT.html    (or: mtacc design ... --html)
"""
import datetime
import html
import json
import sys

from . import plots
from .report import _write_atomically, figure, html_page, report_command, table


def _runs_table(result, set_ups):
    rows = []
    for r in result["runs"]:
        rows.append([r["name"], r["description"], r["instrument"], set_ups.index(r["set_up"]) + 1, r["poses"], f"{r['time_min']:.2f}"])
    return table(["run", "what", "instrument", "set-up", "positions", "min"], rows, left=3)


def build(machine, result):
    """The report's HTML from `Machine.design`'s result."""
    design, own = result["design"], result.get("own_plan")
    set_ups = []
    for r in result["runs"]:
        if r["set_up"] not in set_ups:
            set_ups.append(r["set_up"])
    title = f"Measurement design for {machine.name}"
    parts = [f"<h1>{html.escape(title)}</h1>",
             f"<p class='meta'>{html.escape(machine.name)}; {datetime.date.today().isoformat()}; mtacc design.</p>",
             f"<p class='key'>{len(result['runs'])} runs on {len(set_ups)} set-up{'s' if len(set_ups) != 1 else ''}, "
             f"{design['time_min']:.1f} min of machine time "
             f"(budget {result['budget_min']:g} min); {html.escape(result['criterion'])}-optimal among {result['candidates']} candidate "
             f"runs. The TCP after compensation: {design['tcp_rms_k2_um']:.3g} µm (root mean square over the working volume) and "
             f"{design['tcp_max_k2_um']:.3g} µm (largest), k = 2.</p>"]
    parts.append("<h2>The plan, in the order it is run</h2>")
    parts.append(figure(plots.design_timeline(result), "Each run after the mounting of its instrument and its set-up, minutes from the start"))
    parts.append(_runs_table(result, set_ups))
    parts.append("<p>Set-ups:</p>" + table(["set-up", "where"], [[n, s] for n, s in enumerate(set_ups, 1)], left=2))
    if any(r["target_mm"] is not None for r in result["runs"]):
        parts.append(figure(plots.design_set_ups(result), "Where each set-up's sphere sits in the workpiece frame (+: its origin)"))
    parts.append("<h2>What it determines</h2>")
    parts.append(figure(plots.design_uncertainties(result), "Each parameter's predicted uncertainty (k = 2), first order about the nominal machine"))
    rows = []
    for k, p in enumerate(design["parameters"]):
        row = [p["name"], f"{p['u_k2']:.3g} {p['unit']}"]
        if own and "parameters" in own:
            theirs = own["parameters"][k]["u_k2"]
            row += [f"{theirs:.3g} {p['unit']}", f"{p['u_k2'] / theirs:.2f}"]
        rows.append(row)
    header = ["parameter", "design, U (k = 2)"] + (["your plan", "ratio"] if own and "parameters" in own else [])
    parts.append(table(header, rows))
    if own and "refused" in own:
        parts.append(f"<p>Your plan: {html.escape(own['refused'])}</p>")
    parts.append("<h2>Time against uncertainty</h2>")
    parts.append(figure(plots.design_pareto(result), "The best design at each budget: the TCP's uncertainty after compensation against the machine time"))
    rows = [[f"{p['budget_min']:.1f}", f"{p['time_min']:.1f}", p["runs"], f"{p['tcp_rms_k2_um']:.3g}", f"{p['tcp_max_k2_um']:.3g}",
             f"{p['worst_length_k2_um']:.3g}", f"{p['worst_angle_k2_urad']:.3g}"] if "time_min" in p
            else [f"{p['budget_min']:.1f}", p["refused"], "", "", "", "", ""] for p in result["pareto"]]
    parts.append(table(["budget [min]", "time [min]", "runs", "TCP rms [µm]", "TCP max [µm]", "worst length [µm]", "worst angle [µrad]"], rows))
    t = result["time_model"]
    parts.append(f"<p class='meta'>Machine time: rapid {t['rapid_mm_per_min']:g} mm/min, {t['dwell_s']:g} s per R-test position, "
                 f"{t['probe_time_s']:g} s per probed sphere, {t['set_up_min']:g} min per set-up, {t['change_min']:g} min per instrument "
                 "(docs/conventions.md \"Optimal experimental design\").</p>")
    for note in result["notes"]:
        parts.append(f"<p class='meta'>{html.escape(note)}</p>")
    parts.append("<h2>The plan file</h2><pre>" + html.escape(result["plan"]) + "</pre>")
    return html_page(title, parts)

def write_report(machine, result, path):
    """Writes the report to `path` (whole or not at all)."""
    _write_atomically(str(path), build(machine, result))
    return str(path)


def main(argv=None):
    return report_command(argv, "mtacc design", "Write the HTML report of a measurement design.",
                          [("--options", "the design's options as JSON, {key: [values]} (as mtacc design takes them)")],
                          lambda machine, args: write_report(machine, machine._core.design(json.loads(args.options)), args.html))

if __name__ == "__main__":
    sys.exit(main())
