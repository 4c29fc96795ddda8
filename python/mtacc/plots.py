"""Figures of a machine and its errors. Every function returns a matplotlib Figure;
volumetric_error_map also returns the data it plots with return_data=True, as (figure, data)."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import InputError  # noqa: E402

SIDE_COLOURS = {"tool": "#1f77b4", "workpiece": "#d62728", "bed": "#555555"}


def chain_schematic(machine):
    """The structure code as a chain of boxes from the tool through the bed to the workpiece,
    each axis with its type and direction."""
    axes = {a["name"]: a for a in machine.axes}
    tool_side = list(reversed(machine.tool_chain))  # tool first
    items = [("tool", "tool", None)] + [(n, "tool", axes[n]) for n in tool_side]
    items += [("bed", "bed", None)] + [(n, "workpiece", axes[n]) for n in machine.workpiece_chain]
    items += [("workpiece", "workpiece", None)]
    fig, ax = plt.subplots(figsize=(max(6.0, 1.35 * len(items)), 2.6))
    for i, (name, side, axis) in enumerate(items):
        colour = SIDE_COLOURS[side]
        box = matplotlib.patches.FancyBboxPatch((i - 0.4, -0.35), 0.8, 0.7, boxstyle="round,pad=0.05",
                                                facecolor=colour if axis is None else "white",
                                                edgecolor=colour, linewidth=2)
        ax.add_patch(box)
        ax.text(i, 0.08, name, ha="center", va="center", fontsize=12, weight="bold",
                color="white" if axis is None else colour)
        if axis is not None:
            d = axis["direction"]
            kind = {"linear": "linear", "rotary": "rotary", "spindle": "spindle"}[axis["type"]]
            ax.text(i, -0.18, kind, ha="center", va="center", fontsize=8, color="#333")
            ax.text(i, -0.55, f"({d[0]:.2g}, {d[1]:.2g}, {d[2]:.2g})", ha="center", va="center", fontsize=7,
                    color="#333")
        if i:
            ax.annotate("", xy=(i - 0.45, 0), xytext=(i - 0.55, 0), arrowprops=dict(arrowstyle="-", color="#999"))
    ax.set_xlim(-0.7, len(items) - 0.3)
    ax.set_ylim(-0.8, 0.7)
    ax.axis("off")
    ax.set_title(f"Kinematic chain {machine.structure_tool_first}  (tool side blue, workpiece side red; "
                 "direction = tool relative to workpiece)", fontsize=9)
    fig.tight_layout()
    return fig


def budget_bar_chart(budget, top=20):
    """Largest TCP deviation of each error alone (the `budget` result), largest first."""
    entries = budget["entries"][:top]
    names = [f'{e["error"]} ({e["magnitude"]:.3g} {e["unit"]})' for e in entries]
    values = [e["max_position_error_um"] for e in entries]
    fig, ax = plt.subplots(figsize=(7.5, 0.28 * len(entries) + 1.2))
    y = np.arange(len(entries))
    ax.barh(y, values, color="#4c72b0")
    ax.set_yticks(y, names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("largest TCP deviation over the working volume [µm]")
    ax.grid(axis="x", alpha=0.3)
    fig.tight_layout()
    return fig


def _plane_grid(machine, plane, fixed, samples):
    """Axis positions over a plane of two linear axes across their travel, the others at `fixed`
    (dict, mm/deg; default mid-travel for linear, 0 for rotary): (q, u, v, base)."""
    names = machine.axis_names
    axes = {a["name"]: a for a in machine.axes}
    for n in fixed or {}:
        if n not in names:
            raise InputError(f"fixed: '{n}' is not an axis of {machine.name} (axes: {', '.join(names)})")
        if n in plane:
            raise InputError(f"fixed: '{n}' is an axis of the plane {plane[0]}-{plane[1]}, which runs over its travel")
    base = []
    for n in names:
        a = axes[n]
        if fixed and n in fixed:
            base.append(float(fixed[n]))
        elif a["type"] == "linear":
            base.append(0.5 * (a["travel"][0] + a["travel"][1]))
        else:
            t = a["travel"]
            base.append(0.0 if t is None or t[0] <= 0.0 <= t[1] else t[0])
    i, j = names.index(plane[0]), names.index(plane[1])
    u = np.linspace(*axes[plane[0]]["travel"], samples)
    v = np.linspace(*axes[plane[1]]["travel"], samples)
    uu, vv = np.meshgrid(u, v)
    q = np.tile(base, (uu.size, 1))
    q[:, i] = uu.ravel()
    q[:, j] = vv.ravel()
    return q, u, v, base


def _along(machine, err, axis):
    """The TCP error component along an axis's direction of motion (workpiece frame)."""
    direction = np.asarray(next(a["direction"] for a in machine.axes if a["name"] == axis), float)
    return err[:, :3] @ direction


