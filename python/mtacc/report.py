"""The accuracy report: one self-contained HTML file (figures inline as SVG, no network).

    python3 -m mtacc.report MACHINE [-o DIR] [--errors FILE]     (or: mtacc report ...)
"""
import argparse
import datetime
import html
import io
import os
import sys
import tempfile
import time

import numpy as np

from . import InputError, Machine, UnreachablePose, _options, plots
from ._mtacc import option_fields as _option_fields, read_options as _read_options

# Marks every figure as rendered (non-empty box) and records script errors, so that a
# browser test can read the outcome from the DOM.
CHECK_SCRIPT = """<script>
(function () {
  var errors = [];
  window.addEventListener('error', function (e) { errors.push(String(e.message)); });
  var original = console.error;
  console.error = function () { errors.push(Array.prototype.join.call(arguments, ' ')); original.apply(console, arguments); };
  window.addEventListener('load', function () {
    var figures = document.querySelectorAll('figure.plot');
    var rendered = 0;
    figures.forEach(function (f) {
      var svg = f.querySelector('svg');
      if (!svg) return;
      var box = svg.getBoundingClientRect();
      if (box.width > 50 && box.height > 50 && svg.querySelectorAll('path').length > 0) rendered += 1;
    });
    document.body.setAttribute('data-figures-expected', String(figures.length));
    document.body.setAttribute('data-figures-rendered', String(rendered));
    document.body.setAttribute('data-errors', errors.join(' | '));
  });
})();
</script>"""

DECOMPOSITION_SERIES_POINTS = 3000  # per test along the path: every k-th of ~10^5 instrument samples
DRIFT_SERIES_POINTS = 3000  # per drift test: every k-th sample

STYLE = """<style>
body { font-family: system-ui, sans-serif; max-width: 1100px; margin: 2em auto; color: #222; line-height: 1.45; }
h1 { font-size: 1.6em; margin-bottom: 0.1em; } h2 { border-bottom: 1px solid #ccc; margin-top: 2em; }
table { border-collapse: collapse; font-size: 0.85em; margin: 0.8em 0; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: right; } th { background: #f3f3f3; }
td.l, th.l { text-align: left; }
figure.plot { margin: 1em 0; } figure.plot svg { max-width: 100%; height: auto; }
figcaption { font-size: 0.85em; color: #555; }
.meta { color: #666; font-size: 0.9em; } .key { font-size: 1.15em; background: #f6f8fa; padding: 0.6em 1em; border-radius: 6px; }
</style>"""


def svg(fig):
    buf = io.StringIO()
    fig.savefig(buf, format="svg")
    plots.plt.close(fig)
    text = buf.getvalue()
    return text[text.index("<svg"):]


def figure(fig, caption):
    return f'<figure class="plot">{svg(fig)}<figcaption>{html.escape(caption)}</figcaption></figure>'


