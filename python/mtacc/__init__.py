"""mtacc: geometric accuracy of multi-axis machine tools.

    import mtacc
    m = mtacc.Machine("tilting-table")           # a bundled machine, or a YAML file
    m.errors["X0C"] = "5 um"                      # set by ISO name (or alias), with a unit
    pos, tool = m.fk([[10, 20, 30, -15, 45]])     # axis positions in mm and degrees
    err = m.tcp_errors(q)                         # (n, 6): dx dy dz [um], ea eb ec [urad]
    q = m.ik_path(tcps, tools, branch="negative") # (n, axes) in mm and degrees
    budget = m.budget()                           # the error budget: the same dict as `mtacc budget --json`

Every result that the command line prints with --json comes back here as the same dict (the
library serialises it once); batch kinematics come back as numpy arrays. Units are those of the
command line: mm and degrees for axis positions, mm for the TCP, um and urad for errors. Error
parameters read back in mm or rad (see Errors.unit). One call per pose costs the Python call
overhead: pass all poses of a batch at once.
"""
import json
import os
from collections.abc import Mapping, MutableMapping

import numpy as np

_DATA = os.path.join(os.path.dirname(__file__), "data")
if os.path.isdir(_DATA):  # the installed package carries its own copy of the bundled data
    os.environ.setdefault("MTACC_DATA_DIR", _DATA)

from ._mtacc import InputError, UnreachablePose, __version__  # noqa: E402
from ._mtacc import Machine as _CoreMachine  # noqa: E402
from ._mtacc import Structure as _CoreStructure  # noqa: E402
from ._mtacc import drift_test as _drift_test  # noqa: E402
from ._mtacc import thermal_state as _thermal_state  # noqa: E402
from ._mtacc import positioning as _positioning  # noqa: E402
from ._mtacc import multitasking as _multitasking  # noqa: E402
from ._mtacc import squareness as _squareness  # noqa: E402
from ._mtacc import yry as _yry  # noqa: E402

__all__ = ["__version__", "Machine", "Errors", "Structure", "InputError", "UnreachablePose", "positioning", "drift_test",
           "thermal_state", "squareness", "yry", "multitasking", "as_json"]


def as_json(result):
    """`result` with its ndarrays as nested lists (complex values as [real, imag]): what
    json.dumps takes, and what the command line's --json prints for the same call."""
    if isinstance(result, dict):
        return {k: as_json(v) for k, v in result.items()}
    if isinstance(result, (list, tuple)):
        return [as_json(v) for v in result]
    if isinstance(result, np.ndarray):
        if np.iscomplexobj(result):
            return np.stack([result.real, result.imag], axis=-1).tolist()
        return result.tolist()
    if isinstance(result, np.generic):
        return result.item()
    return result


def positioning(data, conditions=None, tolerances=None):
    """ISO 230-2 evaluation of a positioning-test file (KEY=value or CSV, docs/file-formats.md),
    as `mtacc positioning --json`: per-target means, reversal, s and R, the axis values A, B, E, M,
    R (keys "A_forward", "A", ... in "axis_values") and the deviations, in um or arcsec ("unit");
    "uncertainty": the ISO/TR 230-9 budget from the measurement conditions file (default: the
    documented defaults) with U (k = 2) per value; with a tolerance file, "conformance": each
    toleranced value's verdict (pass, fail, undecided) by the file's decision rule."""
    return _positioning(_options(data=data, conditions=conditions, tolerances=tolerances))


def squareness(aligned_to, alpha, beta, block=None):
    """Squareness of two axes from a calibrated square probed along both sides (the 1991 BCR report
    App. B.5), as `mtacc squareness --json`: aligned_to "x" or "z", the slopes alpha and beta of the
    lines through the readings along the aligned side and the other, and the square's own
    squareness block (all arcsec); "squareness_arcsec" and the "rule" applied."""
    return _squareness(_options(aligned_to=aligned_to, alpha=alpha, beta=beta, block=block))


def yry(y, ytz1, ytz2, xrx, x1, x2):
    """The Y axis's yaw from two straightness runs of a straightedge at X = x1 and x2 (mm; the 1991
    BCR report eq. B.2), as `mtacc yry --json`: y (mm), ytz1 and ytz2 (um, one per y), xrx (arcsec,
    one value or one per y); "yry_arcsec" per y."""
    def values(v):
        return [float(x) for x in np.atleast_1d(v)]

    return _yry(_options(y=values(y), ytz1=values(ytz1), ytz2=values(ytz2), xrx=values(xrx), x1=x1, x2=x2))


def multitasking(data, errors_out=None):
    """The twelve location errors of a multi-tasking machine with a B head and a C spindle from the
    eccentricities of six ball-bar runs (Applied Sciences 10, 1811, Eqs 17-28), as
    `mtacc multitasking --json`: data is the eccentricities file (docs/file-formats.md); per name of
    the paper's Table 1 the value, its unit (um, arcsec) and the ISO errors it stands for
    ("deviations"). errors_out: also write them as an errors file there."""
    return _multitasking(_options(data=data), _text(errors_out))


def thermal_state(machine, path, points=101):
    """A thermal state (docs/file-formats.md "Thermal states") on `machine` (a file or a bundled
    name): per scale ("scales") the axis, its sensors (mm) and their temperatures (degC), the
    reference position and temperature, and the expansion (um) at `points` positions over the
    travel ("position_mm", "expansion_um", "largest_um"); with a spindle ("spindle") its sensors'
    temperatures, per direction the drift they predict and its standard deviation (um, urad), and
    the drift at the TCP ("at_tcp_um")."""
    return _thermal_state(str(machine), str(path), int(points))


def drift_test(test, sensor=None, folds=None, max_sensors=None, position=None, save_model=None, series_points=0):
    """A thermal drift test (ISO 230-3, the 1991 BCR report; docs/file-formats.md "Drift tests"), as
    `mtacc drift --json`: what test it is ("test"), per direction (X Y Z in um, A B in urad) the
    largest drift and its range, the warm-up / cool-down hysteresis against `sensor` (default: the
    temperature that changes most), and the stepwise regression on the temperatures, with each
    coefficient linear in the position of axis `position` (default: the axis that moves, if one
    does). With series_points > 0 also the curves ("series": time, temperatures and positions; per
    direction its drift and the model's prediction). With save_model, the models are also written
    there as a spindle drift model for a thermal state's `spindle:` (docs/file-formats.md). The
    keyword arguments are the options of `mtacc drift`, with its defaults."""
    options = _options(test=test, sensor=sensor, folds=folds, max_sensors=max_sensors, position=position, save_model=save_model)
    return _drift_test(options, int(series_points))