def volumetric_error_map(machine, plane=("X", "Y"), fixed=None, samples=41, return_data=False):
    """|TCP position error| over a plane of two linear axes across their travel, other axes at
    `fixed` (dict {axis: mm or deg}; default mid-travel for linear, 0 for rotary; a name that is
    not an axis is refused). Arrows: the error along the two axes' directions of motion.
    With return_data, (figure, data): data["u"] (samples,) and data["v"] (samples,) the two axes'
    positions [mm], data["errors"] (samples, samples, 6) the TCP errors [um, urad] indexed [v, u]
    (numpy.meshgrid's default "xy" order), data["magnitude"] (samples, samples) [um], data["pose"]
    the other axes' positions."""
    q, u, v, base = _plane_grid(machine, plane, fixed, samples)
    names = machine.axis_names
    i, j = names.index(plane[0]), names.index(plane[1])
    shape = (len(v), len(u))
    err = machine.tcp_errors(q)
    magnitude = np.linalg.norm(err[:, :3], axis=1).reshape(shape)
    fig, ax = plt.subplots(figsize=(6.4, 5.0))
    mesh = ax.imshow(magnitude, origin="lower", extent=(u[0], u[-1], v[0], v[-1]), cmap="viridis",
                     interpolation="bilinear", aspect="equal")
    fig.colorbar(mesh, ax=ax, label="|TCP position error| [µm]")
    step = max(1, samples // 10)
    du, dv = _along(machine, err, plane[0]).reshape(shape), _along(machine, err, plane[1]).reshape(shape)
    if np.any(du != 0.0) or np.any(dv != 0.0):
        uu, vv = np.meshgrid(u, v)
        ax.quiver(uu[::step, ::step], vv[::step, ::step], du[::step, ::step], dv[::step, ::step], color="white", alpha=0.8)
    others = ", ".join(f"{n}={b:g}" for k, (n, b) in enumerate(zip(names, base)) if k not in (i, j))
    ax.set_title(f"Volumetric error over {plane[0]}-{plane[1]} ({others})", fontsize=9)
    ax.set_xlabel(f"{plane[0]} [mm]")
    ax.set_ylabel(f"{plane[1]} [mm]")
    fig.tight_layout()
    if not return_data:
        return fig
    pose = {n: b for k, (n, b) in enumerate(zip(names, base)) if k not in (i, j)}
    return fig, {"u": u, "v": v, "errors": err.reshape(shape + (6,)), "magnitude": magnitude, "pose": pose}


def uncertainty_map(machine, plane=("X", "Y"), fixed=None, samples=31):
    """What an identified model does not know of the TCP over a plane of two linear axes (as
    volumetric_error_map): the k = 2 uncertainty 2 sqrt(u_x² + u_y² + u_z²) [µm] its
    identification's covariance leaves (Machine.tcp_uncertainty), which after compensating with
    the model bounds the residual."""
    q, u, v, base = _plane_grid(machine, plane, fixed, samples)
    names = machine.axis_names
    i, j = names.index(plane[0]), names.index(plane[1])
    k2 = 2 * np.linalg.norm(machine.tcp_uncertainty(q), axis=1).reshape(len(v), len(u))
    fig, ax = plt.subplots(figsize=(6.4, 5.0))
    mesh = ax.imshow(k2, origin="lower", extent=(u[0], u[-1], v[0], v[-1]), cmap="magma", interpolation="bilinear", aspect="equal")
    fig.colorbar(mesh, ax=ax, label="TCP uncertainty, k = 2 [µm]")
    others = ", ".join(f"{n}={b:g}" for k, (n, b) in enumerate(zip(names, base)) if k not in (i, j))
    ax.set_title(f"Uncertainty of the compensated TCP over {plane[0]}-{plane[1]} ({others})", fontsize=9)
    ax.set_xlabel(f"{plane[0]} [mm]")
    ax.set_ylabel(f"{plane[1]} [mm]")
    fig.tight_layout()
    return fig


def _relative_errors(machine, plane, fixed, reference, samples):
    """TCP errors over a plane grid minus the error at `reference` (the two axes; default their
    travel start): (errors, u, v, base, reference pose)."""
    q, u, v, base = _plane_grid(machine, plane, fixed, samples)
    names = machine.axis_names
    ref = q[:1].copy()
    for k, axis in enumerate(plane):
        ref[0, names.index(axis)] = (reference or {}).get(axis, (u, v)[k][0])
    return machine.tcp_errors(q) - machine.tcp_errors(ref), u, v, base, ref


def relative_error_vectors(machine, plane=("X", "Z"), fixed=None, reference=None, samples=8, magnification=None):
    """The 1991 BCR report Fig. 5.2: the TCP error vectors over a plane of two linear axes (the others at
    `fixed`), relative to the error at `reference` (dict of the two axes; default their travel
    start), drawn magnified at the grid points in the plane of the two axes' directions."""
    err, u, v, base, ref = _relative_errors(machine, plane, fixed, reference, samples)
    names = machine.axis_names
    du, dv = _along(machine, err, plane[0]), _along(machine, err, plane[1])
    largest = max(np.hypot(du, dv).max(), 1e-12)
    scale = magnification or 0.45 * min(u[1] - u[0], v[1] - v[0]) / largest
    uu, vv = np.meshgrid(u, v)
    fig, ax = plt.subplots(figsize=(7, 5.6))
    ax.plot(uu.ravel(), vv.ravel(), "+", color="0.6")
    ax.quiver(uu.ravel(), vv.ravel(), du * scale, dv * scale, angles="xy", scale_units="xy", scale=1, color="#c0392b", width=0.004)
    ax.set_aspect("equal")
    ax.set_xlabel(f"{plane[0]} [mm]")
    ax.set_ylabel(f"{plane[1]} [mm]")
    others = ", ".join(f"{n}={b:g}" for n, b in zip(names, base) if n not in plane)
    at = ", ".join(f"{n}={ref[0, names.index(n)]:g}" for n in plane)
    ax.set_title(f"TCP error along {plane[0]}, {plane[1]} relative to {at} ({others}); arrows × {scale:.3g} µm⁻¹·mm, "
                 f"largest {largest:.1f} µm", fontsize=9)
    fig.tight_layout()
    return fig


def error_component_surface(machine, plane=("X", "Z"), axis="Y", fixed=None, reference=None, samples=25):
    """The 1991 BCR report Fig. 5.3: one component of the TCP error (along `axis`'s direction of motion) as a
    surface over a plane of two linear axes, relative to `reference` as in relative_error_vectors."""
    err, u, v, base, _ = _relative_errors(machine, plane, fixed, reference, samples)
    names = machine.axis_names
    w = _along(machine, err, axis).reshape(len(v), len(u))
    uu, vv = np.meshgrid(u, v)
    fig = plt.figure(figsize=(7, 5.4))
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(uu, vv, w, cmap="viridis", linewidth=0.2, edgecolor="0.3")
    ax.set_xlabel(f"{plane[0]} [mm]")
    ax.set_ylabel(f"{plane[1]} [mm]")
    ax.set_zlabel(f"error along {axis} [µm]")
    others = ", ".join(f"{n}={b:g}" for n, b in zip(names, base) if n not in plane)
    ax.set_title(f"TCP error along {axis} over {plane[0]}-{plane[1]} ({others})", fontsize=9)
    fig.tight_layout()
    return fig


def sensitivity_along_path(machine, q_path, parameter, direction=None, s=None):
    """d(TCP)/d(parameter) along a path of axis positions (n, axes), per unit of the parameter
    (µm/µm or µm/µrad); with `direction`, also its projection (the sensitivity coefficient)."""
    q_path = np.asarray(q_path, float)
    s = np.arange(len(q_path)) if s is None else np.asarray(s)
    cols = machine.jacobian(q_path.reshape(len(q_path), -1), [parameter])[1][:, :3, 0]
    scale = 1.0 if machine.errors.unit(parameter) == "mm" else 1e-3
    cols *= scale
    unit = "µm/µm" if scale == 1.0 else "µm/µrad"
    fig, ax = plt.subplots(figsize=(7.0, 3.4))
    for k, label in enumerate("xyz"):
        ax.plot(s, cols[:, k], label=f"d{label}")
    if direction is not None:
        n = np.asarray(direction, float)
        n = n / np.linalg.norm(n, axis=-1, keepdims=True)
        k_coeff = np.sum(cols * n, axis=1)
        ax.plot(s, k_coeff, "k--", label="along normal (k)")
    ax.set_ylabel(f"sensitivity to {parameter} [{unit}]")
    ax.set_xlabel("path parameter")
    ax.legend(fontsize=8, ncol=4)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def axis_positions_along_path(machine, q_path, s=None, s_label="path parameter"):
    """Each commanded axis along a path (mm, deg)."""
    q_path = np.asarray(q_path, float)
    s = np.arange(len(q_path)) if s is None else np.asarray(s)
    names = machine.axis_names
    axes = {a["name"]: a for a in machine.axes}
    fig, panels = plt.subplots(len(names), 1, figsize=(7.0, 1.3 * len(names) + 0.6), sharex=True)
    for k, (ax, n) in enumerate(zip(np.atleast_1d(panels), names)):
        ax.plot(s, q_path[:, k], color="#1f77b4" if axes[n]["type"] == "linear" else "#d62728")
        ax.set_ylabel(f"{n} [{'mm' if axes[n]['type'] == 'linear' else 'deg'}]", fontsize=8)
        ax.grid(alpha=0.3)
    np.atleast_1d(panels)[-1].set_xlabel(s_label)
    fig.tight_layout()
    return fig


def _magnified_polar(reference_label=None, limits=True):
    """A polar figure for deviations magnified about a reference circle of radius 1: the reference
    (grey) and, with `limits`, the dashed circles at 1 -+ 0.4 that a deviation of full scale reaches."""
    fig = plt.figure(figsize=(5.0, 5.0))
    ax = fig.add_subplot(projection="polar")
    theta = np.linspace(0, 2 * np.pi, 361)
    ax.plot(theta, np.ones_like(theta), color="#888", lw=1, label=reference_label)
    for r in (0.6, 1.4) if limits else ():
        ax.plot(theta, np.full_like(theta, r), color="#bbb", lw=0.8, ls="--")
    ax.set_ylim(0, 1.5)
    ax.set_rticks([])
    return fig, ax


def polar_deviation(angle_deg, deviation_um, title="Radial deviation", remove_mean=True):
    """Polar plot of a deviation around a circle, magnified about a reference circle as ballbar
    software shows it: the reference (grey) is the mean (or zero), and the scale bar in the
    title gives the deviation that spans from the reference to the dashed limit circles."""
    angle = np.radians(np.asarray(angle_deg, float))
    dev = np.asarray(deviation_um, float)
    mean = float(dev.mean()) if remove_mean else 0.0
    rel = dev - mean
    half = float(np.max(np.abs(rel))) if rel.size else 0.0
    half = half if half > 0 else 1.0
    fig, ax = _magnified_polar("reference")
    ax.plot(angle, 1.0 + 0.4 * rel / half, color="#d62728", lw=1.6, label="deviation")
    ref = f"mean {mean:+.2f} µm removed" if remove_mean else "reference = 0"
    ax.set_title(f"{title}\nPV {np.ptp(dev):.2f} µm; dashed circles = ±{half:.2f} µm; {ref}", fontsize=9)
    ax.legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    return fig


def measured_cone_form(cone, title=None):
    """The measured cone section beside the simulation (`Machine.cone(measured=...)`): the measured
    deviation normal to the cone (red) and the simulated one of the machine's errors at the same
    angles (blue), magnified about a reference circle, as seed 000 Fig. 3.58 shows the measured form."""
    measured = cone["measured"]
    comparison = measured["comparison"]
    section = next(s for s in measured["cone_sections"] if s["name"] == comparison["section"])
    order = np.argsort(np.asarray(section["phi_deg"], float))
    angle = np.radians(np.asarray(section["phi_deg"], float)[order])
    both = {"measured": np.asarray(section["normal_um"], float)[order],
            "simulated": np.asarray(comparison["simulated_normal_um"], float)[order]}
    half = max(float(np.max(np.abs(v))) for v in both.values()) or 1.0
    fig, ax = _magnified_polar()
    for (label, values), colour in zip(both.items(), ("#d62728", "#1f77b4")):
        ax.plot(np.append(angle, angle[0]), 1.0 + 0.4 * np.append(values, values[0]) / half, color=colour, lw=1.4,
                label=f"{label}: {np.ptp(values):.2f} µm")
    ax.set_title(f"{title or 'Cone section ' + comparison['section'] + ', normal form'}\n"
                 f"dashed circles = ±{half:.2f} µm; RMS difference {comparison['rms_difference_um']:.2f} µm", fontsize=9)
    ax.legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    return fig


def polar_axis_positions(machine, phi_deg, q):
    """Radial representation of the axis positions over the path (Bossoni 2009 Fig. 3.43): each axis
    scaled to its own range, 1 = mid-range, the dashed circles its extremes."""
    phi = np.radians(np.asarray(phi_deg, float))
    q = np.asarray(q, float)
    fig = plt.figure(figsize=(5.4, 5.4))
    ax = fig.add_subplot(projection="polar")
    theta = np.linspace(0, 2 * np.pi, 361)
    for r in (0.6, 1.4):
        ax.plot(theta, np.full_like(theta, r), color="#bbb", lw=0.8, ls="--")
    axes = {a["name"]: a for a in machine.axes}
    for k, name in enumerate(machine.axis_names):
        v = q[:, k]
        half = 0.5 * np.ptp(v)
        if half <= 1e-9:
            continue
        unit = "mm" if axes[name]["type"] == "linear" else "deg"
        ax.plot(np.append(phi, phi[0]), np.append(1 + 0.4 * (v - (v.max() - half)) / half, 1 + 0.4 * (v[0] - (v.max() - half)) / half),
                label=f"{name} ({v.min():.1f} … {v.max():.1f} {unit})")
    ax.set_ylim(0, 1.5)
    ax.set_rticks([])
    ax.set_title("Axis positions over φ, each scaled to its range", fontsize=9)
    ax.legend(loc="lower left", fontsize=7, bbox_to_anchor=(-0.1, -0.12))
    fig.tight_layout()
    return fig


def normal_components(phi_deg, normals, frame="machine"):
    """Components of the surface normal over the path: the sensitive direction of the test."""
    normals = np.asarray(normals, float)
    fig, ax = plt.subplots(figsize=(7.0, 3.0))
    for k, label in enumerate("xyz"):
        ax.plot(phi_deg, normals[:, k], label=f"n{label}")
    ax.set_xlabel("φ [deg]")
    ax.set_ylabel(f"normal ({frame} frame)")
    ax.set_ylim(-1.05, 1.05)
    ax.legend(fontsize=8, ncol=3)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def box_plot(groups, ylabel="equivalent cone form error [µm]"):
    """Box plots (whiskers at minimum and maximum, box at the quartiles, median line) of one
    or more samples: {label: values}."""
    fig, ax = plt.subplots(figsize=(4.5, 4.0))
    labels = list(groups)
    ax.boxplot([np.asarray(groups[k], float) for k in labels], whis=(0, 100), labels=labels,
               medianprops=dict(color="#d62728", lw=2), boxprops=dict(color="#1f77b4"))
    ax.set_ylabel(ylabel)
    ax.grid(axis="y", alpha=0.3)
    fig.tight_layout()
    return fig


def ballbar_polar(result, title=None):
    """Polar ballbar trace (both directions) magnified about the bar length, with the fitted
    eccentric circle c0 + e . d(angle) (least-squares first harmonics, dashed)."""
    angle = np.radians(np.asarray(result["angle_deg"], float))
    dl = np.asarray(result["readings_um"], float)[:, 0]
    sense = np.asarray(result["sense"] or [1] * len(dl))
    e1, e2 = result["eccentricity_plot_um"]
    fit = result["offset_um"] + e1 * np.cos(angle) + e2 * np.sin(angle)
    half = max(float(np.max(np.abs(dl - dl.mean()))), float(np.max(np.abs(fit - dl.mean()))), 1e-3)
    scale = 0.4 / half
    fig, ax = _magnified_polar("nominal", limits=False)
    for s, colour, label in ((1, "#1f77b4", "counter-clockwise"), (-1, "#d62728", "clockwise")):
        sel = sense == s
        if sel.any():
            ax.plot(angle[sel], 1.0 + scale * (dl[sel] - dl.mean()), color=colour, lw=1.4, label=label)
    order = np.argsort(angle)
    ax.plot(angle[order], 1.0 + scale * (fit[order] - dl.mean()), color="#2ca02c", lw=1.2, ls="--",
            label="fitted eccentricity")
    ax.set_title(f"{title or result['name']}\ndeviation ±{half:.2f} µm full scale about L = {result['length_mm']:g} mm; "
                 f"eccentricity ({e1:+.2f}, {e2:+.2f}) µm", fontsize=9)
    ax.legend(loc="lower left", fontsize=7)
    fig.tight_layout()
    return fig


def identified_values(result, truth=None):
    """Identified machine parameters with their 95 % intervals (1.96 u), lengths and angles on
    separate axes; `truth` (name -> value in the same unit) adds the simulated values."""
    estimates = result["estimates"]
    names = [e["parameter"] for e in estimates]
    values = np.array([e["value"] for e in estimates])
    u = np.array([e["standard_uncertainty"] for e in estimates])
    units = [e["unit"] for e in estimates]
    keep = [k for k, e in enumerate(estimates) if not e["setup"]]  # machine parameters, not set-up errors
    groups = [(unit, [k for k in keep if units[k] == unit]) for unit in ("um", "urad")]
    groups = [(unit, ks) for unit, ks in groups if ks]
    fig, axes = plt.subplots(1, len(groups), figsize=(4.5 * len(groups), 3.6), squeeze=False)
    for ax, (unit, ks) in zip(axes[0], groups):
        x = np.arange(len(ks))
        ax.errorbar(x, values[ks], yerr=1.96 * u[ks], fmt="o", color="#1f77b4", capsize=3, label="identified ± 95 %")
        if truth:
            ax.plot(x, [truth.get(names[k], np.nan) for k in ks], "x", color="#d62728", label="simulated")
        ax.set_xticks(x, [names[k] for k in ks], rotation=45, fontsize=8)
        ax.set_ylabel("µm" if unit == "um" else "µrad")
        ax.axhline(0, color="#aaa", lw=0.8)
        ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def plan_runs(runs, axis_names):
    """What the operator will see the machine do: each run's axis positions over its poses (mm
    for linear, degrees for rotary axes; an axis that does not move is left out), one panel per
    run, titled with its instrument and where its sphere or work ball is placed."""
    cols = min(3, len(runs))
    rows = (len(runs) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 2.4 * rows), squeeze=False)
    for ax, r in zip(axes.flat, runs):
        q = np.asarray(r["q"], float)
        for k, name in enumerate(axis_names):
            if np.ptp(q[:, k]) > 1e-9:
                ax.plot(np.arange(1, len(q) + 1), q[:, k], ".-", lw=0.8, ms=3, label=name, color=f"C{k}")  # an axis keeps its colour
        placed = "" if r["target_mm"] is None else " at (" + ", ".join(f"{v:.4g}" for v in r["target_mm"]) + ") mm"
        ax.set_title(f"{r['name']}: {r['instrument']}{placed}", fontsize=8)
        ax.set_xlabel("pose", fontsize=7)
        ax.tick_params(labelsize=7)
        if ax.lines:
            ax.legend(fontsize=6)
    for ax in axes.flat[len(runs):]:
        ax.set_visible(False)
    axes[0][0].set_ylabel("position [mm, °]")
    fig.tight_layout()
    return fig