def table(header, rows, left=1):
    head = "".join(f'<th class="{"l" if i < left else ""}">{html.escape(str(h))}</th>' for i, h in enumerate(header))
    body = "".join("<tr>" + "".join(f'<td class="{"l" if i < left else ""}">{html.escape(str(c))}</td>'
                                    for i, c in enumerate(r)) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def fmt_pose(pose):
    return ", ".join(f"{k}={v:.4g}" for k, v in pose.items())


def circle_test(machine):
    """The X-Y circle the library computes (the radial component of the TCP error, as an ISO 230-4
    circular test sees the geometric errors)."""
    c = machine.xy_circle()
    if c is None:
        return ""
    fig = plots.polar_deviation(c["phi_deg"], c["radial_deviation_um"],
                                title=f"Circle R {c['radius_mm']:g} mm in X-Y, radial TCP deviation")
    return ("<h2>Circular test (X-Y)</h2><p>A circle of radius "
            f"{c['radius_mm']:g} mm around mid-travel with the rotary axes at zero; the radial component of the TCP "
            "error is what a ballbar would record from the geometric errors alone (no servo effects).</p>"
            + figure(fig, "Radial TCP deviation around the circle (reference circle grey, deviation red)"))


def five_axis_circle(machine, top_parameter):
    """The library's 5-axis circle: axis positions, radial deviation and the sensitivity to the
    largest error."""
    try:
        c = machine.tilted_circle()
    except (UnreachablePose, InputError) as e:
        return f"<h2>5-axis circle</h2><p>Not reachable on this machine: {html.escape(str(e))}</p>"
    if c is None:
        return ""
    q, phi = np.asarray(c["q"]), np.asarray(c["phi_deg"])
    centre = ", ".join(f"{v:g}" for v in c["centre_mm"])
    out = (f"<h2>5-axis circle</h2><p>TCP circle of radius {c['radius_mm']:g} mm around ({centre}) mm in the workpiece "
           "frame, tool tilted 30° towards the circle's centre (a cone-frustum-like path), solved through the generic "
           "inverse kinematics as one continuous path.</p>")
    out += figure(plots.axis_positions_along_path(machine, q, phi, "φ [deg]"), "Axis positions along the path")
    out += figure(plots.polar_deviation(phi, c["radial_deviation_um"], title="5-axis circle, radial TCP deviation"),
                  "Radial TCP deviation along the 5-axis circle")
    if top_parameter:
        out += figure(plots.sensitivity_along_path(machine, q, top_parameter, direction=np.asarray(c["radial_direction"]), s=phi),
                      f"Sensitivity of the TCP to {top_parameter} along the path (dashed: radial, the sensitivity coefficient k)")
    return out


def cone_section(machine, monte_carlo=200):
    """The cone-frustum test piece of Bossoni 2009 with the recommended set-up of §3.6."""
    family = machine.cone_preset_name()
    if family is None:
        return ""
    try:
        cone = machine.cone(preset=family, points=720, single_errors=True)
    except (UnreachablePose, InputError) as e:
        return f"<h2>Cone-frustum test piece</h2><p>The recommended set-up is not reachable: {html.escape(str(e))}</p>"
    try:  # the bundled limits (Bossoni 2009 Table 3.9) name the axes of a B-C tilting table
        cone["monte_carlo"] = machine.cone(preset=family, points=720, monte_carlo=monte_carlo)["monte_carlo"]
    except InputError as e:
        cone["monte_carlo_skipped"] = str(e)
    spec, path = cone["cone"], cone["path"]
    phi, q = np.asarray(path["phi_deg"]), np.asarray(path["q"])
    out = (f"<h2>Cone-frustum test piece (Bossoni 2009)</h2><p>Recommended set-up '{family}' (§3.6): α {spec['alpha_deg']:g}°, "
           f"β {spec['beta_deg']:g}°, r {spec['radius_mm']:g} mm, centre ({', '.join(f'{c:g}' for c in spec['centre_mm'])}) mm, "
           f"γ {spec['gamma_deg']:g}°; {spec['points']} points, feed {spec['feed_mm_per_min']:g} mm/min.</p>")
    for w in cone["warnings"]:
        out += f"<p><b>Warning:</b> {html.escape(w)}</p>"
    out += table(["axis", "min", "max", "range", "reversals", "max speed [/s]", "max accel. [/s²]"],
                  [[a["axis"], f'{a["min"]:.3f}', f'{a["max"]:.3f}', f'{a["range"]:.3f}', len(a["reversals_phi_deg"]),
                    f'{a["max_speed_per_s"]:.3f}', f'{a["max_acceleration_per_s2"]:.3f}'] for a in cone["axes"]])
    out += figure(plots.axis_positions_along_path(machine, q, phi, "φ [deg]"), "Axis positions over φ")
    out += figure(plots.polar_axis_positions(machine, phi, q), "Radial representation of the axis positions")
    out += figure(plots.normal_components(phi, np.asarray(path["normals_machine"])),
                  "Surface normal in the machine frame: the direction in which errors show on the cone")
    if "form_error_um" in cone:
        out += (f"<p class='key'>Equivalent cone form error of this machine's errors: "
                f"<b>{cone['form_error_um']:.2f} µm</b> (exact procedure, §3.9).</p>")
        out += figure(plots.polar_deviation(phi, cone["deviation_um"], title="All errors: normal deviation after the circle fit",
                                            remove_mean=False), "Cone form deviation of all errors together")
        singles = sorted(cone["single_errors"], key=lambda e: -e["form_error_um"])
        out += table(["error", "form error [µm]", "type (§3.10.4)"],
                     [[e["error"], f'{e["form_error_um"]:.3f}', e["type"]] for e in singles[:12]])
        for e in singles[:3]:
            out += figure(plots.polar_deviation(phi, e["deviation_um"], title=f'{e["error"]} alone', remove_mean=False),
                          f'Cone form deviation caused by {e["error"]} alone')
    if "monte_carlo" in cone:
        mc = cone["monte_carlo"]
        out += (f"<p>Monte Carlo: {monte_carlo} machines with errors drawn uniformly within Bossoni 2009 Table 3.9: median "
                f"{mc['median_um']:.2f} µm, quartiles {mc['lower_quartile_um']:.2f} / {mc['upper_quartile_um']:.2f} µm, "
                f"range {mc['min_um']:.2f} … {mc['max_um']:.2f} µm (thesis Table 3.5: 8.8, 6.9 / 11.0, 2.6 … 23.9 µm).</p>")
        out += figure(plots.box_plot({"equivalent cone form error": mc["form_errors_um"]}),
                      "Distribution of the equivalent cone form error over the Monte Carlo samples")
    elif "monte_carlo_skipped" in cone:
        out += f"<p>Monte Carlo skipped: the Bossoni 2009 Table 3.9 limits do not fit this machine ({html.escape(cone['monte_carlo_skipped'])}).</p>"
    return out


def plan_table(runs, axis_names):
    """The plan for the operator: each run's instrument, poses, what it moves and where the balls are."""
    rows = []
    for r in runs:
        q = np.asarray(r["q"], float)
        spread = q.max(axis=0) - q.min(axis=0)
        moves = ", ".join(f"{name} {q[:, k].min():.4g}..{q[:, k].max():.4g}" for k, name in enumerate(axis_names) if spread[k] > 1e-9)
        placement = r["target_mm"]
        rows.append([r["name"], r["instrument"], r["poses"], moves or "—",
                     "—" if placement is None else ", ".join(f"{v:.4g}" for v in placement),
                     ", ".join(f"{v:.4g}" for v in r["tool_ball_mm"])])
    return table(["run", "instrument", "poses", "axes moved [mm, °]", "sphere / work ball [mm] (— set at the tool ball)",
                  "tool ball [mm]"], rows)


def identification_section(machine, plan, obs, data=(), measured=()):
    """A test plan's measurements identified: the measured files given (`data`, read as
    `measured`) or, without them, the plan simulated from this machine's errors (0.5 µm noise);
    the plan for the operator, the ballbar and R-test evaluations, the plan's observability, the
    estimates with their uncertainties and correlations, what was held, the goodness of fit and
    each run's residuals. Returns the HTML and the identified model as an errors file's text (None
    when the plan cannot determine its parameters)."""
    out = f"<h2>Measurement and identification: {html.escape(plan)}</h2>"
    with tempfile.TemporaryDirectory() as tmp:
        if data:
            files = [str(f) for f in data]
            runs = list(measured)
            out += (f"<p>{len(files)} measured runs, read from: {html.escape(', '.join(os.path.basename(f) for f in files))}. "
                    "The errors not identified are held at the values of the machine file (or --errors), listed below.</p>")
        else:
            runs = machine.simulate(plan, noise="0.5 um", seed=1, output=tmp)["runs"]
            files = [r["file"] for r in runs]
            out += (f"<p><b>Simulated data:</b> the {len(runs)} runs of the plan were simulated from the errors this report "
                    "was given, with 0.5 µm reading noise, and identified back holding every other error at its true "
                    "value; the identification shows what the plan can do, not what a machine measured. Give the "
                    "measured files with --data to identify from them.</p>")
        out += "<h3>The plan</h3>" + plan_table(runs, machine.axis_names)
        out += figure(plots.plan_runs(runs, machine.axis_names), "Each run's axis positions over its poses, as the machine will move")
        rows = []
        for r, f in zip(runs, files):
            if r["instrument"] == "ballbar":
                ev = machine.evaluate_ballbar(f)
                out += figure(plots.ballbar_polar(ev), f"Ballbar run {html.escape(r['name'])}: trace and fitted eccentricity")
                d = ev["diagnostics"]
                g = max(x["circular_deviation_um"] for x in ev["directions"])
                rows.append([r["name"], f"{g:.2f}", "—" if ev["hysteresis_um"] is None else f"{ev['hysteresis_um']:.2f}",
                             f"{d['squareness_urad']:.1f}", f"{d['scale_mismatch_um_per_m']:.1f}", f"{d['backlash_a_um']:.2f}",
                             f"{d['backlash_b_um']:.2f}"])
        if rows:
            out += table(["run", "G [µm]", "H [µm]", "squareness [µrad]", "scale mismatch [µm/m]", "backlash a [µm]",
                          "backlash b [µm]"], rows)
        rtest = [(r, f) for r, f in zip(runs, files) if r["instrument"] == "rtest"]
        if rtest:
            evaluated = [machine.evaluate_rtest(f) for _, f in rtest]
            out += table(["R-test run", "axis", "range dX dY dZ [µm]", "range radial, axial, tangential [µm]"],
                         [[r["name"], e["moving_axis"], " ".join(f"{v:.2f}" for v in e["range_um"]),
                           "—" if e["about_the_axis"] is None else
                           " ".join(f"{e['about_the_axis']['range_um'][k]:.2f}" for k in ("radial", "axial", "tangential"))]
                          for (r, _), e in zip(rtest, evaluated)])
        out += figure(plots.singular_values(obs), "Singular values of the plan's scaled Jacobian")
        findings = "".join(f"<li>{html.escape(f)}</li>" for f in obs["findings"]) or "<li>every parameter is determined</li>"
        out += f"<ul>{findings}</ul>"
        if not obs["identifiable"]:
            return out + "<p>Identification skipped: the plan cannot determine its parameter set.</p>", None
        written = os.path.join(tmp, "identified.yaml")
        result = machine.identify(files, plan=plan, noise="0.5 um" if not data else None, errors_out=written)
        with open(written, encoding="utf-8") as f:
            model = f.read()
    estimates = [e for e in result["estimates"] if not e["setup"]]
    truth = None if data else {e["parameter"]: machine.errors.get(e["parameter"], 0.0) * (1e3 if e["unit"] == "um" else 1e6)
                               for e in estimates if e["parameter"] in machine.errors.names()}
    out += "<h3>Identified parameters</h3>"
    out += figure(plots.identified_values(result, truth),
                  "Identified parameters (95 % intervals)" + (" and the simulated values" if truth else ""))
    out += table(["parameter", "value", "u (k = 1)", "U (k = 2)", "unit"],
                 [[e["parameter"], f"{e['value']:.4f}", f"{e['standard_uncertainty']:.4f}", f"{2 * e['standard_uncertainty']:.4f}",
                   e["unit"]] for e in estimates])
    strong = result["correlations_above_0_9"]
    out += "<p>Correlations above 0.9: " + (html.escape("; ".join(strong)) if strong else "none") + ".</p>"
    held = machine.errors
    out += ("<p>Held at their values, not identified: " +
            (html.escape(", ".join(f"{h} = {held[h] * (1e3 if held.unit(h) == 'mm' else 1e6):.3f} "
                                   f"{'µm' if held.unit(h) == 'mm' else 'µrad'}" for h in result["held"])) if result["held"] else "none") +
            ".</p>")
    q = result["quality"]
    if q["p_value"] is None:
        out += "<p>Goodness of fit: not tested (the files state no reading noise).</p>"
    else:
        verdict = ("<b>fails</b>: the residuals are larger than the stated noise explains (errors the parameter set does not "
                   "model, outliers, or an understated noise; the run whose residuals stand out below is where to look)"
                   if q["p_value"] < q["fit_significance"] else "passes")
        out += (f"<p>Goodness of fit against the noise of {html.escape(q['noise_source'])}: χ² = {q['chi_square']:.4g} for "
                f"{result['degrees_of_freedom']} degrees of freedom, p = {q['p_value']:.3g}: {verdict}.</p>")
    out += table(["run", "instrument", "residual RMS [µm]", "largest [µm]", "stated noise [µm]"],
                 [[r["run"], r["instrument"], f"{r['rms_um']:.3f}", f"{r['max_um']:.3f}",
                   "—" if r["noise_um"] is None else f"{r['noise_um']:.3f}"] for r in result["run_residuals"]])
    out += figure(plots.run_residuals(result), "Residuals of each run at the estimates (the largest in red)")
    out += (f"<p>Residual standard deviation {result['sigma_um']:.3f} µm (RMS {result['residual_rms_um']:.3f} µm, "
            f"largest {result['residual_max_um']:.3f} µm) after {result['iterations']} iterations.</p>")
    out += ("<p>The identified model is written beside this report as <code>&lt;machine&gt;-identified.yaml</code>: an errors "
            "file that every command reads with --errors, with the record of the data it came from.</p>")
    return out, model


def dynamics_section(structure_name, compare=None):
    """Modes, FRF, acceleration response (Table 7.1 form) at position 1 of a structure model,
    and the Hx/X map over Y-Z compared with a second design."""
    from . import Structure
    s = Structure(structure_name)
    at = {a["name"]: (a["travel_mm"][1] if a["name"] == "Y" else a["travel_mm"][0] if a["name"] == "Z" else 0.0)
          for a in s.axes}
    out = f"<h2>Structural dynamics: {html.escape(s.name)}</h2>"
    out += ("<p>Rigid-body model (Bossoni 2009 part II): " + f"{len(s.bodies)} bodies, {6 * len(s.bodies)} DOF, evaluated at "
            + ", ".join(f"{k} = {v:g} mm" for k, v in at.items()) + " (position 1: Y and Z extended, X centred).</p>")
    modes = s.modes(at=at, count=8)
    rows = [[k + 1, f"{m['frequency_hz']:.1f}", f"{m['damped_frequency_hz']:.1f}", f"{100 * m['damping_ratio']:.2f}"]
            for k, m in enumerate(modes["modes"])]
    out += table(["mode", "f [Hz]", "damped f [Hz]", "ζ [%]"], rows, left=0)
    out += figure(plots.mode_shape_view(s, modes, 0, at), "First mode shape")
    f = np.arange(1.0, 201.0)
    method, coupling = s.frf_method(at=at)
    how = ("modal sum (the damping is proportional)" if method == "modal"
           else f"direct solve (the damping couples the modes by up to {100 * coupling:.0f} %)")
    out += figure(plots.frf_plot(f, s.frf(f, at=at)),
                  f"FRF of the TCP relative to the workpiece: direct terms and cross-talk; {how}")
    r = s.acceleration_response(at=at)
    names = [a["name"] for a in s.axes]
    out += "<p>Quasi-static TCP displacement per axis acceleration [µm/g<sub>n</sub>] (the form of Bossoni 2009 Table 7.1):</p>"
    out += table(["response"] + [f"{n}''" for n in names],
                 [[f"H{c}"] + [f"{r[f'H{c}'][n]:.1f}" for n in names] for c in "xyz"])
    maps = [s.map("Hx/X")]
    out += figure(plots.dynamics_map(maps[0], f"|Hx/X''| over Y-Z: {s.name}"), "Inertial compliance over the Y-Z section")
    if compare:
        other = Structure(compare)
        maps.append(other.map("Hx/X"))
        out += figure(plots.dynamics_map(maps[1], f"|Hx/X''| over Y-Z: {other.name}"), "The same for the second design")
        out += figure(plots.box_plot({m_name: np.asarray(m["values"]).ravel() for m_name, m in
                                      zip(("design 1", "design 2"), maps)}, ylabel="|Hx/X''| [µm/g]"),
                      f"Distribution over the 400 positions: design 1 = {html.escape(s.name)}, design 2 = {html.escape(other.name)}")
    return out


def cubic_section(machine_path, errors, load):
    """Li et al. 2021's cubic machining test on this machine: tool paths, the simulated surface, the zone
    heights with and without M_WC, and the sensitivity maps of the rotary axes' location errors."""
    grid = 0.02
    try:
        aligned = Machine(machine_path, errors, alignment="machine", load=load).cubic(grid=grid, sensitivities=True, sensitivity_grid=0.05)
        on_table = Machine(machine_path, errors, alignment="table", load=load).cubic(grid=grid)
    except (UnreachablePose, InputError) as e:
        return f"<h2>Cubic machining test (Li et al. 2021)</h2><p>Not machinable on this machine: {html.escape(str(e))}</p>"
    out = ("<h2>Cubic machining test (Li et al. 2021)</h2><p>A 48 mm block cut in 3 × 3 zones of 16 mm by 3-axis zig-zag "
           "passes (0.1 mm pick, ball-end mill ø6 mm), the rotary axes clamped so that the tool leans 30° towards "
           "the centre (Li et al. 2021 Tables 1–2). The tool path goes through the inverse kinematics and every CL point "
           "through the machine's errors; the surface is cut by material removal on a "
           f"{grid * 1000:g} µm grid. A step between zones or a tilt inside one shows the errors. <i>With M<sub>WC</sub></i>: "
           "the workpiece frame aligned with the machine at the reference pose (the transformation M<sub>WC</sub> from "
           "workpiece to table); <i>without</i>: the workpiece fixed to the table as clamped.</p>")
    out += figure(plots.cubic_layout(aligned), "Zones, tool paths and tool tilt; the clamped rotary axes per zone")
    out += figure(plots.cubic_surface_map(aligned), "Simulated machined surface minus the error-free one, referenced to "
                                                    "zone I (workpiece aligned with the machine, M_WC)")
    out += figure(plots.cubic_zone_bars(aligned, on_table), "Zone mean heights with and without M_WC")
    out += table(["zone", "axes", "E with M_WC [µm]", "tilt x, y [µm/mm]", "E without M_WC [µm]",
                  "without M_WC, ref. zone I [µm]"],
                 [[a["name"], fmt_pose({k: v for k, v in a["axes"].items()}), f'{a["deviation"]["mean_um"]:.3f}',
                   f'{a["deviation"]["slope_x_um_per_mm"]:.4f}, {a["deviation"]["slope_y_um_per_mm"]:.4f}',
                   f'{t["deviation"]["mean_um"]:.3f}', f'{t["measured"]["mean_um"]:.3f}']
                  for a, t in zip(aligned["zones"], on_table["zones"])])
    out += figure(plots.cubic_sensitivity_maps(aligned), "Sensitivity k = E / ε of each location error of the rotary "
                                                         "axes over the block (Li et al. 2021 Figs 10 and 12); white: |k| below 0.05 mm/mm or 1 mm/rad, "
                                                         "the sampled scallops' shift")
    return out


def components_section(results):
    """The 1991 BCR report: each directly measured component with its runs, mean and C1 piecewise fit."""
    out = ("<h2>Component errors from direct measurements (the 1991 BCR report)</h2><p>Each component measured along its "
           "axis, forward and backward over several runs; the mean of the runs fitted by a C1 piecewise "
           "quadratic with fixed breaks and stepwise removal of terms that are not significant.</p>")
    for r in results:
        f = r["fit"]
        out += figure(plots.component_fit(r), f"{html.escape(r['component'])} ({r['iso_name']}) from "
                                              f"{html.escape(r['file'])}: {len(r['runs_forward'])} runs each way")
        notes = [html.escape(c) for c in r["corrections"]]
        flagged = r["disturbances"]
        if flagged["readings"]:
            every = (f", recurring every {flagged['interval_s'] / 60:.1f} min" if flagged["interval_s"] else "")
            notes.append(f"{len(flagged['readings'])} disturbed reading(s) flagged{every}")
        out += "".join(f"<p>{n}.</p>" for n in notes)
        out += (f"<p>Residual {f['residual_std']:.3g} {r['unit']} ({f['degrees_of_freedom']} degrees of freedom); "
                f"removed: {html.escape(' '.join(f['removed'])) or 'none'}. The fitted function as the machine YAML "
                f"loads it:</p><pre>{html.escape(r['yaml'])}</pre>")
    return out


def plates_section(results):
    """The 1991 BCR report §5.3: each measured plate against the machine's error model."""
    out = ("<h2>Hole and ball plates (the 1991 BCR report)</h2><p>Each plate measured relative to its reference feature, "
           "corrected for the scale and plate temperatures, its misalignment removed; the model's deviations "
           "from the machine's errors (D<sub>h</sub> = −(E(q<sub>h</sub>) − E(q<sub>ref</sub>))), and the residual.</p>")
    for r in results:
        out += figure(plots.plate_vectors(r), f"{html.escape(r['file'])}: measured and modelled deviations, and the residual")
        bound = (f"; k = 2 bound {r['bound_um']:.2f} µm, {r['beyond_bound']} component(s) beyond it"
                 if r["bound_um"] is not None else "")
        out += f"<p>Residual RMS {r['residual_rms_um']:.3f} µm, largest {r['residual_max_um']:.3f} µm{bound}.</p>"
    return out


def stiffness_section(result):
    """The 1991 BCR report §4.2 and §5.4: the finite-stiffness changes of the errors and what they add to the TCP."""
    largest = result["largest_tcp_error"]
    out = ("<h2>Finite stiffness (the 1991 BCR report)</h2><p>Changes of the component errors with another axis's position or "
           f"the workpiece load, at a load of <b>{result['workpiece_load_kg']:g} kg</b> (each load-dependent change "
           "scaled linearly from the load it was measured under). They are part of every result above.</p>")
    out += figure(plots.stiffness_changes(result), "Changes of the errors along their axes")
    out += table(["change", "along", "measured under", "scale here", "largest change"],
                 [[t["error"], t["axis"] + (f" and {t['with']}" if t["with"] else ""),
                   "no load dependence" if t["reference_load_kg"] is None else f"{t['reference_load_kg']:g} kg",
                   f"{t['load_factor']:.3g}", f"{t['largest']:.3f} {t['unit']}"]
                  for t in result["terms"]], left=2)
    out += table(["largest TCP position error", "µm", "at"],
                 [[label, f"{largest[key]['position_error_um']:.3f}", fmt_pose(largest[key]["pose"])]
                  for key, label in (("geometric", "geometric errors alone"), ("stiffness_alone", "stiffness changes alone"),
                                     ("added_by_stiffness", "added by the stiffness changes"))], left=1)
    out += f"<p class='meta'>Over {result['poses']} poses, {result['samples_per_axis']} positions per axis.</p>"
    return out


def compensation_section(result):
    """Issue 17: what each controller table leaves of the TCP position error when a controller applies it."""
    g = result["grid"]
    others = {k: v for k, v in g["pose"].items() if k not in ("X", "Y", "Z")}
    at = f" (other axes at {html.escape(fmt_pose(others))})" if others else ""
    out = ("<h2>After compensation</h2><p>The corrections of the X, Y, Z commands that put the TCP where the nominal "
           f"machine puts it, tabulated on {g['nodes'][0]} × {g['nodes'][1]} × {g['nodes'][2]} nodes over the travel{at}, "
           "and the error a controller applying each table leaves, over the nodes and the midpoints between them "
           "(`mtacc compensate --tables` writes the files).</p>")
    out += figure(plots.compensation_residuals(result), "TCP position error left by each table")
    entries = [(t["format"], t) for t in result["tables"]]
    for key, label in (("linuxcnc_kins", lambda k: f"LinuxCNC {k['kins']} pins"), ("siemens_toolholder", lambda k: f"SINUMERIK $TC_CARR type {k['type']}")):
        if result[key]["applicable"]:
            entries.append((f"{label(result[key])} (over the rotary axes' poses)", result[key]))
    # Along the user's test path, when one was given: what each output leaves where the machine works.
    along = "check_program" in result
    def moving(r):
        return f"{r['moving_forward_max_um']:.3f} / {r['moving_backward_max_um']:.3f}" if "moving_forward_max_um" in r else "—"
    rows = [[name, f"{t['residual']['after_max_um']:.3f}", f"{t['residual']['after_rms_um']:.3f}", moving(t["residual"]),
             *([f"{t['along_program']['after_max_um']:.3f}"] if along else []), t["carries"], "; ".join(t.get("not_carried", [])) or "—"]
            for name, t in entries]
    header = ["table", "largest [µm]", "RMS [µm]", "moving forward / backward, largest [µm]",
              *([f"along {result['check_program']}, largest [µm]"] if along else []), "carries", "not carried"]
    out += table(header, rows, left=1)
    rotary = result.get("rotary_positioning", [])
    if rotary:
        out += ("<p class='meta'>The rotary axes' own positioning in the LEC and LinuxCNC files: "
                + "; ".join(f"{r['axis']}: {r['positions']} positions {r['step_deg']:.3g}° apart{', modulo' if r['modulo'] else ''}, "
                            f"largest correction {r['largest_correction_urad']:.1f} µrad, reversal {r['largest_reversal_urad']:.1f} µrad"
                            for r in rotary) + ".</p>")
    return out


def positioning_section(results):
    """ISO 230-2 charts and axis values of each positioning-test file."""
    out = ("<h2>Positioning (ISO 230-2)</h2><p>Accuracy A, systematic deviation E and repeatability R of "
           "positioning in each direction (↑, ↓) and both, range of the mean bidirectional deviation M, reversal "
           "value B and its mean; formulas in docs/conventions.md.</p>")
    for r in results:
        v = r["axis_values"]
        out += figure(plots.positioning_chart(r), f"{html.escape(r['name'])}: deviations of every cycle, means and "
                                                  f"±2 s bands ({len(r['positions'])} targets, {r['cycles']} cycles each way)")
        u = r["uncertainty"]["quantities"]
        out += table(["", "↑", "↓", "bidirectional", "U (k = 2)"],
                     [[q, f"{v[q + '_forward']:.3f}", f"{v[q + '_backward']:.3f}", f"{v[q]:.3f}", f"{u[q]['U']:.3f}"]
                      for q in ("A", "E", "R")]
                     + [[q, "", "", f"{v[key]:.3f}", f"{u[key]['U']:.3f}" if key in u else ""]
                        for q, key in (("M", "M"), ("B", "B"), ("B mean", "B_mean"))])
        defaulted = r["uncertainty"]["defaulted"]
        out += (f"<p class='meta'>U after ISO/TR 230-9 with {html.escape(r['uncertainty']['instrument'])}"
                + (f"; defaults for {html.escape(', '.join(defaulted))}" if defaulted else "") + ".</p>")
        out += "".join(f"<p>Note: {html.escape(n)}.</p>" for n in r["notes"])
        out += f"<p class='meta'>{html.escape(r['file'])}, values in {r['unit']}.</p>"
    return out


def decomposition_section(result):
    """Andolfatto et al. 2011: the recorded TCP errors split over the feeds."""
    tests = result["tests"]
    out = ("<h2>Error decomposition (Andolfatto et al. 2011)</h2><p>The tool relative to the workpiece measured along one trajectory at "
           f"{len(tests)} feeds, split into servo contouring (c), link (l), motion (m), thermal drift (td) and dynamic (d) "
           f"errors; motion errors fitted on the {result['reference_feed_mm_per_min']:g} mm/min test (Legendre degree "
           f"{result['degree']} in the normalised {result['parameter']}"
           + (f"; {result['reference_samples_left_out']} samples where its axes accelerate left out" if result["reference_samples_left_out"] else
              "; every sample")
           + f"), {result['interpolation']} resampling, the drift constant in the {result['drift_frame']} frame. The mean of the dynamic error is "
           "booked as drift, and only the sum of link and motion errors is fixed by the reference test.</p>")
    if result.get("link_uncertainty"):
        worst = [max(t["link_uncertainty_um"]["max"][d] for t in tests) for d in range(3)]
        out += (f"<p>Link errors from an identification ({len(result['link_uncertainty']['parameters'])} parameters): their standard "
                f"uncertainty along the path is at most {worst[0]:.3f}, {worst[1]:.3f}, {worst[2]:.3f} um in x, y, z (k = 1).</p>")
    out += figure(plots.decomposition_over_feeds(result), "Shares, largest errors and dynamic RMS over the feeds")
    slowest, fastest = min(tests, key=lambda t: t["feed_mm_per_min"]), max(tests, key=lambda t: t["feed_mm_per_min"])
    for t in [slowest] if slowest is fastest else [slowest, fastest]:
        if "series" in t:
            out += figure(plots.decomposition_along_path(t), f"The contributions along the path at {t['feed_mm_per_min']:.0f} mm/min")
    rows = []
    for t in tests:
        s, p = t["shares_percent"], t["split_shares_percent"]
        rows.append([f"{t['feed_mm_per_min']:.0f}", f"{t['clock_offset_ms']:.3f}" + ("" if t["clock_offset_estimated"] else " (given)"),
                     f"{s['contouring']:.1f} / {s['quasi_static']:.1f} / {s['dynamic']:.1f}",
                     " / ".join(f"{p[k]:.1f}" for k in ("contouring", "link", "motion", "drift", "dynamic")),
                     " ".join(f"{v:.2f}" for v in t["drift_um"]), " ".join(f"{v:.3f}" for v in t["dynamic_rms_um"])])
    out += table(["feed [mm/min]", "clock offset [ms]", "c / qs / d [%] (eq. 21)", "c / l / m / td / d [%] (Table 1)",
                  "drift x y z [µm]", "d RMS x y z [µm]"], rows, left=0)
    return out


def drift_section(result):
    """A thermal drift test (ISO 230-3, the 1991 BCR report): curves, hysteresis and the regression on the temperatures."""
    name = html.escape(os.path.basename(result["file"]))
    along = result.get("position_axis")
    out = (f"<h2>Drift test: {name}</h2><p>{html.escape(result['test'][0].upper() + result['test'][1:])}: "
           f"{result['samples']} samples over {result['duration_s'] / 3600:.1f} h, "
           f"{len(result['sensors'])} temperature sensors. The drift is taken from the first sample; each direction is "
           "regressed on the temperatures" + (f", each coefficient linear in the position of {along}" if along else "") +
           ", the sensors chosen stepwise by five-fold cross-validated RMS in contiguous blocks. "
           "A model that needs more sensors than the best single one explains is one that a single sensor cannot "
           "(the 1991 BCR report's conclusion)." +
           (" The machine at rest, each direction's range is its environmental temperature variation error (ETVE)."
            if "ETVE" in result["test"] else "") + "</p>")
    out += figure(plots.drift_test_curves(result), "Drift and tilts over time with each model's prediction, the residuals, the temperatures")
    if "hysteresis_sensor" in result:
        out += figure(plots.drift_hysteresis(result), "Warm-up and cool-down against the temperature that changes most")
    rows = []
    for d in result["directions"]:
        unit = d["unit"].replace("u", "µ")
        h = d.get("hysteresis")
        m = d.get("model")
        rows.append([d["direction"], f"{d['largest']:.2f} {unit} at {d['largest_at_s'] / 3600:.2f} h", f"{d['range']:.2f}",
                     f"{h['difference']:.2f} at {h['at_C']:.1f} °C" if h else "-",
                     ", ".join(f"{s['sensor']} ({s['coefficient_per_K']:.3g} ± {s['standard_error_per_K']:.2g}"
                               + (f", {s['coefficient_per_K_per_mm']:+.3g} ± {s['standard_error_per_K_per_mm']:.2g} per mm {along}" if along else "")
                               + ")" for s in m["sensors"]) if m else "-",
                     f"{m['cross_validated_rms']:.3f}" if m else "-",
                     f"{m['best_single_sensor']}: {m['best_single_sensor_rms']:.3f}" if m else "-"])
    out += table(["direction", "largest drift", "range" + (" (ETVE)" if "ETVE" in result["test"] else ""), "hysteresis (cool − warm)",
                  "sensors (per K ± 1 s.e.)", "cross-validated RMS",
                  "best single sensor"], rows)
    return out


def thermal_section(state):
    """The thermal state the report's machine is evaluated at: each scale's temperatures and
    expansion, and the spindle's drift its temperatures predict."""
    name = html.escape(os.path.basename(state["file"]))
    out = f"<h2>Thermal state: {name}</h2><p>Every figure of this report is the warm machine's."
    if state["scales"]:
        out += (" Each scale's expansion (the temperature linear between its sensors, the 1991 BCR report §2.7) is added to its axis's "
                "positioning error. A warm scale reads short, so the axis goes the expansion beyond its command.")
    if "spindle" in state:
        out += (" The spindle's drift, predicted from its temperatures by the model of a spindle drift test (ISO 230-3, "
                "the 1991 BCR report §2.6), moves the spindle: its location errors take the drift at the test's probe set 1 and the tilts.")
    out += "</p>"
    if state["scales"]:
        out += figure(plots.thermal_state_scales(state), "Temperatures along each scale and the scale's expansion over the travel")
        out += table(["axis", "sensors [mm]", "temperatures [°C]", "reference", "α [1/K]", "largest expansion [µm]"],
                     [[s["axis"], ", ".join(f"{p:g}" for p in s["sensors_mm"]), ", ".join(f"{t:.2f}" for t in s["temperatures_C"]),
                       f"{s['reference_mm']:g} mm, {s['reference_temperature_C']:g} °C", f"{s['expansion_per_K']:.3g}",
                       f"{s['largest_um']:.2f}"] for s in state["scales"]])
    if "spindle" in state:
        spindle = state["spindle"]
        temperatures = ", ".join(f"{html.escape(s['name'])} {s['temperature_C']:.2f} °C" for s in spindle["sensors"])
        tcp = spindle["at_tcp_um"]
        out += (f"<p>Spindle at {temperatures}; probe set 1 {spindle['probe_above_tcp_mm']:g} mm above the TCP. At the TCP the tool "
                f"moves by ({tcp[0]:.2f}, {tcp[1]:.2f}, {tcp[2]:.2f}) µm.</p>")
        out += table(["direction", "predicted drift", "± 1 σ (a new reading)"],
                     [[d["direction"], f"{d['drift']:.2f} {d['unit']}", f"{d['sigma']:.2f} {d['unit']}"] for d in spindle["directions"]])
    return out


def build_report(machine, output=None, errors=None, load=None, samples=None, plan=None, data=None, structure=None, compare=None,
                 positioning=None, plate=None, component=None, drift=None, thermal=None, decomposition=None, progress=None):
    """Writes <output>/<machine>-report.html atomically (output: a folder, default the current one)
    and returns its path; the options as `mtacc report` takes them (each list one file or several),
    progress(step) told of each step."""
    o = _read_options("report", _options(output=output, errors=errors, load=load, samples=samples, plan=plan, data=data,
                                         structure=structure, compare=compare, positioning=positioning, plate=plate,
                                         component=component, drift=drift, thermal=thermal, decomposition=decomposition))
    machine_path, output_dir, errors, load, samples = machine, o["output"], o["errors"], o["load"], o["samples"]
    plan, data, structure, compare, positioning = o["plan"], o["data"], o["structure"], o["compare"], o["positioning"]
    plates, components, drift, thermal, decomposition = o["plate"], o["component"], o["drift"], o["thermal"], o["decomposition"]
    start = time.perf_counter()
    steps = ["machine", "error budget", "volumetric error maps", "circular test", "5-axis circle", "cone frustum",
             "cubic machining test", "writing"]
    if plan:
        steps.insert(-1, "identification")
    if structure:
        steps.insert(-1, "structural dynamics")
    if positioning:
        steps.insert(-1, "positioning")
    if components:
        steps.insert(-1, "component errors")
    if plates:
        steps.insert(-1, "plates")
    if decomposition:
        steps.insert(-1, "error decomposition")
    if drift:
        steps.insert(-1, "drift tests")
    done = []

    def step(name):
        done.append(name)
        if progress:
            progress(f"report: [{len(done)}/{len(steps)}] {name}")

    # Every input is read before the first progress line, so that bad input ends in one line.
    if os.path.exists(output_dir) and not os.path.isdir(output_dir):
        raise InputError(f"output: '{output_dir}' is a file; name a folder for the report")
    machine = Machine(machine_path, errors, load=load, thermal=thermal)
    from . import thermal_state
    thermal_result = thermal_state(machine_path, thermal) if thermal else None
    # The stiffness grid takes at most 12 positions per axis (its section states how many it used).
    stiffness = machine.stiffness(min(samples, 12)) if machine.check()["stiffness_changes"] else None
    if stiffness:
        steps.insert(-1, "finite stiffness")
    linear_with_travel = {a["name"] for a in machine.axes if a["type"] == "linear" and a["travel"] is not None}
    compensation = machine.compensation_tables(nodes=(11, 11, 11)) if {"X", "Y", "Z"} <= linear_with_travel else None
    if compensation:
        steps.insert(-1, "after compensation")
    budget = machine.budget(samples=samples)
    if data and not plan:
        raise InputError("data: measured files need --plan (the parameters to identify and how the runs were planned)")
    observability = machine.observability(plan) if plan else None
    measured = [machine.read_measurement(f) for f in data]
    if structure:
        from . import Structure
        Structure(structure)
        if compare:
            Structure(compare)
    from . import positioning as evaluate_positioning
    positioning_results = [evaluate_positioning(f) for f in positioning]
    from . import drift_test
    drift_results = [drift_test(f, series_points=DRIFT_SERIES_POINTS) for f in drift]
    component_results = [machine.fit_component(f) for f in components]
    plate_results = [machine.compare_plate(f) for f in plates]
    decomposition_result = machine.decompose(decomposition, series=DECOMPOSITION_SERIES_POINTS) if decomposition else None
    step("machine")
    parts = [f"<h1>Accuracy report: {html.escape(machine.name)}</h1>",
             f'<p class="meta">{html.escape(machine.file)} · structure {html.escape(machine.structure)} · '
             f'generated {datetime.datetime.now().strftime("%Y-%m-%d %H:%M")} by mtacc'
             + (f' · at the thermal state {html.escape(os.path.basename(thermal))}' if thermal else "") + "</p>"]

    grid = machine.working_volume_grid(samples)
    combined = np.linalg.norm(machine.tcp_errors(grid)[:, :3], axis=1)
    step("error budget")
    parts.append(f'<p class="key">Largest TCP position error over the working volume ({len(grid)} poses): '
                 f"<b>{combined.max():.2f} µm</b> (median {np.median(combined):.2f} µm). "
                 f'Largest single contributor: <b>{html.escape(budget["entries"][0]["error"])}</b> '
                 f'({budget["entries"][0]["max_position_error_um"]:.2f} µm).</p>')

    parts.append("<h2>Machine</h2>")
    parts.append(figure(plots.chain_schematic(machine), "Kinematic chain from the tool through the bed to the workpiece"))
    rows = []
    for a in machine.axes:
        unit = "mm" if a["type"] == "linear" else "deg"
        travel = "continuous" if a["travel"] is None else f'{a["travel"][0]:g} … {a["travel"][1]:g} {unit}'
        rows.append([a["name"], a["type"], a["side"], "({:.3g}, {:.3g}, {:.3g})".format(*a["direction"]),
                     "({:.4g}, {:.4g}, {:.4g})".format(*a["location_mm"]), travel, a["error_frame"]])
    parts.append(table(["axis", "type", "side", "direction", "location [mm]", "travel", "errors act in"], rows, left=3))
    if thermal_result:
        parts.append(thermal_section(thermal_result))

    params = machine.errors
    rows = []
    for name in params:
        unit = params.unit(name)
        value = params[name] * (1e3 if unit == "mm" else 1e6)
        rows.append([name, f"{value:.3f}", "µm" if unit == "mm" else "µrad"])
    parts.append(f"<h2>Error parameters</h2><p>{len(rows)} non-zero of {len(params.names())} parameters "
                 "(ISO 230-1 names; conventions in docs/conventions.md).</p>")
    parts.append(table(["parameter", "value", "unit"], rows))

    basis = ("each non-zero error of the description alone, at its value" if budget["basis"] == "model"
             else "every error alone at 10 µm / 30 µrad")
    parts.append(f"<h2>Error budget</h2><p>{basis}; largest deviation over a grid of {samples} positions per axis "
                 f"({budget['poses']} poses).</p>")
    parts.append(figure(plots.budget_bar_chart(budget), "Largest TCP deviation of each error alone"))
    parts.append(table(["rank", "error", "magnitude", "max TCP dev. [µm]", "max tilt [µrad]", "worst pose"],
                       [[k + 1, e["error"], f'{e["magnitude"]:.3g} {e["unit"]}', f'{e["max_position_error_um"]:.3f}',
                         f'{e["max_orientation_error_urad"]:.2f}', fmt_pose(e["worst_pose"])]
                        for k, e in enumerate(budget["entries"][:15])], left=0))

    linear = [a["name"] for a in machine.axes if a["type"] == "linear"]
    maps = ""
    if {"X", "Y"} <= set(linear):
        maps += figure(plots.volumetric_error_map(machine, ("X", "Y")), "TCP position error over the X-Y plane")
    if {"X", "Z"} <= set(linear):
        maps += figure(plots.volumetric_error_map(machine, ("X", "Z")), "TCP position error over the X-Z plane")
    rotary = [a for a in machine.axes if a["type"] == "rotary" and a["travel"] is not None]
    if rotary and {"X", "Y"} <= set(linear):
        tilt = rotary[0]
        angle = 30.0 if tilt["travel"][0] <= 30.0 <= tilt["travel"][1] else tilt["travel"][0]
        maps += figure(plots.volumetric_error_map(machine, ("X", "Y"), fixed={tilt["name"]: angle}),
                       f'TCP position error over the X-Y plane with {tilt["name"]} = {angle:g}°')
    parts.append("<h2>Volumetric error maps</h2>" + maps)
    try:
        machine.tcp_uncertainty([0.0] * len(machine.axis_names))
        known = True
    except InputError:  # errors that no identification wrote: no covariance
        known = False
    if known and {"X", "Y"} <= set(linear):
        parts.append("<h2>What the identified model does not know</h2><p>The covariance of the identified parameters (the errors "
                     "file's record) carried to the TCP, first order: after compensating with this model, the residual lies "
                     "within this k = 2 bound at about 95 % of the positions (tests/python/test_compensation_uncertainty.py).</p>"
                     + figure(plots.uncertainty_map(machine, ("X", "Y")), "k = 2 uncertainty of the TCP over the X-Y plane")
                     + (figure(plots.uncertainty_map(machine, ("X", "Z")), "k = 2 uncertainty of the TCP over the X-Z plane")
                        if "Z" in linear else ""))
    step("volumetric error maps")
    parts.append(circle_test(machine))
    step("circular test")
    parameters = set(machine.errors.names())
    top = next((e["error"] for e in budget["entries"] if e["error"] in parameters), None)
    parts.append(five_axis_circle(machine, top))
    step("5-axis circle")
    parts.append(cone_section(machine))
    step("cone frustum")
    if machine.cone_preset_name() is not None:
        parts.append(cubic_section(machine_path, errors, load))
    step("cubic machining test")
    if plan:
        section, identified_model = identification_section(machine, plan, observability, data, measured)
        parts.append(section)
        step("identification")
    if structure:
        parts.append(dynamics_section(structure, compare))
        step("structural dynamics")
    if components:
        parts.append(components_section(component_results))
        step("component errors")
    if stiffness:
        parts.append(stiffness_section(stiffness))
        step("finite stiffness")
    if compensation:
        parts.append(compensation_section(compensation))
        step("after compensation")
    if plates:
        parts.append(plates_section(plate_results))
        step("plates")
    if decomposition:
        parts.append(decomposition_section(decomposition_result))
        step("error decomposition")
    if positioning:
        parts.append(positioning_section(positioning_results))
        step("positioning")
    if drift:
        parts.extend(drift_section(r) for r in drift_results)
        step("drift tests")

    elapsed = time.perf_counter() - start
    parts.append(f'<p class="meta">Built in {elapsed:.1f} s.</p>')
    document = html_page(f"mtacc report: {machine.name}", parts)
    os.makedirs(output_dir, exist_ok=True)
    base = os.path.splitext(os.path.basename(machine.file))[0]
    target = os.path.join(output_dir, f"{base}-report.html")
    if plan and identified_model:
        _write_atomically(os.path.join(output_dir, f"{base}-identified.yaml"), identified_model)
    _write_atomically(target, document)
    step("writing")
    return target


def html_page(title, parts):
    """A self-contained report page: the style, the check that it loads without an error, the parts."""
    return ("<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            f"<title>{html.escape(title)}</title>{STYLE}{CHECK_SCRIPT}</head><body>" + "\n".join(parts) + "</body></html>")


def report_command(argv, prog, description, arguments, write):
    """The `python3 -m` entry of a report that a CLI command runs: MACHINE, --html, --errors and its own
    `arguments` [(flag, help)], then write(machine, args); a bad input is one line and exit status 2."""
    parser = argparse.ArgumentParser(prog=prog, description=description)
    parser.add_argument("machine", help="machine file, or the name of a bundled machine")
    for flag, help_text in arguments:
        parser.add_argument(flag, required=True, help=help_text)
    parser.add_argument("--html", required=True, help="the report to write")
    parser.add_argument("--errors", help="errors file")
    args = parser.parse_args(argv)
    try:
        write(Machine(args.machine, errors=args.errors), args)
    except InputError as e:
        print(f"mtacc: error: {e}", file=sys.stderr)
        return 2
    print(args.html)
    return 0


def _write_atomically(target, text):
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(target) or ".", prefix=".report-", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise


def main(argv=None):
    """The command line of `mtacc report` (the CLI runs this with its flags), made from the
    report's option schema, as the CLI's are."""
    parser = argparse.ArgumentParser(prog="mtacc report", description="Write the HTML accuracy report of a machine.")
    parser.add_argument("machine", help="machine file, or the name of a bundled machine")
    for field in _option_fields("report"):
        names = ["--" + field["key"].replace("_", "-")] + (["-o"] if field["key"] == "output" else [])
        several = field["kind"] in ("list", "numbers")
        parser.add_argument(*names, dest=field["key"], action="append" if several else "store", help=field["help"])
    args = parser.parse_args(argv)
    options = {key: value for key, value in vars(args).items() if key != "machine"}
    try:
        path = build_report(args.machine, **options, progress=lambda s: print(s, file=sys.stderr, flush=True))
    except (InputError, UnreachablePose) as e:
        message = str(e)
        first = message.split(":", 1)[0]
        if f"--{first}" in parser._option_string_actions:  # a workflow key: named as the option
            message = "--" + message
        else:  # a file or name as a whole: named by the option that gave it
            given = {value: name for name, value in vars(args).items() if isinstance(value, str)}
            given.update({value: name for name, values in vars(args).items() if isinstance(values, list) for value in values})
            if first in given:
                name = given[first]
                message = (name if name == "machine" else "--" + name) + ": " + message
        print(f"mtacc: error: {message}", file=sys.stderr)
        return 2
    print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