def _text(value):
    return "" if value is None else str(value)


def _with_arrays(result, *paths):
    """`result` with the numeric lists at `paths` as float ndarrays. A path is a sequence of keys;
    "*" stands for every element of a list (e.g. ("single_errors", "*", "deviation_um")); a path
    that is absent is skipped."""
    def convert(node, path):
        if not path or node is None:
            return
        key, rest = path[0], path[1:]
        if key == "*":
            for item in node:
                convert(item, rest)
        elif isinstance(node, dict) and key in node:
            if rest:
                convert(node[key], rest)
            else:
                node[key] = np.asarray(node[key], dtype=float)

    for path in paths:
        convert(result, path)
    return result


def _options(**given):
    """Keyword arguments as a workflow's option values (the CLI's flags, by the same keys): None
    leaves the workflow's default, a list or tuple gives each item, True/False a flag, anything else
    its text (a number, a path, "0.5 um")."""
    values = {}
    for key, value in given.items():
        if value is None:
            continue
        if isinstance(value, bool):
            values[key] = ["true" if value else "false"]
        elif isinstance(value, (list, tuple)):
            values[key] = [str(v) for v in value]
        else:
            values[key] = [str(value)]
    return values


def _vector(value):
    """(x, y, z) as the CLI's text "x,y,z"; text and None as they are."""
    return value if value is None or isinstance(value, str) else ",".join(repr(float(v)) for v in value)


def _setup_text(setup):
    """Set-up errors {name: "10 um"} as the CLI's text "xW=10 um"; text and None as they are."""
    return setup if setup is None or isinstance(setup, str) else ",".join(f"{name}={value}" for name, value in setup.items())


def _assignments(values, key):
    """{name: number} ({axis: mm or deg}, {tool: mm}), or the CLI's text itself, as the CLI's text
    "B=10.0,C=0.0"; None stays None (the workflow's default)."""
    if values is None or isinstance(values, str):
        return values
    if not isinstance(values, Mapping):
        raise InputError(f"{key}: expected {{name: number}} or the text 'B=10,C=0', not {type(values).__name__}")
    try:
        return ",".join(f"{name}={float(value)!r}" for name, value in values.items())
    except (TypeError, ValueError):
        raise InputError(f"{key}: each value must be a number") from None


class Errors(MutableMapping):
    """The machine's non-zero error parameters by ISO 230-1 name (aliases accepted).

    It behaves like collections.Counter: iteration, len() and `in` cover the non-zero parameters;
    reading a parameter the machine has but that is zero gives 0.0 (and get() its default); a name
    the machine does not have raises KeyError; `del` sets a parameter to zero.

    Units, one rule: a bare number is in the unit the parameter reads back in, mm for a length and
    rad for an angle (unit(name) says which); a string carries its own unit ("10 um", "30 urad",
    "5 arcsec"), and a string without one is refused. Results elsewhere (tcp_errors, budgets) are
    in um and urad, as the command line prints them.
    """

    def __init__(self, core):
        self._core = core

    def __getitem__(self, name):
        try:
            return self._core.get_error(name)
        except InputError as e:
            raise KeyError(str(e)) from None

    def __setitem__(self, name, value):
        self._core.set_error(name, value)

    def __delitem__(self, name):
        self[name]  # KeyError for a name the machine does not have
        self._core.set_error(name, 0.0)

    def __contains__(self, name):
        try:
            return isinstance(name, str) and self._core.get_error(name) != 0.0
        except InputError:
            return False

    def get(self, name, default=None):
        return self[name] if name in self else default

    def __iter__(self):
        return iter(self._core.nonzero_errors())

    def __len__(self):
        return len(self._core.nonzero_errors())

    def __repr__(self):
        return f"Errors({dict(self)!r})"

    def unit(self, name):
        """'mm' or 'rad'."""
        return self._core.error_unit(name)

    def names(self):
        """Every parameter of the machine: location errors, then component-error coefficients."""
        return self._core.check()["parameters"]