def run_residuals(result):
    """Each run's residuals (reading minus model at the estimates) along its poses, one panel per
    run, with the run's RMS; a run whose residuals stand out is where the model misses."""
    runs = result["run_residuals"]
    cols = min(3, len(runs))
    rows = (len(runs) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 2.4 * rows), squeeze=False, sharey=True)
    largest = max(r["max_um"] for r in runs)
    for ax, r in zip(axes.flat, runs):
        values = np.asarray(r["residuals_um"], float)
        for c in range(values.shape[1]):
            ax.plot(values[:, c], ".-", lw=0.8, ms=3, label="dx dy dz".split()[c] if values.shape[1] == 3 else "dL")
        ax.set_title(f"{r['run']}: RMS {r['rms_um']:.2f} µm", fontsize=8,
                     color="#d62728" if r["max_um"] >= 0.5 * largest and largest > 0 else "black")
        ax.axhline(0, color="#aaa", lw=0.8)
        ax.tick_params(labelsize=7)
    for ax in axes.flat[len(runs):]:
        ax.set_visible(False)
    axes[0][0].set_ylabel("residual [µm]")
    axes[0][0].legend(fontsize=6)
    fig.tight_layout()
    return fig


def singular_values(observability):
    """Singular values of the plan's column-normalised Jacobian (log scale); a drop of many
    decades marks a combination the plan cannot determine."""
    sv = np.asarray(observability["singular_values"], float)
    fig, ax = plt.subplots(figsize=(6.0, 3.0))
    floor = sv[sv > 0].min() * 1e-3 if (sv > 0).any() else 1e-16
    ax.semilogy(np.arange(1, len(sv) + 1), np.maximum(sv, floor), "o-", color="#1f77b4")
    ax.set_xlabel("index")
    ax.set_ylabel("singular value")
    ax.set_title(f"rank {observability['rank']} of {len(sv)}, condition {observability['condition']:.3g}", fontsize=9)
    fig.tight_layout()
    return fig


