"""mtacc: geometric accuracy of multi-axis machine tools.

    import mtacc
    m = mtacc.Machine("tilting-table")           # a bundled machine, or a YAML file
    m.errors["X0C"] = "5 um"                      # set by ISO name (or alias), with a unit
    pos, tool = m.fk([[10, 20, 30, -15, 45]])     # axis positions in mm and degrees
    err = m.tcp_errors(q)                         # (n, 6): dx dy dz [um], ea eb ec [urad]
    q = m.ik_path(tcps, tools, branch="negative") # (n, axes) in mm and degrees
    budget = m.budget()                           # the error budget, as the CLI's --json

Units are those of the command line: mm and degrees for axis positions, mm for the TCP,
um and urad for errors. Error parameters read back in mm or rad (see Errors.unit).
"""
from collections.abc import MutableMapping

import numpy as np

from ._mtacc import InputError, Structure, UnreachablePose
from ._mtacc import Machine as _CoreMachine

__all__ = ["Machine", "Errors", "InputError", "UnreachablePose"]


class Errors(MutableMapping):
    """The machine's error parameters by ISO 230-1 name (aliases accepted).

    Reading gives the value in mm (lengths) or rad (angles); writing accepts a number in
    those units or a string with a unit such as "10 um", "30 urad", "5 arcsec".
    Iteration visits the non-zero parameters.
    """

    def __init__(self, core):
        self._core = core

    def __getitem__(self, name):
        return self._core.get_error(name)

    def __setitem__(self, name, value):
        self._core.set_error(name, value)

    def __delitem__(self, name):
        self._core.set_error(name, 0.0)

    def __iter__(self):
        return iter(self._core.nonzero_errors())

    def __len__(self):
        return len(self._core.nonzero_errors())

    def unit(self, name):
        """'mm' or 'rad'."""
        return self._core.error_unit(name)

    def names(self):
        """Every parameter of the machine: location errors, then component-error coefficients."""
        return self._core.parameter_names()


class Machine:
    """A machine description with its errors (from the machine file, or `errors=FILE`)."""

    def __init__(self, machine, errors=None):
        self._core = _CoreMachine(str(machine), "" if errors is None else str(errors))
        self.errors = Errors(self._core)

    name = property(lambda self: self._core.name)
    file = property(lambda self: self._core.file)
    structure = property(lambda self: self._core.structure)
    structure_tool_first = property(lambda self: self._core.structure_tool_first)
    axis_names = property(lambda self: self._core.axis_names)
    axes = property(lambda self: self._core.axes)
    tool_chain = property(lambda self: self._core.tool_chain)
    workpiece_chain = property(lambda self: self._core.workpiece_chain)
    tool_direction = property(lambda self: np.array(self._core.tool_direction))

    def _q(self, q):
        q = np.asarray(q, dtype=float)
        return q.reshape(1, -1) if q.ndim == 1 else q

    def fk(self, q, directions=None, nominal=False):
        """TCP positions (n, 3) [mm] and tool directions (n, 3) in the workpiece frame."""
        return self._core.fk(self._q(q), directions, nominal)

    def tcp_errors(self, q, directions=None):
        """(n, 6): position error dx dy dz [um] and orientation error [urad], actual minus nominal."""
        return self._core.tcp_errors(self._q(q), directions)

    def ik(self, tcp, tool=(0, 0, 1), branch="auto", all=False):
        """Solutions for one TCP [mm] and tool direction: a list of dicts (pose in mm/deg)."""
        return self._core.ik(list(map(float, tcp)), list(map(float, tool)), branch, all)

    def ik_path(self, tcps, tools, branch="auto"):
        """Axis positions (n, axes) [mm, deg] along a continuous path."""
        return self._core.ik_path(np.asarray(tcps, float), np.asarray(tools, float), branch)

    def jacobian(self, q, params=None):
        """(names, J): J is 6 x n, d(dx, dy, dz [mm], rotation [rad]) / d(parameter [mm or rad])."""
        return self._core.jacobian(np.asarray(q, float).ravel(), params)

    def sensitivity_coefficient(self, q, parameter, epsilon, direction):
        """Seed 001 eq. 15: k = E / epsilon with the exact model; epsilon in mm/rad or with a unit
        ("10 um"); E is the TCP deviation along `direction` (outward normal) in mm."""
        return self._core.sensitivity_coefficient(np.asarray(q, float).ravel(), parameter, epsilon, list(map(float, direction)))

    def cone(self, alpha=45.0, beta=30.0, radius=40.0, centre=(-65.0, 0.0, 150.0), gamma=0.0, face_milling=False,
             points=720, branch="negative", feed=500.0, single_errors=False, monte_carlo=0, limits=None, seed=1):
        """The cone-frustum test piece of seed 000 on this machine (as `mtacc cone`): path (phi in deg,
        points, tools, normals), axis positions q (mm, deg) and their statistics, warnings; with
        errors the equivalent cone form error and its deviation (um); optionally each error alone
        and a Monte Carlo over limits (default: seed 000 Table 3.9)."""
        return self._core.cone(alpha, beta, radius, list(map(float, centre)), gamma, face_milling, points, branch, feed,
                               single_errors, monte_carlo, "" if limits is None else str(limits), seed)

    def simulate(self, plan, noise_um=0.0, seed=1, output_dir=None):
        """Every run of a test plan (YAML path or bundled name, e.g. "tilting-table-rtest") simulated
        on this machine with its errors: list of dicts (poses in mm/deg, readings in um, ballbar
        angle_deg and sense). With output_dir, also written as measurement CSV files."""
        return self._core.simulate(str(plan), noise_um, seed, "" if output_dir is None else str(output_dir))

    def read_measurement(self, path):
        """A measurement CSV file (docs/file-formats.md) as the dict `simulate` returns."""
        return self._core.read_measurement(str(path))

    def evaluate_ballbar(self, path):
        """ISO 230-4 circular deviation, radial deviation, hysteresis, eccentricity and the
        ballbar diagnostics of a ballbar CSV file (um, urad, ms)."""
        return self._core.evaluate_ballbar(str(path))

    def observability(self, plan, parameters=None):
        """Rank, condition number, singular values and the findings (parameters without effect,
        groups the plan cannot separate) of a test plan for the given parameters (default:
        the plan's own list)."""
        return self._core.observability(str(plan), list(parameters or []))

    def identify(self, files, parameters, robust=False):
        """Least-squares estimates (um, urad) with standard uncertainties of `parameters` from
        measurement CSV files; refuses (InputError) a set the data cannot determine."""
        return self._core.identify([str(f) for f in files], list(parameters), robust)

    def working_volume_grid(self, samples=5):
        """Grid of `samples` positions per axis across its travel (mm, deg), as the budget uses."""
        return self._core.working_volume_grid(samples)

    def budget(self, samples=5, length=None, angle=None):
        """Each error alone: largest TCP deviation over a grid of `samples` positions per axis."""
        return self._core.budget(samples, length, angle)