class Machine:
    """A machine description with its errors.

    machine: a YAML file or the name of a bundled machine. errors: an errors file (replacing the
    machine file's errors), or a dict {name: value} (the machine file's errors set to zero, then
    these; values as Errors takes them). load: the workpiece load in kg that scales the errors'
    load-dependent stiffness changes (default: their file's workpiece_load). thermal: a thermal
    state (YAML: the temperatures along the scales) whose scale expansion joins the errors
    (default: cold, 20 degC). A Machine copies (copy.copy and copy.deepcopy alike give an
    independent machine) and pickles: its files are read again, its errors set as they were."""

    def __init__(self, machine, errors=None, alignment=None, load=None, thermal=None):
        errors_file = None if isinstance(errors, Mapping) else errors
        self._args = (str(machine), _text(errors_file), _text(alignment), None if load is None else float(load), _text(thermal))
        self._build()
        if isinstance(errors, Mapping):
            self.errors.clear()
            self.errors.update(errors)

    def _build(self):
        self._core = _CoreMachine(*self._args)
        self._description = self._core.check()
        self.errors = Errors(self._core)

    def __getstate__(self):
        return {"args": self._args, "errors": dict(self.errors)}

    def __setstate__(self, state):
        self._args = tuple(state["args"])
        self._build()
        self.errors.clear()
        self.errors.update(state["errors"])

    def __repr__(self):
        def shown_value(name, value):
            length = self.errors.unit(name) == "mm"
            return f"{name}={value * (1e3 if length else 1e6):.4g} {'um' if length else 'urad'}"

        shown = ", ".join(shown_value(k, v) for k, v in list(self.errors.items())[:6])
        more = ", ..." if len(self.errors) > 6 else ""
        return f"<mtacc.Machine {self.name!r}, {len(self.errors)} non-zero errors: {{{shown}{more}}}>"

    def check(self):
        """The machine summary, as `mtacc check --json` (with the current errors)."""
        return self._core.check()

    name = property(lambda self: self._description["name"])
    file = property(lambda self: self._description["file"])
    structure = property(lambda self: self._description["structure"])
    structure_tool_first = property(lambda self: self._description["structure_tool_first"])
    axis_names = property(lambda self: self._description["axis_names"])
    axes = property(lambda self: self._description["axes"])
    tool_chain = property(lambda self: self._description["tool_chain"])
    workpiece_chain = property(lambda self: self._description["workpiece_chain"])
    tool_direction = property(lambda self: np.array(self._description["tool"]["direction"]))

    @staticmethod
    def _q(q):
        q = np.asarray(q, dtype=float)
        return q.reshape(1, -1) if q.ndim == 1 else q

    def fk(self, q, directions=None, nominal=None, threads=None):
        """TCP positions (n, 3) [mm] and tool directions (n, 3) in the workpiece frame.
        q: one pose (axes,) or many (n, axes) [mm, deg]; threads: 0 for every core, else that many.
        The batch is the fast path: many poses in one call run in C++ (below a microsecond a pose).
        One pose a call costs a few microseconds: the compiled model is kept between calls until an
        error is changed."""
        return self._core.fk(self._q(q), directions, _options(nominal=nominal, threads=threads), False)

    def tcp_errors(self, q, directions=None, threads=None):
        """(n, 6): the TCP's position error dx dy dz [um] and orientation error (rotation vector) [urad],
        actual minus nominal, in the workpiece frame. q: one pose (axes,) or many (n, axes) [mm, deg];
        directions: None (every axis standing still, reversal errors not applied) or an int array of
        q's shape with the sign of each axis's motion (+1, -1, 0); threads: 0 for every core."""
        position, orientation = self._core.fk(self._q(q), directions, _options(threads=threads), True)
        return np.hstack([position, orientation])

    def ik(self, tcp, tool=None, branch=None, all=None, with_errors=None, near=None):
        """Solutions for one TCP [mm] and tool direction, as `mtacc ik --json` lists them; with_errors: the
        commands that reach the pose on the machine with its errors (the inverse error model), with the
        nominal pose it started from and the residual (um, urad); near: a pose ({axis: mm or deg}) whose
        rotary angles the solution stays closest to, a free angle at a singular pose kept at its value."""
        result, _ = self._core.ik([], [], _options(tcp=_vector(tcp), tool=_vector(tool), branch=branch, all=all, with_errors=with_errors,
                                                   near=_assignments(near, "near")))
        return result["solutions"]

    def ik_path(self, tcps, tools, branch=None, with_errors=None):
        """Axis positions (n, axes) [mm, deg] along a continuous path through the TCPs (n, 3) [mm] with the
        tool directions (n, 3) (unit vectors, workpiece frame); with_errors: on the machine with its
        errors (as `ik`)."""
        _, q = self._core.ik(np.asarray(tcps, float).tolist(), np.asarray(tools, float).tolist(), _options(branch=branch, with_errors=with_errors))
        return q

    def jacobian(self, q, params=None):
        """(names, J): the derivative of the pose error by each parameter.
        q: one pose (axes,) or many (n, axes) [mm, deg], each within travel.
        J: (6, p) for one pose, (n, 6, p) for many; rows dx, dy, dz [mm] and the rotation vector
        [rad], one column per parameter of `names` (derivative per mm or per rad of the parameter).
        params: the parameters to differentiate by (default: every parameter of the machine)."""
        q = np.asarray(q, dtype=float)
        names, J = self._core.jacobian(self._q(q), list(params or []))
        return names, (J[0] if q.ndim == 1 else J)

    def sensitivity(self, pose, direction=None, parameters=None, epsilon_length=None, epsilon_angle=None):
        """As `mtacc sensitivity --json`: how every error parameter (or those named) moves the TCP at
        `pose` ({axis: mm or deg}, or the CLI's text), per unit of the parameter, and the coefficient
        k = E / epsilon (Li et al. 2021 eq. 15) along `direction` (x, y, z; default the tool
        direction), first order and with the exact model at epsilon_length ("10 um") or
        epsilon_angle ("30 urad")."""
        return self._core.sensitivity(_options(pose=_assignments(pose, "pose"), direction=_vector(direction), parameters=parameters,
                                               epsilon_length=epsilon_length, epsilon_angle=epsilon_angle))

    def sensitivity_coefficient(self, q, parameter, epsilon, direction):
        """Li et al. 2021 eq. 15: k = E / epsilon with the exact model, at one pose q (axes,) [mm, deg]
        within travel; epsilon in mm/rad or with a unit ("10 um"); E is the TCP deviation along
        `direction` (the outward normal, any length but zero) in mm. k is in mm/mm or mm/rad."""
        q = np.asarray(q, dtype=float)
        if q.ndim != 1:
            raise InputError(f"q: one pose, an array of shape (axes,), not {q.shape}")
        return self._core.sensitivity_coefficient(self._q(q), parameter, epsilon, list(map(float, direction)))

    def working_volume_grid(self, samples=5):
        """(samples ** axes, axes) poses [mm, deg]: `samples` positions per axis across its travel, every
        combination, as the budget uses."""
        return self._core.working_volume_grid(samples)

    def budget(self, samples=None, length=None, angle=None, threads=None):
        """The error budget (as `mtacc budget --json`, whose options these keyword arguments are, with
        its defaults): each error alone, its largest TCP deviation [um] and tool tilt [urad] over a grid
        of `samples` (2 to 50, default 5) positions per axis across the travel. Without length and
        angle: each non-zero error of the machine at its value, one entry per component error
        function. With them (with their units, e.g. "10 um", "30 urad"): every location error and
        every component error as a constant of that size."""
        return self._core.budget(_options(samples=samples, length=length, angle=angle, threads=threads))

    def cone(self, preset=None, alpha=None, beta=None, radius=None, centre=None, gamma=None, face_milling=None, points=None,
             chord_tolerance=None, branch=None, feed=None, single_errors=None, monte_carlo=None, limits=None, seed=None,
             gcode=None, cl=None, measured=None):
        """The cone-frustum test piece of Bossoni 2009 (as `mtacc cone --json`, whose options these keyword
        arguments are, with its defaults; angles in deg, lengths in mm): path, axis positions and their
        statistics, the form error of the machine's errors, each error alone, a Monte Carlo over limits.
        preset: "tilting-table", "swivel-head", "double-pivot", "seed000-comparison", "nas979" or "family" (this machine's).
        gcode, cl: files to write the NC program and the CL data to, as `--gcode` and `--cl`.
        measured: CMM points of the machined cone (docs/file-formats.md "Measured cone frustum"): per
        section circularity (least squares, minimum zone), diameter, axis offset and the form per
        point, the best-fit cone, and the section nearest the path beside the simulated form
        ("measured"; plots.measured_cone_form draws it).
        Arrays (n points, s samples, k limits): path["phi_deg"] (n,), path["points_mm"], ["tools"],
        ["normals"], ["normals_machine"] (n, 3), path["q"] (n, axes) [mm, deg]; "deviation_um" and
        "raw_deviation_um" (n,), also per single error; monte_carlo["form_errors_um"] (s,) and
        monte_carlo["drawn"]["values"] (s, k), each limit's drawn value in its unit (["units"], um or
        urad) under its key (["names"]). limits: a limits file (docs/file-formats.md "Error limits";
        default: Bossoni 2009 Table 3.9) or the same mapping as a dict, each range with its units:
        {"X0B": ("-10 um", "10 um"), "EXX.rev": ("0 um", "4 um"), "EXX.lin": ("-3 um", "3 um"),
        "EXX.cyclic": {"range": ("-1 um", "1 um"), "pitch": "30 mm"}}. A location error and a reversal
        (.rev, or .hyst as Bossoni 2009 writes it) are limited by the parameter's own name; ".lin" and
        ".<k>harm" are the error's change over the axis's range on the path (Bossoni 2009 eqs 3.63-3.66),
        not a coefficient per mm, and so have names of their own."""
        limits_yaml = json.dumps({"limits": limits}) if isinstance(limits, Mapping) else ""
        centre_text = None if centre is None else ",".join(repr(float(c)) for c in centre)
        options = _options(preset=preset, alpha=alpha, beta=beta, radius=radius, centre=centre_text, gamma=gamma, face_milling=face_milling,
                           points=points, chord_tolerance=chord_tolerance, branch=branch, feed=feed, single_errors=single_errors,
                           monte_carlo=monte_carlo, limits=None if isinstance(limits, Mapping) else limits, seed=seed, gcode=gcode, cl=cl,
                           measured=measured)
        result = self._core.cone(options, limits_yaml)
        return _with_arrays(result, ("path", "phi_deg"), ("path", "points_mm"), ("path", "tools"), ("path", "normals"),
                            ("path", "normals_machine"), ("path", "q"), ("deviation_um",), ("raw_deviation_um",),
                            ("single_errors", "*", "deviation_um"), ("single_errors", "*", "raw_deviation_um"),
                            ("monte_carlo", "form_errors_um"), ("monte_carlo", "drawn", "values"))

    def cubic(self, test=None, grid=None, inset=None, chord_tolerance=None, sensitivities=None, sensitivity_parameters=None,
              sensitivity_grid=None, threads=None, gcode=None, cl=None, map=None, map_limit=None, heights=None, surface=None,
              zones_out=None, scan=None, scan_grid=None, scan_zones_out=None, trace=None, trace_cl=None):
        """The cubic machining test of Li et al. 2021 (as `mtacc cubic --json`): per zone the clamped axes, the
        deviation E (machined minus error-free surface) and the surface referenced to zone I, as mean
        height (um) and tilts (um/mm); with sensitivities, k = E / epsilon of each error with and
        without M_WC. Adds numpy arrays (ny, nx), row j at y = y0 + (j + 0.5) spacing: "heights_um"
        (the machined surface about the nominal face), "referenced_deviation_um", and per error
        "sensitivity_maps"[name]["with_alignment" | "on_table"] (mm/mm or mm/rad); "tool_tips": the CL
        points (n, 3) of each zone. The keyword arguments are `mtacc cubic`'s options, with its defaults
        (lengths in mm; map_limit with its unit, "10 um"); gcode, cl, map, heights, surface and zones_out
        name files to write as the command does. scan: a scanned face of the block (.csv x,y,z, .ply or
        .stl; docs/file-formats.md "Scanned surfaces"), evaluated on cells of scan_grid mm (0.5) into
        zone planes beside the simulated ones ("scan"); scan_zones_out writes them for cubic_identify.
        trace: the axes' actual positions recorded during the cut (CSV or .npy, time_s and a column per
        axis, mm and deg): the surface machined along them beside the programmed one ("trace", Li et
        al. 2021 eqs 13-14); trace_cl writes their CL data (tool tip and vector)."""
        return self._core.cubic(_options(test=test, grid=grid, inset=inset, chord_tolerance=chord_tolerance, sensitivities=sensitivities,
                                         sensitivity_parameters=sensitivity_parameters, sensitivity_grid=sensitivity_grid,
                                         threads=threads, gcode=gcode, cl=cl, map=map, map_limit=map_limit, heights=heights,
                                         surface=surface, zones_out=zones_out, scan=scan, scan_grid=scan_grid,
                                         scan_zones_out=scan_zones_out, trace=trace, trace_cl=trace_cl))

    def cubic_identify(self, zones, parameters, test=None, noise=None, threads=None, errors_out=None):
        """Errors from the zone results of a cubic machining test (CSV: zone,height_um[,slope_x_um_per_mm,
        slope_y_um_per_mm]), as `mtacc cubic-identify --json`, whose options these keyword arguments are
        (test: the bundled seed001-cubic by default; noise: "0.2 um", default the file's '# noise:' line);
        refuses (InputError) a set the zones cannot determine, naming what they cannot separate.
        errors_out: as identify's."""
        options = _options(zones=zones, parameters=[parameters] if isinstance(parameters, str) else list(parameters), test=test,
                           noise=noise, threads=threads)
        return self._core.cubic_identify(options, _text(errors_out))

    def fit_component(self, data, breaks=None, pieces=None, degree=None, significance=None, period=None, period_zero=None,
                      disturbance_threshold=None, remove_disturbed=None, errors_out=None):
        """A component error fitted to its direct-measurement runs (the 1991 BCR report), as `mtacc fit --json`: the
        runs, their means, the C1 piecewise-polynomial fit (breaks in mm or deg) with its uncertainty,
        the terms removed by the stepwise test, flagged readings, and "yaml", the machine YAML entry.
        errors_out: a path for this machine's errors with the fitted function in place, its coefficients'
        covariance and the data file's hash (an errors file, as `mtacc fit --errors-out`)."""
        options = _options(data=data, breaks=breaks, pieces=pieces, degree=degree, significance=significance, period=period,
                           period_zero=period_zero, disturbance_threshold=disturbance_threshold, remove_disturbed=remove_disturbed)
        return self._core.fit_component(options, _text(errors_out))

    def stiffness(self, samples=None):
        """The finite-stiffness changes of the errors (the 1991 BCR report) at this machine's workpiece load, and the
        largest TCP errors over the working-volume grid (`samples` per axis, 2 to 12, default 5) of the geometric
        errors, of the changes alone and added by them, as `mtacc stiffness --json` (values in um or urad)."""
        return self._core.stiffness(_options(samples=samples))

    def acceptance(self, tests, html=None):
        """Every test of an acceptance tests file (docs/file-formats.md "Acceptance tests"), as `mtacc
        acceptance --json`: "summary" (per test and quantity: value, U at k = 2, tolerance, verdict),
        "overall", and per test its uncertainty budget, its conformance and its own evaluation
        ("detail"). html: also write the HTML acceptance report there (mtacc.acceptance)."""
        result = self._core.acceptance(_options(tests=tests))
        if html is not None:
            from . import acceptance as _report
            _report.write_report(self, result, html)
        return result

    def design(self, time=None, parameters=None, instruments=None, reach=None, criterion=None, noise=None, plan=None, plan_out=None,
               radii=None, spread=None, lengths=None, positions=None, points=None, feed=None, rapid=None, rotary_rapid=None,
               acceleration=None, rotary_acceleration=None, dwell=None, probe_time=None, setup_time=None, change_time=None,
               threads=None, html=None):
        """The measurement plan that determines `parameters` (default: `plan`'s) best in the machine `time`
        available ("30min", "1.5h"), as `mtacc design --json`, whose options these keyword arguments are:
        chosen among the R-test, touch-probe and ballbar runs the `instruments` (default rtest, ballbar)
        can make within the travel, by `criterion` D, A, I (the TCP after compensation over the working
        volume) or "plan" (the largest uncertainty relative to `plan`'s); reach=True instead of a time:
        the shortest design that determines every parameter at least as well as `plan`. "runs" (name,
        instrument, minutes), "design" (time, k = 2 uncertainties, the TCP's), "own_plan" (the same for
        `plan`), "pareto" (time against uncertainty), "plan" (the plan YAML; plan_out writes it).
        noise: per instrument, e.g. "rtest=0.5um,ballbar=1um"; the time model: rapid (mm/min),
        rotary_rapid (deg/min), acceleration (mm/s^2), rotary_acceleration (deg/s^2), dwell and
        probe_time (s per position), setup_time (min per set-up), change_time (min per instrument).
        html: also write the report for the operator there (mtacc.measurement_design)."""
        result = self._core.design(_options(time=time, parameters=parameters, instruments=instruments, reach=reach, criterion=criterion,
                                            noise=noise, plan=plan, plan_out=plan_out, radii=radii, spread=spread, lengths=lengths,
                                            positions=positions, points=points, feed=feed, rapid=rapid, rotary_rapid=rotary_rapid,
                                            acceleration=acceleration, rotary_acceleration=rotary_acceleration, dwell=dwell,
                                            probe_time=probe_time, setup_time=setup_time, change_time=change_time, threads=threads))
        if html is not None:
            from . import measurement_design as _report
            _report.write_report(self, result, html)
        return result

    def rotary_tests(self, axes=None, radius=None, spread=None, length=None, positions=None, points=None, feed=None,
                     plan_out=None, programs=None, decimals=None):
        """The ISO 10791-6 tests around each rotary axis (as `mtacc rotary-tests --json`, whose options these
        keyword arguments are): per axis the R-test at two set-ups (a table axis: the sphere at `radius`
        from the line and `spread` along it; a head axis: the tool ball at the tip and `spread` beyond) and
        the ballbar (`length`) radial, tangential and axial; per test its set-up, sweep, the results on
        this machine (um: R-test radial, tangential, axial ranges with the sphere set at the first
        position; ballbar length range) and the location errors each result sees ("sees": um of range
        per um or urad, each error alone). plan_out: write the plan `simulate`/`identify` read;
        programs: a folder for a G-code program per test, its positions with `decimals` places (default 6)."""
        return self._core.rotary_tests(_options(axes=axes, radius=radius, spread=spread, length=length, positions=positions,
                                                points=points, feed=feed, plan_out=plan_out, programs=programs, decimals=decimals))

    def compensate_program(self, program, tool_length=None, tolerance=None, direction_tolerance=None, check_errors=None):
        """The axis program (G-code) at `program` compensated for this machine's errors, as `mtacc
        compensate --json`, plus "gcode", the compensated program's text. tool_length: {H number: mm
        beyond the machine's tool} for G43 H<n> (or the CLI's text "1=0,2=35.5"); tolerance (um) and
        direction_tolerance (urad): the deviation allowed between written points (default 0.1 um and
        5 urad). "deviation_before" and "deviation_after": the TCP deviation from the program's
        nominal path on the machine with its errors, as written and compensated; check_errors: an
        errors file of this machine (as measured again, or a simulation's truth) both are also run
        on ("check")."""
        return self._core.compensate_program(_options(program=program, tool_length=_assignments(tool_length, "tool_length"),
                                                      tolerance=tolerance, direction_tolerance=direction_tolerance,
                                                      check_errors=check_errors))

    def tcp_uncertainty(self, q):
        """(n, 3): the standard uncertainty (k = 1) of the TCP position [um] along x, y, z of the workpiece
        frame that this model's identification leaves (its errors file's covariance, first order
        through the parameter Jacobian): after compensating with it, what is not known of the residual.
        q: one pose (axes,) or many (n, axes) [mm, deg]. Raises InputError for errors no identification wrote."""
        return self._core.tcp_uncertainty(self._q(q))

    def deviation(self, program, intended=None, tool_length=None, step=None):
        """The program (G-code) run on this machine with its errors, against the nominal path of
        `intended` (another program, at its closest point) or its own, as `mtacc deviation --json`:
        largest and RMS TCP deviation (um), tool direction (urad), per feed block ("blocks", by line),
        sampled every `step` mm of nominal TCP path (at least 4 a block; default 0.5). tool_length:
        {H number: mm beyond the machine's tool} for G43 H<n>, or the CLI's text "1=0,2=35.5"."""
        return self._core.deviation(_options(program=program, intended=intended, tool_length=_assignments(tool_length, "tool_length"),
                                             step=step))

    def compensation_tables(self, nodes=None, pose=None, functions=None, linuxcnc_type=None, check_program=None):
        """Controller tables for this machine, as `mtacc compensate --tables --json`: the correction grid
        over X, Y, Z (`nodes` along each over its travel, default (21, 21, 21)) at `pose` of the other
        axes ({axis: mm or deg}, default 0), its reduction to at most `functions` one-axis functions
        (default 9) and the LinuxCNC COMP_FILE of each axis (linuxcnc_type 1, trims, or 0), each with
        the TCP error a controller applying it leaves ("residual", um), and along `check_program`
        (G-code, "along_program") when given. "contents" holds each file's text by name."""
        nodes = None if nodes is None or isinstance(nodes, str) else ",".join(str(int(n)) for n in nodes)
        return self._core.compensation_tables(_options(nodes=nodes, pose=_assignments(pose, "pose"), functions=functions,
                                                       linuxcnc_type=linuxcnc_type, check_program=check_program))

    def compare_plate(self, data):
        """A measured hole or ball plate (CSV, docs/file-formats.md) against this machine's error model, as
        `mtacc plate --json`: per feature the measured and modelled deviations and the residual (um) with
        the misalignment removed, and the residual's k = 2 bound when the file states the 2S values."""
        return self._core.compare_plate(_options(data=data))

    def evaluate_artefact(self, data):
        """A calibrated artefact measured on this machine (a step gauge, ball bar, plate or 3-D artefact:
        CSV with certificate and measured positions, docs/file-formats.md "Artefact measurements"; a
        plate file is read too), as `mtacc artefact --json`: per feature the deviations along the
        probed directions after the file's alignment, their k = 2 uncertainty, the model's and the
        residual (um); per direction the range, RMS and largest; the alignment and the uncertainty's
        contributors."""
        return self._core.evaluate_artefact(_options(data=data))

    def simulate_artefact(self, layout, output, noise=None, seed=None):
        """Writes the measurement of the artefact in `layout` (an artefact file without measured
        values) that this machine with its errors gives, as `mtacc simulate artefact`; noise: each
        measured coordinate's standard deviation ("0.3 um", default 0)."""
        self._core.simulate_artefact(_options(layout=layout, output=output, noise=noise, seed=seed))

    def decompose(self, set, series=None, drift_frame=None):
        """Andolfatto et al. 2011's decomposition of recorded signals (a decomposition set, docs/file-formats.md), as
        `mtacc decompose --json`: per feed the clock offset (ms), shares of eq. 21 with both denominators,
        drift, maxima and dynamic RMS (um), and the power law of the dynamic RMS over the feeds. With
        series > 0, each test's contributions along the normalised path u ("series", um), at most that
        many points. drift_frame:
        "machine" (Andolfatto et al. 2011's: the drift constant in the machine frame) or "workpiece"; default the set's
        drift_frame, else machine. Warnings (an offset at its search limit, instrument spikes): result["warnings"]."""
        return self._core.decompose(_options(set=set, series=series, drift_frame=drift_frame))

    def simulate_motion(self, program, output, feeds=None, structure=None, noise=None, seed=None, acceleration=None, jerk_time_ms=None,
                        kv=None, feed_forward=None, format=None, clock_offset_ms=None):
        """Andolfatto et al. 2011's virtual machine runs the G-code `program` at each feed (mm/min, FGROUP; default the
        seed's ladder) and writes the command, encoder, instrument and truth signals (format "csv" or
        "npy") and set.yaml into `output`, as `mtacc simulate motion --json`. `structure`: a structure
        model for the dynamic error. `kv` (1/s) and `feed_forward`: one number for every axis or a list
        with one per commanded axis. noise: the instrument's, e.g. "0.2 um" (the default)."""
        return self._core.simulate_motion(_options(program=program, output=output, feeds=feeds, structure=structure, noise=noise, seed=seed,
                                                   acceleration=acceleration, jerk_time_ms=jerk_time_ms, kv=kv, feed_forward=feed_forward,
                                                   format=format, clock_offset_ms=clock_offset_ms))

    def identify_plates(self, files, piece=None, errors_out=None):
        """The component functions of X, Y, Z (C1 piecewise, pieces of about `piece` mm, default 100) and the
        squareness from measured plates, one file per placement, as `mtacc plate-identify --json`:
        estimates with uncertainties (um, urad) and whether the plates determine each, the
        observability findings, and "yaml", the identified model as an errors file (Machine(errors=...) reads it).
        errors_out: a path to write that model to with the record of the data, as `--errors-out`."""
        return self._core.identify_plates(_options(files=list(files), piece=piece), _text(errors_out))

    def simulate_plate(self, output, origin, axes=None, stylus=None, plate=None, features=None, pose=None, probe=None, simulation=None,
                       noise=None, seed=None):
        """Writes the plate measurement this machine with its errors gives (as `mtacc simulate plate`):
        reference feature at `origin` (mm, workpiece frame), plate axes u, v (default ((1, 0, 0),
        (0, 1, 0))), stylus (mm, tool frame), plate = (rows, columns, pitch mm) (default (9, 9, 50));
        probe = (2S_u, 2S_v) and simulation 2S in um, to state in the file; pose: the axes that
        stay, {"B": 0, "C": 0} (mm, deg); noise a length ("0.3 um", default 0). Each may also be the
        CLI's text."""
        def text(value, form):
            return value if value is None or isinstance(value, str) else form(value)
        self._core.simulate_plate(_options(
            output=output, origin=text(origin, lambda o: f"{o[0]}, {o[1]}, {o[2]} mm"),
            axes=text(axes, lambda a: f"{a[0][0]},{a[0][1]},{a[0][2]} / {a[1][0]},{a[1][1]},{a[1][2]}"),
            stylus=text(stylus, lambda t: f"{t[0]}, {t[1]}, {t[2]} mm"), plate=text(plate, lambda p: f"{p[0]} x {p[1]}, pitch {p[2]} mm"),
            features=features, pose=_assignments(pose, "pose"), probe=text(probe, lambda p: f"{p[0]}, {p[1]} um"),
            simulation=text(simulation, lambda v: f"{v} um"), noise=noise, seed=seed))

    def simulate_component(self, component, output, step=None, runs=None, noise=None, abbe_offset=None, instrument=None, reading_time=None,
                           disturbance=None, disturbance_interval=None, settling=None, settling_time=None, seed=None):
        """Writes direct-measurement runs of one component (the 1991 BCR report name or ISO) simulated from this
        machine's errors to `output`, as `mtacc simulate component`: every `step` mm or deg (10) over
        the travel, `runs` (20) each way, with `noise` one reading's (e.g. "0.5 arcsec"), measured at
        `abbe_offset` (dx, dy, dz mm) from the carriage; `disturbance` (e.g. "1.5 arcsec") every
        `disturbance_interval` s, and `settling` a drift at the start that dies away with the time
        constant `settling_time` (s)."""
        abbe = abbe_offset if abbe_offset is None or isinstance(abbe_offset, str) else f"{','.join(repr(float(v)) for v in abbe_offset)} mm"
        self._core.simulate_component(_options(component=component, output=output, step=step, runs=runs, noise=noise, abbe_offset=abbe,
                                               instrument=instrument, reading_time=reading_time, disturbance=disturbance,
                                               disturbance_interval=disturbance_interval, settling=settling, settling_time=settling_time,
                                               seed=seed))

    def cone_preset_name(self):
        """The Bossoni 2009 §3.6 preset of this machine's family, or None."""
        return self._core.cone_preset_name()

    def simulate(self, plan, noise=None, seed=None, output=None, setup=None):
        """Every run of a test plan (YAML path or bundled name) simulated on this machine with its errors,
        as `mtacc simulate plan --json`; with output (a folder), also written as measurement CSV files.
        `noise` is a length ("0.5 um", default 0); `setup`: set-up errors with units {name: "10 um"}
        (xT yT zT xW yW zW aN bN cN dL), as `--setup`. A tool ball off the TCP is a key of each
        of the plan's runs (`tool_ball: [0 mm, 0 mm, -50 mm]`), not an argument: runs differ."""
        return self._core.simulate(_options(plan=plan, noise=noise, seed=seed, output=output, setup=_setup_text(setup)))

    def simulate_ballbar(self, noise=None, seed=None, setup=None, output=None, tool_ball=None, plane=None, centre=None, radius=None,
                         points=None, feed=None, pose=None, one_direction=None, lag=None, backlash=None, spike=None, spike_time=None):
        """An ISO 230-4 ballbar circle simulated on this machine, as `mtacc simulate ballbar --json`
        (written to `output`, a CSV, when given): in `plane` (XY, the default; YZ, ZX) about the work
        ball `centre` (mm, workpiece frame), bar length `radius` ("100 mm"), `points` per direction
        (360), both directions unless one_direction, at `feed` mm/min; the other axes at `pose`
        ({axis: mm or deg}); servo lag, backlash and reversal spikes per axis as the CLI's text
        ("X=1ms", "X=5um", "Y=4um") with their decay `spike_time` (s)."""
        return self._core.simulate_ballbar(_options(noise=noise, seed=seed, setup=_setup_text(setup), output=output, tool_ball=_vector(tool_ball),
                                                    plane=plane, centre=_vector(centre), radius=radius, points=points, feed=feed,
                                                    pose=_assignments(pose, "pose"), one_direction=one_direction, lag=lag, backlash=backlash,
                                                    spike=spike, spike_time=spike_time))

    def simulate_rtest(self, sphere, noise=None, seed=None, setup=None, output=None, tool_ball=None, axis=None, from_=None, to=None,
                       points=None, pose=None, probe=None):
        """An R-test (or with probe=True touch-probe) run on the `sphere` (mm, workpiece frame) while the
        rotary `axis` (C, the default) steps through `points` angles (12) `from_` ("0 deg") `to`
        ("330 deg"; the CLI's --from and --to), as `mtacc simulate rtest --json` (written to `output`,
        a CSV, when given); the other axes at `pose`."""
        return self._core.simulate_rtest(_options(sphere=_vector(sphere), noise=noise, seed=seed, setup=_setup_text(setup), output=output,
                                                  tool_ball=_vector(tool_ball), axis=axis, **{"from": from_}, to=to, points=points,
                                                  pose=_assignments(pose, "pose"), probe=probe))

    def read_measurement(self, path):
        """A measurement CSV file (docs/file-formats.md) as one run of `simulate`'s result: "q" its
        poses (n, axes) [mm, deg], "readings_um" (n, channels) [um] (a ballbar's change of length),
        and the instrument's set-up (a ballbar's "length_mm")."""
        return self._core.read_measurement(str(path))

    def evaluate_ballbar(self, data):
        """ISO 230-4 evaluation (circular deviations G, F, H in um), eccentricity (um) and diagnostics of
        a ballbar CSV file (as `mtacc evaluate --json`)."""
        return self._core.evaluate_ballbar(_options(data=data))

    def evaluate_rtest(self, data):
        """An R-test run about the axis that moves (ISO 10791-6, as `mtacc evaluate --json`): the axis
        ("moving_axis", its "position" in mm or deg), the sphere's displacement per pose in machine X, Y,
        Z (["readings_um"], (n, 3)) and its range ("range_um"); where the sphere travels around the axis
        (a table axis), "about_the_axis": the fitted line and per pose the radial, axial and tangential
        components ["radial_axial_tangential_um"] (n, 3) with their ranges."""
        return _with_arrays(self._core.evaluate_rtest(_options(data=data)), ("position",), ("readings_um",), ("q",),
                            ("about_the_axis", "radial_axial_tangential_um"))

    def observability(self, plan, data=None, parameters=None, setup=None, noise=None, from_nominal=None, threads=None):
        """Rank, singular values and findings of a test plan (as `mtacc observability --json`, whose
        options these keyword arguments are, with its defaults), for the plan's parameters or
        `parameters`; `data`: measurement files whose runs are added to the plan's.
        result["singular_values"] (p,) of the column-normalised Jacobian, descending;
        result["singular_vectors"] (k, p) the right singular vectors as rows (numpy.linalg.svd's Vh),
        over result["names"]; a parameter without effect is 0 in every row.
        result["identifiable_set"]: when the plan cannot determine every parameter, the set it can
        ("parameters", each with what its estimate "stands_for") and those to hold at zero ("held").
        noise (e.g. "0.5 um"; default: the plan's runs' `noise:`): result["prediction"] gives each
        parameter's predicted standard uncertainty (um, urad; set-up unknowns flagged "setup") and
        result["prediction"]["correlation"] (q, q) over them."""
        options = _options(plan=plan, data=data, parameters=parameters, setup=setup, noise=noise, from_nominal=from_nominal,
                           threads=threads)
        return _with_arrays(self._core.observability(options), ("singular_values",), ("singular_vectors",),
                            ("prediction", "correlation"))

    def identify(self, data, parameters=None, plan=None, setup=None, robust=None, robust_scale=None, noise=None,
                 uncertainty_fraction=None, from_nominal=None, threads=None, errors_out=None):
        """Least-squares estimates with standard uncertainties (um or urad, "unit"), covariance (um^2,
        um urad, urad^2) and correlation (as `mtacc identify --json`, whose options these keyword
        arguments are, with its defaults) from the measurement CSV files `data`; the parameters default
        to the plan's list; refuses (InputError) a set the data cannot determine. `noise` (e.g.
        "0.5 um", default: the files' '# noise:' lines) feeds the goodness-of-fit test;
        result["quality"]["warnings"] lists what is doubtful. The errors not determined are held at
        this machine's values (result["held"] names the non-zero ones); from_nominal=True holds them at
        zero. errors_out: a path to write the identified errors to, as an errors file that
        Machine(errors=...) and every command's --errors read (docs/file-formats.md "Identified errors")."""
        options = _options(data=list(data), plan=plan, parameters=parameters, setup=setup, robust=robust, robust_scale=robust_scale,
                           noise=noise, uncertainty_fraction=uncertainty_fraction, from_nominal=from_nominal, threads=threads)
        return self._core.identify(options, _text(errors_out))

    def xy_circle(self):
        """The report's X-Y circle: radial TCP deviation [um] at each angle [deg] around mid-travel, or
        None (a machine without X and Y)."""
        return self._core.xy_circle()

    def tilted_circle(self):
        """The report's 5-axis circle (tool tilted 30 deg towards the centre): radial TCP deviation [um]
        at each angle [deg], or None (a machine without two rotary axes)."""
        return self._core.tilted_circle()