def frf_plot(frequencies, h, title="FRF of the TCP relative to the workpiece"):
    """Magnitude (log) and phase of the direct terms Hxx, Hyy, Hzz and of the cross-talk, with
    the grey 2 % of the direct response that Bossoni 2009 draws as the measurement uncertainty of
    cross-talk (L5700-5716)."""
    f = np.asarray(frequencies, float)
    h = np.asarray(h)
    fig, axes = plt.subplots(2, 2, figsize=(9.0, 5.6), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    names = "xyz"
    colours = ("#d62728", "#2ca02c", "#1f77b4")
    for k in range(3):
        axes[0, 0].semilogy(f, np.abs(h[:, k, k]), color=colours[k], label=f"H{names[k]}/F{names[k]}")
        axes[1, 0].plot(f, np.degrees(np.angle(h[:, k, k])), color=colours[k])
    pairs = [(1, 0), (2, 0), (2, 1)]
    for (i, j), colour in zip(pairs, ("#9467bd", "#8c564b", "#e377c2")):
        axes[0, 1].semilogy(f, np.abs(h[:, i, j]), color=colour, label=f"H{names[i]}/F{names[j]}")
        axes[1, 1].plot(f, np.degrees(np.angle(h[:, i, j])), color=colour)
    axes[0, 1].semilogy(f, 0.02 * np.abs(h[:, 0, 0]), color="#aaa", ls="--", label="2 % of Hx/Fx")
    axes[0, 0].set_title("direct", fontsize=9)
    axes[0, 1].set_title("cross-talk", fontsize=9)
    for ax in axes[0]:
        ax.set_ylabel("|H| [µm/N]")
        ax.legend(fontsize=7)
    for ax in axes[1]:
        ax.set_ylabel("phase [°]")
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylim(-185, 185)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return fig


def mode_shape_view(structure, modes, index, at=None):
    """The structure's bodies as boxes in two views (Y-Z and X-Y), undeformed (grey) and
    displaced by mode `index` (coloured by the axis that moves them, Bossoni 2009 Fig. 6.2),
    scaled to a visible deflection."""
    at = at or {}
    shape = np.asarray(modes["modes"][index]["shape"])
    bodies = structure.bodies
    travel_shift = {a["name"]: at.get(a["name"], 0.0) for a in structure.axes}
    direction = {"X": np.array([1.0, 0, 0]), "Y": np.array([0, 1.0, 0]), "Z": np.array([0, 0, 1.0])}
    span = max(max(b["size_mm"]) for b in bodies)
    motion = np.array([np.linalg.norm(shape[6 * i:6 * i + 3]) * 1e3 for i in range(len(bodies))])  # mm
    scale = 0.15 * span / max(motion.max(), 1e-12)
    colours = {"X": "#d62728", "Y": "#2ca02c", "Z": "#1f77b4"}
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 4.2))
    for ax, (u, v), label in zip(axes, ((1, 2), (0, 1)), ("Y-Z view", "X-Y view")):
        for i, b in enumerate(bodies):
            move = sum((travel_shift.get(a, 0.0) * direction.get(a, 0) for a in b["moved_by"]), np.zeros(3))
            c = np.array(b["centre_mm"]) + move  # centre of gravity: the body turns about it
            box = np.array(b["box_centre_mm"]) + move - c
            half = np.array(b["size_mm"]) / 2
            corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [-1, -1]], float)
            pts = np.tile(box, (5, 1))
            pts[:, u] += corners[:, 0] * half[u]
            pts[:, v] += corners[:, 1] * half[v]
            ax.plot(c[u] + pts[:, u], c[v] + pts[:, v], color="#bbb", lw=0.8)
            t, r = shape[6 * i:6 * i + 3] * 1e3 * scale, shape[6 * i + 3:6 * i + 6] * scale
            moved = pts + t + np.cross(r, pts)
            colour = colours.get(b["moved_by"][-1], "#555") if b["moved_by"] else "#555"
            ax.plot(c[u] + moved[:, u], c[v] + moved[:, v], color=colour, lw=1.4)
        ax.set_aspect("equal")
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("XYZ"[u] + " [mm]")
        ax.set_ylabel("XYZ"[v] + " [mm]")
    fig.suptitle(f"mode {index + 1}: {modes['modes'][index]['frequency_hz']:.1f} Hz (deflection magnified)", fontsize=10)
    fig.tight_layout()
    return fig


def dynamics_map(result, title=None):
    """A quantity over a grid of two axes as a colour map (Bossoni 2009 Fig. 7.7)."""
    fig, ax = plt.subplots(figsize=(5.2, 4.2))
    mesh = ax.pcolormesh(result["a_mm"], result["b_mm"], np.asarray(result["values"]).T, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label=f"{result['quantity']} [{result['unit'].replace('um', 'µm')}]")
    ax.set_xlabel(f"{result['axes'][0]} [mm]")
    ax.set_ylabel(f"{result['axes'][1]} [mm]")
    ax.set_title(title or result["quantity"], fontsize=9)
    fig.tight_layout()
    return fig


def _extent(grid, shape):
    x0, y0, h = grid["x0"], grid["y0"], grid["spacing"]
    return [x0, x0 + shape[1] * h, y0, y0 + shape[0] * h]


def _zone_outlines(ax, result, labels=None):
    half = result["zone_size_mm"] / 2
    for k, z in enumerate(result["zones"]):
        x, y = z["centre_mm"]
        ax.add_patch(matplotlib.patches.Rectangle((x - half, y - half), 2 * half, 2 * half, fill=False, lw=0.8,
                                                  edgecolor="#333"))
        text = z["name"] if labels is None else f'{z["name"]}\n{labels[k]}'
        ax.text(x, y, text, ha="center", va="center", fontsize=7)


def cubic_layout(result, every=20):
    """The cubic test seen from above: zones, every `every`-th pass of each zone's zig-zag tool path
    (CL points), and the tool vector's horizontal part (arrow towards the holder)."""
    fig, ax = plt.subplots(figsize=(5.2, 5.2))
    half = result["block_mm"] / 2
    cx, cy = result["block_centre_mm"]
    ax.add_patch(matplotlib.patches.Rectangle((cx - half, cy - half), 2 * half, 2 * half, fill=False, lw=1.5))
    for z, tips in zip(result["zones"], result["tool_tips"]):
        passes = tips.reshape(-1, 2, 3)[::every]
        for p in passes:
            ax.plot(p[:, 0], p[:, 1], color="#1f77b4", lw=0.6)
        x, y = z["centre_mm"]
        i, j, _ = z["tool_vector"]
        if abs(i) + abs(j) > 1e-9:
            ax.annotate("", xy=(x + 8 * i, y + 8 * j), xytext=(x, y), arrowprops=dict(arrowstyle="->", color="#d62728"))
    _zone_outlines(ax, result, [" ".join(f"{k}={v:g}" for k, v in z["axes"].items() if k in "ABC") for z in result["zones"]])
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title("Zones, tool paths (every %dth pass) and tool tilt (red)" % every, fontsize=9)
    fig.tight_layout()
    return fig


def cubic_surface_map(result, limit_um=None):
    """The machined minus the error-free surface referenced to the reference zone's plane (the
    simulated counterpart of Li et al. 2021 Fig. 16), with each zone's mean height."""
    dev = result["referenced_deviation_um"]
    limit = limit_um or max(1e-3, float(np.percentile(np.abs(dev), 99.5)))
    fig, ax = plt.subplots(figsize=(6.2, 5.2))
    image = ax.imshow(dev, origin="lower", extent=_extent(result["grid"], dev.shape), cmap="RdBu_r", vmin=-limit,
                      vmax=limit, interpolation="antialiased")
    _zone_outlines(ax, result, [f'{z["measured"]["mean_um"]:.2f} µm' for z in result["zones"]])
    fig.colorbar(image, ax=ax, label="height deviation [µm]")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title(f"Simulated surface referenced to zone {result['reference_zone']}", fontsize=9)
    fig.tight_layout()
    return fig


def cubic_zone_bars(with_alignment, on_table):
    """Zone mean heights of the same errors with M_WC (eqs. 10-12) and without (eq. 2): the deviation
    in the workpiece frame, and the surface referenced to zone I, which agree (Li et al. 2021 L243)."""
    names = [z["name"] for z in with_alignment["zones"]]
    x = np.arange(len(names))
    series = [("E with M_WC", [z["deviation"]["mean_um"] for z in with_alignment["zones"]], "#1f77b4"),
              ("E without M_WC", [z["deviation"]["mean_um"] for z in on_table["zones"]], "#ff7f0e"),
              ("without M_WC, referenced to zone I", [z["measured"]["mean_um"] for z in on_table["zones"]], "#2ca02c")]
    fig, ax = plt.subplots(figsize=(7.5, 3.4))
    for k, (label, values, colour) in enumerate(series):
        ax.bar(x + (k - 1) * 0.27, values, 0.27, label=label, color=colour)
    ax.axhline(0, color="#333", lw=0.6)
    ax.set_xticks(x, names)
    ax.set_ylabel("zone mean height [µm]")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def cubic_sensitivity_maps(result, limit=None):
    """k = E / epsilon over the block for each error (Li et al. 2021 eq. 15), with M_WC (top row, Fig. 12)
    and without (bottom row, Fig. 10); colours per error, mm/mm or mm/rad. The colour scale is at
    least 0.05 mm/mm or 1 mm/rad, so that an error without effect, whose map holds only the
    scallops' sampling (about 0.001 mm/mm), shows white."""
    maps = result["sensitivity_maps"]
    names = list(maps)
    units = {k["parameter"]: k["unit"] for k in result["sensitivities"]}
    fig, axes = plt.subplots(2, len(names), figsize=(1.9 * len(names) + 0.6, 4.4), squeeze=False)
    for c, name in enumerate(names):
        pair = maps[name]
        floor = 0.05 if units[name] == "mm/mm" else 1.0
        scale = limit or max(floor, float(max(np.abs(pair["with_alignment"]).max(), np.abs(pair["on_table"]).max())))
        for r, key in enumerate(["with_alignment", "on_table"]):
            ax = axes[r][c]
            image = ax.imshow(pair[key], origin="lower", extent=_extent(result["sensitivity_grid"], pair[key].shape),
                              cmap="RdBu_r", vmin=-scale, vmax=scale)
            ax.set_xticks([])
            ax.set_yticks([])
            if r == 0:
                ax.set_title(f"{name}\n±{scale:.3g} {units[name]}", fontsize=8)
        axes[0][0].set_ylabel("with M_WC", fontsize=8)
        axes[1][0].set_ylabel("without M_WC", fontsize=8)
    fig.tight_layout()
    return fig


def positioning_chart(result, title=None):
    """The ISO 230-2 chart of a positioning test (`mtacc.positioning`): every deviation by
    direction, the mean unidirectional deviations x̄i↑ and x̄i↓ with their ±2 s bands, and the
    axis values A, B, E, M, R beside them."""
    t = np.array([p["target"] for p in result["positions"]])
    unit, target_unit = result["unit"], result["target_unit"]
    fig, ax = plt.subplots(figsize=(9, 4.8))
    colours = {"forward": "#c0392b", "backward": "#2471a3"}
    for key, arrow in (("forward", "↑"), ("backward", "↓")):
        dev = np.asarray(result[f"deviations_{key}"])
        mean = np.array([p[f"mean_{key}"] for p in result["positions"]])
        s = np.array([p[f"s_{key}"] for p in result["positions"]])
        c = colours[key]
        for j in range(dev.shape[1]):
            ax.plot(t, dev[:, j], ".", color=c, alpha=0.45, markersize=5)
        ax.plot(t, mean, "-", color=c, linewidth=1.8, label=f"x̄i{arrow} (mean of {dev.shape[1]} cycles)")
        ax.plot(t, mean + 2 * s, "--", color=c, linewidth=0.9, label=f"x̄i{arrow} ± 2 si{arrow}")
        ax.plot(t, mean - 2 * s, "--", color=c, linewidth=0.9)
    ax.plot(t, [p["mean"] for p in result["positions"]], ":", color="k", linewidth=1.2, label="x̄i (bidirectional)")
    ax.axhline(0, color="0.6", linewidth=0.6)
    ax.set_xlabel(f"target position [{target_unit}]")
    ax.set_ylabel(f"positional deviation [{unit}]")
    ax.set_title(title or f"ISO 230-2: {result['name']}")
    v = result["axis_values"]
    text = "\n".join([f"{'':9}{'↑':>8}{'↓':>8}{'↑↓':>8}",
                      f"{'A':9}{v['A_forward']:8.2f}{v['A_backward']:8.2f}{v['A']:8.2f}",
                      f"{'E':9}{v['E_forward']:8.2f}{v['E_backward']:8.2f}{v['E']:8.2f}",
                      f"{'R':9}{v['R_forward']:8.2f}{v['R_backward']:8.2f}{v['R']:8.2f}",
                      f"{'M':9}{'':16}{v['M']:8.2f}",
                      f"{'B':9}{'':16}{v['B']:8.2f}",
                      f"{'B mean':9}{'':16}{v['B_mean']:8.2f}",
                      f"[{unit}]"])
    ax.text(1.02, 1.0, text, transform=ax.transAxes, va="top", family="monospace", fontsize=8)
    ax.legend(fontsize=8, loc="lower left")
    fig.tight_layout()
    return fig


def component_fit(result, title=None):
    """A component error as the 1991 BCR report Figs 5.1 and D.x show it (`Machine.fit_component`): every run
    forward and backward, their mean (dashed) and the fitted C1 piecewise polynomial (solid) with
    its ±2 u band; the breaks marked, flagged readings circled."""
    x = np.asarray(result["positions"])
    unit, pos_unit = result["unit"], result["position_unit"]
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for key, colour in (("runs_forward", "#c0392b"), ("runs_backward", "#2471a3")):
        for k, run in enumerate(result[key]):
            ax.plot(x, run, color=colour, alpha=0.18, linewidth=0.7,
                    label=f"{len(result[key])} runs {key.split('_')[1]}" if k == 0 else None)
    ax.plot(x, result["mean"], "k--", linewidth=1.2, label="mean of the runs")
    f = result["fit"]
    grid, value, u = np.asarray(f["grid"]), np.asarray(f["grid_value"]), np.asarray(f["grid_uncertainty"])
    ax.plot(grid, value, color="k", linewidth=1.8, label="fit (C1 piecewise quadratic)")
    ax.fill_between(grid, value - 2 * u, value + 2 * u, color="0.5", alpha=0.3, label="fit ± 2 u")
    for b in f["breaks"]:
        ax.axvline(b, color="0.8", linewidth=0.6, zorder=0)
    flagged = result["disturbances"]["readings"]
    if flagged:
        ys = [result[f"runs_{d['direction']}"][d["run"] - 1][int(np.argmin(abs(x - d["position"])))] for d in flagged]
        ax.plot([d["position"] for d in flagged], ys, "o", mfc="none", color="#8e44ad", markersize=8,
                label=f"flagged ({len(flagged)})")
    ax.set_xlabel(f"{result['axis']} position [{pos_unit}]")
    ax.set_ylabel(f"{result['component']} [{unit}]")
    removed = f", removed: {' '.join(f['removed'])}" if f["removed"] else ""
    ax.set_title(title or f"{result['component']} ({result['iso_name']}): residual {f['residual_std']:.3g} {unit}{removed}")
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    return fig


def plate_vectors(result, magnification=None, title=None):
    """A plate comparison (`Machine.compare_plate`) as the 1991 BCR report Figs 5.4-5.15 draw it: the nominal
    grid with the measured and the modelled deviation of each feature as magnified vectors, and
    the residual beside it."""
    nominal = np.array([f["nominal_mm"] for f in result["features"]])
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.2), sharex=True, sharey=True)
    largest = max(np.abs(np.array([f[k] for f in result["features"] for k in ("measured_um", "simulated_um")])).max(), 1e-9)
    pitch = result["plate"]["pitch_mm"]
    scale = magnification or 0.4 * pitch / largest * 1e3  # the largest vector 0.4 pitch long
    for ax, keys, heading in ((axes[0], (("measured_um", "#c0392b", "measured"), ("simulated_um", "#2471a3", "model")), "deviations"),
                              (axes[1], (("residual_um", "k", "measured − model"),), "residual")):
        ax.plot(nominal[:, 0], nominal[:, 1], "+", color="0.6", markersize=5)
        for key, colour, label in keys:
            d = np.array([f[key] for f in result["features"]]) * 1e-3 * scale
            ax.quiver(nominal[:, 0], nominal[:, 1], d[:, 0], d[:, 1], angles="xy", scale_units="xy", scale=1, color=colour,
                      width=0.004, label=label)
        ax.set_aspect("equal")
        ax.set_xlabel("u [mm]")
        ax.set_title(f"{heading} × {scale:.0f}")
        ax.legend(fontsize=8, loc="upper left")
    axes[0].set_ylabel("v [mm]")
    bound = result["bound_um"]
    fig.suptitle(title or (f"Plate at ({', '.join(f'{c:g}' for c in result['origin_mm'])}) mm: residual RMS "
                           f"{result['residual_rms_um']:.2f} µm" + (f", k = 2 bound {bound:.2f} µm, {result['beyond_bound']} beyond"
                                                                     if bound is not None else "")))
    fig.tight_layout()
    return fig