class Structure:
    """A rigid-body structure model (Bossoni 2009 part II); axis positions `at` as {axis: mm}."""

    def __init__(self, model):
        self._core = _CoreStructure(str(model))
        self._description = self._core.describe()

    name = property(lambda self: self._description["name"])
    axes = property(lambda self: self._description["axes"])
    bodies = property(lambda self: self._description["bodies"])

    def modes(self, at=None, count=None):
        """As `mtacc dynamics modes --json`: the first `count` modes (default 12), per mode its
        frequencies [Hz], damping ratio, dominant body and DOF, and "shape" an ndarray (6 x bodies,),
        mass-normalised [m, rad per sqrt(kg)], whose entries result["dofs"] labels "<body>.x", ".y",
        ".z", ".rx", ".ry", ".rz"."""
        result = _with_arrays(self._core.modes(_options(at=_assignments(at, "at"), count=count)), ("modes", "*", "shape"))
        result["dofs"] = [f"{b['name']}.{d}" for b in self.bodies for d in ("x", "y", "z", "rx", "ry", "rz")]
        return result

    def frf(self, frequencies, at=None, method=None):
        """(n, 3, 3) complex FRF of the TCP relative to the workpiece [um/N], H[s, i, k] the
        displacement along i per force along k (x, y, z) at frequencies[s] [Hz] (the CLI's --from,
        --to and --step make such a grid). method: "auto" (the default: the modal sum where the
        damping is proportional, where it is exact; else the direct solve), "modal" or "direct".
        frf_method(at) says which "auto" uses."""
        rows = self._core.frf(list(map(float, frequencies)), _options(at=_assignments(at, "at"), method=method))["frf"]
        h = np.empty((len(rows), 3, 3), complex)
        for s, row in enumerate(rows):
            for i, a in enumerate("xyz"):
                for k, b in enumerate("xyz"):
                    h[s, i, k] = row["magnitude_um_per_n"][f"H{a}{b}"] * np.exp(1j * np.radians(row["phase_deg"][f"H{a}{b}"]))
        return h

    def frf_method(self, at=None):
        """The method "auto" computes the FRF with at these positions ("modal" or "direct"), and the
        damping's coupling of the modes (0 for proportional damping)."""
        r = self._core.frf([1.0], _options(at=_assignments(at, "at")))
        return r["method"], r["damping_coupling"]

    def acceleration_response(self, at=None):
        """As `mtacc dynamics accel --json`: {"Hx": {axis: um/g_n}, ...} (Bossoni 2009 Table 7.1 form)."""
        return self._core.acceleration_response(_options(at=_assignments(at, "at")))["response_um_per_g"]

    def map(self, quantity=None, axes=None, grid=None, at=None):
        """As `mtacc dynamics map --json`: a quantity ("Hx/X" um/g, the default; "Cxx" um/N, "f1" Hz;
        result["unit"]) over a grid of two axes (default ("Y", "Z")) across their travel, with its
        statistics. grid: (na, nb) positions of axes[0] and axes[1] (default (20, 20)), or the CLI's
        text "20x20". result["a_mm"] (na,), result["b_mm"] (nb,), result["values"] (na, nb) with
        values[i, k] at a_mm[i], b_mm[k] (numpy.meshgrid's indexing="ij")."""
        if grid is not None and not isinstance(grid, str):
            try:
                na, nb = (int(n) for n in grid)
                if (na, nb) != tuple(grid):
                    raise ValueError
            except (TypeError, ValueError):
                raise InputError(f"grid: expected two whole numbers of positions (na, nb), e.g. (20, 20), not {grid!r}") from None
            grid = f"{na}x{nb}"
        result = self._core.map(_options(quantity=quantity, axes=axes, grid=grid, at=_assignments(at, "at")))
        return _with_arrays(result, ("a_mm",), ("b_mm",), ("values",))