def artefact_deviations(result, magnification=None, title=None):
    """A calibrated artefact's evaluation (`Machine.evaluate_artefact`): a step gauge or ball bar as its
    deviations along the artefact (u) per direction, measured with its U (k = 2) band and the
    model's dashed; a plate or 3-D artefact as magnified in-plane vectors (measured and model) and,
    probed in three directions, the out-of-plane deviation of each feature in colour."""
    features = result["features"]
    place = np.array([f["calibrated_mm"] for f in features])
    measured = np.array([f["deviation_um"] for f in features])
    model = np.array([f["simulated_um"] for f in features])
    band = np.array([f["expanded_uncertainty_um"] for f in features])
    directions = "uvw"[:measured.shape[1]]
    if result["dimension"] == 1:
        fig, ax = plt.subplots(figsize=(8, 4.5))
        order = np.argsort(place[:, 0])
        for k, (d, colour) in enumerate(zip(directions, ("#c0392b", "#2471a3", "#27ae60"))):
            u = place[order, 0]
            ax.fill_between(u, measured[order, k] - band[order, k], measured[order, k] + band[order, k], color=colour, alpha=0.15)
            ax.plot(u, measured[order, k], "o-", color=colour, label=f"along {d}")
            ax.plot(u, model[order, k], "--", color=colour, lw=1)
        ax.set_xlabel("position along the artefact u [mm]")
        ax.set_ylabel("deviation [µm]")
        ax.legend(fontsize=8)
        ax.set_title(title or f"{result['artefact']}: measured (U band, k = 2) and model (dashed), {result['alignment']['method']}")
        fig.tight_layout()
        return fig
    panels = 2 if measured.shape[1] == 3 else 1
    fig, axes = plt.subplots(1, panels, figsize=(5.5 * panels, 5.2), squeeze=False)
    span = max(np.ptp(place[:, 0]), np.ptp(place[:, 1]), 1e-9)
    largest = max(np.abs(np.r_[measured[:, :2].ravel(), model[:, :2].ravel()]).max(), 1e-9)
    scale = magnification or 0.1 * span / largest * 1e3
    ax = axes[0][0]
    ax.plot(place[:, 0], place[:, 1], "+", color="0.6")
    for values, colour, label in ((measured, "#c0392b", "measured"), (model, "#2471a3", "model")):
        ax.quiver(place[:, 0], place[:, 1], values[:, 0] * 1e-3 * scale, values[:, 1] * 1e-3 * scale, angles="xy", scale_units="xy",
                  scale=1, color=colour, width=0.004, label=label)
    ax.set_aspect("equal")
    ax.set(xlabel="u [mm]", ylabel="v [mm]", title=f"in-plane deviations × {scale:.0f}")
    ax.legend(fontsize=8, loc="upper left")
    if panels == 2:
        ax = axes[0][1]
        limit = max(np.abs(measured[:, 2]).max(), 1e-9)
        points = ax.scatter(place[:, 0], place[:, 1], c=measured[:, 2], cmap="coolwarm", vmin=-limit, vmax=limit, s=80)
        fig.colorbar(points, ax=ax, label="deviation along w [µm]")
        ax.set_aspect("equal")
        ax.set(xlabel="u [mm]", title="out of the plane")
    fig.suptitle(title or f"{result['artefact']}, {result['alignment']['method']} alignment; U (k = 2) up to "
                          f"{result['uncertainty']['largest_um']:.2f} µm")
    fig.tight_layout()
    return fig


def stiffness_changes(result, title=None):
    """The finite-stiffness changes of `Machine.stiffness` as the 1991 BCR report Figs. 4.18 and 4.20 show them:
    one panel per changed axis, each change against its axis's position at the machine's load, one
    line per measured position of the other axis it depends on."""
    terms = result["terms"]
    axes = list(dict.fromkeys(t["axis"] for t in terms))
    fig, panels = plt.subplots(1, len(axes), figsize=(4.8 * len(axes), 4), squeeze=False)
    for ax, name in zip(panels[0], axes):
        for k, t in enumerate(t for t in terms if t["axis"] == name):
            values = np.asarray(t["values"])
            colour = f"C{k}"
            if t["with"] is None:
                ax.plot(t["positions"], values[:, 0], "o-", color=colour, label=t["error"])
                continue
            styles = ("-", "--", ":", "-.")
            for j, at in enumerate(t["with_positions"]):
                ax.plot(t["positions"], values[:, j], "o" + styles[j % 4], color=colour, markersize=3,
                        label=f"{t['error']}, {t['with']} = {at:g}")
        units = sorted({t["unit"] for t in terms if t["axis"] == name})
        ax.axhline(0, color="0.7", linewidth=0.6)
        ax.set_xlabel(f"{name} position")
        ax.set_ylabel(f"change [{', '.join(units)}]")
        ax.legend(fontsize=7)
    fig.suptitle(title or f"Changes of the errors under a workpiece load of {result['workpiece_load_kg']:g} kg")
    fig.tight_layout()
    return fig


def compensation_residuals(result, title=None):
    """The TCP position error left by each controller table of `Machine.compensation_tables`, beside the
    uncorrected error: largest and RMS over the check lattice."""
    tables = result["tables"]
    functions = next(len(t["functions"]) for t in tables if t["format"] == "one-axis")
    names = {"grid": "3-D grid", "one-axis": f"{functions} one-axis functions", "siemens-cec": "Siemens CEC",
             "siemens-lec": "Siemens LEC per axis", "linuxcnc": "LinuxCNC per joint", "heidenhain": "HEIDENHAIN .COM", "isg-volumetric": "TwinCAT/ISG volumetric"}
    labels = ["uncorrected"] + [names[t["format"]] for t in tables]
    largest = [tables[0]["residual"]["before_max_um"]] + [t["residual"]["after_max_um"] for t in tables]
    rms = [tables[0]["residual"]["before_rms_um"]] + [t["residual"]["after_rms_um"] for t in tables]
    fig, ax = plt.subplots(figsize=(7, 3.6))
    y = np.arange(len(labels))
    ax.barh(y - 0.2, largest, height=0.4, label="largest", color="C3")
    ax.barh(y + 0.2, rms, height=0.4, label="RMS", color="C0")
    for k, (a, b) in enumerate(zip(largest, rms)):
        ax.text(a, k - 0.2, f" {a:.2f}", va="center", fontsize=8)
        ax.text(b, k + 0.2, f" {b:.2f}", va="center", fontsize=8)
    ax.set_yticks(y, labels)
    ax.invert_yaxis()
    ax.set_xlabel("TCP position error [µm]")
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(title or "TCP position error left by each table")
    fig.tight_layout()
    return fig



DECOMPOSITION_COLOURS = (("contouring", "contouring c", "#2471a3"), ("link", "link l", "#7d3c98"), ("motion", "motion m", "#229954"),
                         ("drift", "drift td", "#d68910"), ("dynamic", "dynamic d", "#c0392b"))


def decomposition_along_path(test, title=None):
    """One test of `mtacc decompose --json --series N` along the normalised path u (Figs 9-10 form):
    per direction the contouring, link, motion, drift and dynamic errors."""
    series = test["series"]
    u = np.array(series["u"])
    fig, axes = plt.subplots(3, 1, figsize=(11, 7.5), sharex=True)
    for d, ax in enumerate(axes):
        direction = "xyz"[d]
        for key, label, colour in DECOMPOSITION_COLOURS:
            if key == "drift":
                ax.plot(u, np.full_like(u, test["drift_um"][d]), color=colour, linewidth=1.2, label=label)
            else:
                ax.plot(u, series[f"{key}_um"][direction], color=colour, linewidth=0.8, label=label)
        ax.axhline(0, color="#999999", linewidth=0.5)
        ax.set_ylabel(f"{direction} [µm]")
    axes[0].legend(fontsize=8, ncol=5, loc="lower center", bbox_to_anchor=(0.5, 1.0))
    axes[-1].set_xlabel(f"normalised path u (one instrument sample in {series['stride']})")
    fig.suptitle(title or f"Errors along the path at {test['feed_mm_per_min']:.0f} mm/min (Figs 9-10 form)")
    fig.tight_layout()
    return fig


def decomposition_over_feeds(result, title=None):
    """Andolfatto et al. 2011 over the feeds (`mtacc decompose --json`): the five-way mean-norm shares of eq. 21
    stacked per feed (Table 1 form), the largest contouring, quasi-static and dynamic errors per
    direction (Tables 2-3 form), and the dynamic RMS per direction on log axes with the power laws
    of eq. 23 (Fig. 11 form)."""
    tests = result["tests"]
    feeds = np.array([t["feed_mm_per_min"] for t in tests])
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    ax = axes[0]
    bottom = np.zeros(len(tests))
    positions = np.arange(len(tests))
    for key, label, colour in DECOMPOSITION_COLOURS:
        share = np.array([t["split_shares_percent"][key] for t in tests])
        ax.bar(positions, share, bottom=bottom, color=colour, label=label)
        bottom += share
    ax.set_xticks(positions, [f"{f:.0f}" for f in feeds], rotation=45)
    ax.set_xlabel("feed [mm/min]")
    ax.set_ylabel("mean-norm share [%] (five norms, Table 1 form)")
    ax.set_ylim(0, 100)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.25), ncol=3)
    ax = axes[1]
    styles = {"contouring_max_um": ("-", "contouring"), "quasi_static_max_um": ("--", "quasi-static"), "dynamic_max_um": (":", "dynamic")}
    colours = ("#c0392b", "#229954", "#2471a3")
    for key, (style, name) in styles.items():
        values = np.array([t[key] for t in tests])
        for d, colour in enumerate(colours):
            ax.plot(feeds, values[:, d], style, marker="o", markersize=3, color=colour, label=f"{name} {'xyz'[d]}")
    ax.set_xscale("log")
    ax.set_xlabel("feed [mm/min]")
    ax.set_ylabel("largest |error| along the path [µm]")
    ax.legend(fontsize=7, ncol=3)
    ax = axes[2]
    rms = np.array([t["dynamic_rms_um"] for t in tests])
    line = np.geomspace(feeds.min(), feeds.max(), 50)
    for d, colour in enumerate(colours):
        ax.plot(feeds, rms[:, d], "o", color=colour, label=f"{'xyz'[d]}")
        law = result["dynamic_rms_power_law"].get("xyz"[d])
        if law:
            ax.plot(line, law["kappa_um"] * line ** law["exponent"], "-", color=colour, linewidth=1,
                    label=f"{law['kappa_um']:.3g}·F^{law['exponent']:.2f}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("feed [mm/min]")
    ax.set_ylabel("dynamic error RMS [µm]")
    ax.legend(fontsize=8)
    fig.suptitle(title or "Error decomposition over the feeds (Andolfatto et al. 2011)")
    fig.tight_layout()
    return fig


def drift_test_curves(result, title=None):
    """A thermal drift test (`mtacc drift --json` with series): the drift of X, Y, Z and the tilts
    A, B over time with each model's prediction dashed (shaded ± 2 standard deviations of a new
    reading), the displacements' residuals (measured minus predicted), and the temperatures below (with the axis position where the drift
    depends on it)."""
    series = result["series"]
    hours = np.array(series["time_s"]) / 3600
    fig, axes = plt.subplots(4, 1, figsize=(11, 11), sharex=True, gridspec_kw={"height_ratios": [3, 2, 2, 3]})
    colours = {"X": "#c0392b", "Y": "#229954", "Z": "#2471a3", "A": "#7d3c98", "B": "#d68910"}
    for d in result["directions"]:
        ax = axes[0] if d["unit"] == "um" else axes[1]
        ax.plot(hours, d["series"], color=colours[d["direction"]], linewidth=1, label=d["direction"])
        if "predicted" in d:
            sensors = ", ".join(s["sensor"] for s in d["model"]["sensors"]) or "offset"
            ax.plot(hours, d["predicted"], "--", color=colours[d["direction"]], linewidth=1, label=f"{d['direction']} from {sensors}")
            band = 2 * np.array(d["predicted_sigma"])
            ax.fill_between(hours, np.subtract(d["predicted"], band), np.add(d["predicted"], band), color=colours[d["direction"]],
                            alpha=0.15, linewidth=0)
            if d["unit"] == "um":
                axes[2].plot(hours, np.subtract(d["series"], d["predicted"]), color=colours[d["direction"]], linewidth=0.7,
                             label=f"{d['direction']}: cross-validated RMS {d['model']['cross_validated_rms']:.2f} µm")
    axes[0].set_ylabel("drift [µm]")
    axes[1].set_ylabel("tilt [µrad]")
    if not axes[1].lines:
        axes[1].text(0.5, 0.5, "no tilts: the probes are at one height", ha="center", va="center", transform=axes[1].transAxes)
        axes[1].set_yticks([])
    axes[2].set_ylabel("measured − predicted [µm]")
    for name, values in series["temperatures_C"].items():
        axes[3].plot(hours, values, linewidth=1, label=name)
    axes[3].set_ylabel("temperature [°C]")
    axes[3].set_xlabel("time [h]")
    for ax in axes:
        if ax.lines:
            ax.legend(fontsize=7, ncol=2)
    if "position_mm" in series:
        position = axes[3].twinx()
        position.plot(hours, series["position_mm"], color="0.6", linewidth=0.6, drawstyle="steps-post")
        position.set_ylabel(f"{result['position_axis']} [mm]", color="0.4")
    fig.suptitle(title or f"{result['test'][0].upper() + result['test'][1:]}: drift, its prediction, and the temperatures")
    fig.tight_layout()
    return fig


def drift_hysteresis(result, title=None):
    """Each displacement's drift against the hysteresis sensor's temperature: the warm-up and the
    cool-down branches (the 1991 BCR report: 40 or 52 um of Y drift for the same rise)."""
    series = result["series"]
    sensor = result["hysteresis_sensor"]
    temperature = np.array(series["temperatures_C"][sensor])
    peak = int(np.argmax(temperature))
    fig, ax = plt.subplots(figsize=(7, 5))
    colours = {"X": "#c0392b", "Y": "#229954", "Z": "#2471a3"}
    for d in result["directions"]:
        if d["unit"] != "um":
            continue
        drift = np.array(d["series"])
        ax.plot(temperature[:peak + 1], drift[:peak + 1], "-", color=colours[d["direction"]], linewidth=1, label=f"{d['direction']} warming")
        ax.plot(temperature[peak:], drift[peak:], ":", color=colours[d["direction"]], linewidth=1.2, label=f"{d['direction']} cooling")
    ax.set_xlabel(f"{sensor} temperature [°C]")
    ax.set_ylabel("drift [µm]")
    ax.legend(fontsize=8)
    ax.set_title(title or f"Drift against the {sensor} temperature: warm-up and cool-down")
    fig.tight_layout()
    return fig


def thermal_state_scales(state, title=None):
    """A thermal state (`mtacc.thermal_state`): per scale the sensors' temperatures along the axis
    (linear between them, as the model takes them) and the scale's expansion over the travel, zero
    at the reference position."""
    scales = state["scales"]
    fig, axes = plt.subplots(2, len(scales), figsize=(max(7.5, 5.5 * len(scales)), 6.5), squeeze=False, sharex="col")
    for c, s in enumerate(scales):
        top, bottom = axes[0][c], axes[1][c]
        position = np.array(s["position_mm"])
        top.plot(position, np.interp(position, s["sensors_mm"], s["temperatures_C"]), color="#c0392b", linewidth=1)
        top.plot(s["sensors_mm"], s["temperatures_C"], "o", color="#c0392b", label="sensors")
        top.axhline(s["reference_temperature_C"], color="0.5", linewidth=0.8, linestyle=":", label="scale reads true")
        top.set_ylabel("temperature [°C]")
        top.set_title(f"{s['axis']} scale")
        top.legend(fontsize=8)
        bottom.plot(position, s["expansion_um"], color="#2471a3", linewidth=1.2)
        bottom.axvline(s["reference_mm"], color="0.5", linewidth=0.8, linestyle=":", label=f"reference {s['reference_mm']:g} mm")
        bottom.axhline(0, color="0.8", linewidth=0.6)
        bottom.set_xlabel(f"{s['axis']} [mm]")
        bottom.set_ylabel("expansion Δ [µm]")
        bottom.legend(fontsize=8)
    fig.suptitle(title or "Thermal state: temperatures along the scales, their expansion")
    fig.tight_layout()
    return fig


VERDICT_COLOURS = {"pass": "#1e8449", "fail": "#c0392b", "undecided": "#d68910"}


def conformance_chart(test):
    """An acceptance test's values against their tolerances (`Machine.acceptance`, one entry of
    "tests"): each value with its expanded uncertainty U (k = 2) as a bar and whiskers, the
    tolerance as a line, coloured by the verdict of the decision rule."""
    verdicts = test["conformance"]["verdicts"]
    fig, ax = plt.subplots(figsize=(8, 0.6 + 0.55 * len(verdicts)))
    for i, v in enumerate(verdicts):
        y = len(verdicts) - 1 - i
        c = VERDICT_COLOURS[v["verdict"]]
        ax.barh(y, v["value"], height=0.5, color=c, alpha=0.55)
        ax.errorbar(v["value"], y, xerr=v["U"], fmt="none", ecolor="k", capsize=4, linewidth=1)
        ax.plot([v["tolerance"]] * 2, [y - 0.35, y + 0.35], color="k", linewidth=2.2)
        ax.text(max(v["value"] + v["U"], v["tolerance"]) * 1.02, y, v["verdict"], va="center", color=c, fontsize=9)
    ax.set_yticks(range(len(verdicts)), [v["quantity"] for v in reversed(verdicts)])
    right = max(max(v["value"] + v["U"], v["tolerance"]) for v in verdicts)
    ax.set_xlim(0, right * 1.25)
    ax.set_xlabel(f"result ± U (k = 2), tolerance as the black line [{test['unit']}]")
    ax.set_title(f"{test['name']} ({test['standard']})")
    fig.tight_layout()
    return fig


def rotary_test_deviations(test):
    """An ISO 10791-6 rotary-axis test's deviations over the axis's positions (`Machine.acceptance`,
    the "detail" of a rotary test): the R-test's radial, tangential and axial deviations (the sphere
    set at the first position) or the ballbar's length deviation."""
    d = test["detail"]
    fig, ax = plt.subplots(figsize=(9, 4))
    for quantity, values in d["deviations"].items():
        ax.plot(d["axis_position_deg"], values, ".-", markersize=4, label=f"{quantity} (range {d['ranges'][quantity]:.2f} {d['unit']})")
    ax.axhline(0, color="0.6", linewidth=0.6)
    ax.set_xlabel("rotary axis position [deg]")
    ax.set_ylabel(f"deviation [{d['unit']}]")
    ax.set_title(f"{test['name']}: {d['instrument']}")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def geometric_test(test):
    """An ISO 230-1 test from direct measurements (`Machine.acceptance`, the "detail" of a geometric
    test): the mean of the runs along the axis and, for a straightness, its deviations from the
    end-point and least-squares reference lines."""
    d = test["detail"]
    fig, ax = plt.subplots(figsize=(9, 4))
    x = d["positions_mm"]
    ax.plot(x, d["mean"], "o-", markersize=3, color="0.35", label=f"{d['component']}: mean of the runs")
    if "end_point_residual" in d:
        ax.plot(x, d["end_point_residual"], "-", color="#2471a3", label="from the end-point line")
        ax.plot(x, d["least_squares_residual"], "--", color="#c0392b", label="from the least-squares line")
    ax.axhline(0, color="0.6", linewidth=0.6)
    ax.set_xlabel("position [mm]")
    ax.set_ylabel(f"deviation [{d['unit']}]")
    ax.set_title(f"{test['name']} ({d['kind'].replace('_', ' ')})")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def circular_test(test):
    """An ISO 230-4 circular test (`Machine.acceptance`, the "detail" of a circular test): the
    ballbar's length deviation over the angle, each direction apart."""
    d = test["detail"]
    fig, ax = plt.subplots(figsize=(9, 4))
    angle, deviation, sense = (np.asarray(d[k]) for k in ("angle_deg", "deviation", "sense"))
    for s, name, colour in ((1, "counter-clockwise", "#c0392b"), (-1, "clockwise", "#2471a3")):
        if np.any(sense == s):
            ax.plot(angle[sense == s], deviation[sense == s], ".", markersize=3, color=colour, label=name)
    ax.axhline(0, color="0.6", linewidth=0.6)
    ax.set_xlabel("angle in the plane [deg]")
    ax.set_ylabel(f"length deviation [{d['unit']}]")
    ax.set_title(f"{test['name']}: ballbar, radius {d['radius_mm']:g} mm")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def design_uncertainties(result):
    """A measurement design (`Machine.design`): each parameter's predicted k = 2 uncertainty, the
    design's beside the user's plan's when one was given; lengths and angles on their own axes."""
    design, own = result["design"], result.get("own_plan")
    own = own if own and "parameters" in own else None
    groups = [(unit, [k for k, p in enumerate(design["parameters"]) if p["unit"] == unit]) for unit in ("um", "urad")]
    groups = [(unit, ks) for unit, ks in groups if ks]
    fig, axes = plt.subplots(1, len(groups), figsize=(4.6 * len(groups), 3.4), squeeze=False)
    for ax, (unit, ks) in zip(axes[0], groups):
        x = np.arange(len(ks))
        width = 0.38 if own else 0.6
        ax.bar(x - (width / 2 if own else 0), [design["parameters"][k]["u_k2"] for k in ks], width, color="#2471a3",
               label=f"design, {design['time_min']:.1f} min")
        if own:
            ax.bar(x + width / 2, [own["parameters"][k]["u_k2"] for k in ks], width, color="0.65", label=f"your plan, {own['time_min']:.1f} min")
        ax.set_xticks(x, [design["parameters"][k]["name"] for k in ks], rotation=45, ha="right", fontsize=8)
        ax.set_ylabel(f"U (k = 2) [{'µm' if unit == 'um' else 'µrad'}]")
        ax.grid(axis="y", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def design_pareto(result):
    """A measurement design's Pareto table: the TCP's k = 2 uncertainty after compensation over the
    working volume (root mean square and largest) against the machine time, the user's plan marked."""
    rows = [p for p in result["pareto"] if "time_min" in p]
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    t = [p["time_min"] for p in rows]
    ax.plot(t, [p["tcp_rms_k2_um"] for p in rows], "o-", color="#2471a3", label="designs: TCP, root mean square")
    ax.plot(t, [p["tcp_max_k2_um"] for p in rows], "s--", color="#2471a3", alpha=0.6, label="designs: TCP, largest")
    own = result.get("own_plan")
    if own and "tcp_rms_k2_um" in own:
        ax.plot([own["time_min"]], [own["tcp_rms_k2_um"]], "D", color="#c0392b", label="your plan: root mean square")
        ax.plot([own["time_min"]], [own["tcp_max_k2_um"]], "x", color="#c0392b", label="your plan: largest")
    ax.axvline(result["budget_min"], color="0.6", linewidth=0.8, linestyle=":")
    ax.set_xlabel("machine time [min]")
    ax.set_ylabel("TCP uncertainty after compensation, k = 2 [µm]")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def design_set_ups(result):
    """Where the designed plan's spheres sit on the workpiece (x, y and x, z), each numbered as the
    runs' table numbers its set-up."""
    set_ups = []
    for r in result["runs"]:
        if r["target_mm"] is not None and r["set_up"] not in [s for s, _ in set_ups]:
            set_ups.append((r["set_up"], r["target_mm"]))
    fig, axes = plt.subplots(1, 2, figsize=(8.4, 3.8))
    for ax, (i, j, names) in zip(axes, ((0, 1, "xy"), (0, 2, "xz"))):
        ax.plot([0], [0], "+", color="0.4", markersize=12)
        for n, (_, p) in enumerate(set_ups, 1):
            ax.plot(p[i], p[j], "o", color="#c0392b", markersize=9)
            ax.annotate(str(n), (p[i], p[j]), textcoords="offset points", xytext=(6, 6), fontsize=9)
        ax.set_xlabel(f"{names[0]} [mm]")
        ax.set_ylabel(f"{names[1]} [mm]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        ax.set_title(f"workpiece frame, {names}", fontsize=9)
    fig.tight_layout()
    return fig


def design_timeline(result):
    """The designed plan in the order it is run: each run's motion and readings, the set-ups and the
    instruments' mounting, in minutes from the start."""
    fig, ax = plt.subplots(figsize=(9.0, 0.3 * len(result["runs"]) + 1.4))
    clock, seen_set_ups, seen_instruments = 0.0, set(), set()
    labels = []
    for y, r in enumerate(result["runs"]):
        start = clock
        if r["instrument"] not in seen_instruments:
            seen_instruments.add(r["instrument"])
            clock += result["time_model"]["change_min"]
        if r["set_up"] not in seen_set_ups:
            seen_set_ups.add(r["set_up"])
            clock += result["time_model"]["set_up_min"]
        if clock > start:
            ax.barh(y, clock - start, left=start, color="0.75")
        ax.barh(y, r["time_min"], left=clock, color="#2471a3")
        clock += r["time_min"]
        labels.append(r["name"])
    ax.set_yticks(range(len(labels)), labels, fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("minutes from the start (grey: mounting and set-ups; blue: the run)")
    ax.grid(axis="x", alpha=0.3)
    fig.tight_layout()
    return fig
