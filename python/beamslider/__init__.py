"""beamslider from Python: scenes, modes, coefficients, backbones and
adaptation runs of the beam with a sliding mass, as NumPy arrays.

Every function runs the same computation as the command line
(``beamslider COMMAND ...``) inside this process, with the same checks and
the same files, and returns what those files hold::

    import beamslider
    scene = beamslider.Scene("mueller2023")
    scene.set("Excitation/Frequency", 124.0)
    run = beamslider.simulate(scene, model="rom", case="signature-move", end_time=20)
    run.trace["t_s"], run.trace["slider_x_over_L"]   # NumPy arrays
    run.verdict, run.outcome                         # one line, its class

Bad input raises ``ValueError`` with the command line's one-line message; a
failed run or solver raises ``RuntimeError`` saying where and why. Ctrl-C
stops a long run at its next step and raises ``Interrupted`` (a
``KeyboardInterrupt``) carrying what was computed (``.result``); so does
``interrupt()`` called from another thread. ``progress=print`` shows the
progress lines the command line would print. Columns and units of every
table: doc/python.md and doc/cli.md.
"""

import csv
import io
import math
import numbers
import os
import shutil
import tempfile
import warnings

import numpy as np

from . import _core

__all__ = ["Scene", "Run", "FEBeam", "ReducedModel", "Solid", "Result", "Interrupted", "NotConvergedWarning", "PartialResultWarning", "interrupt", "modes", "coefficients", "statics", "backbone", "simulate",
           "ensemble", "sweep", "map", "ladder", "verify", "Ensemble", "Ladder", "Sweep", "Map", "Branches", "read_table"]


class NotConvergedWarning(UserWarning):
    """A study finished, but its reference did not prove its convergence in
    Δt (doc/verification.md §6): its result says so in ``.convergence``."""


class PartialResultWarning(UserWarning):
    """A study stopped by Ctrl-C was saved: the folder holds what it had
    computed, and its run.txt says that it is partial."""


class Interrupted(KeyboardInterrupt):
    """A run stopped by Ctrl-C, SIGTERM or interrupt(); ``result`` holds what it
    had computed (the rows written before it stopped), or None."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


def interrupt():
    """Stops the running beamslider command (in another thread) at its next
    step, as Ctrl-C does; the command then raises Interrupted. With no
    command running it does nothing (no request is kept for later)."""
    _core.interrupt()


class Scene:
    """A scene file (a path, or a name in the project's meshes/, default
    mueller2023) with parameter overrides, as ``--set`` gives them on the
    command line. Each ``set`` is checked at once."""

    def __init__(self, scene="mueller2023"):
        self.path = _core.resolve_scene(str(scene))
        self._overrides = []
        self._text = _core.scene_text(self.path, self._overrides)
        self._values = _core.scene_parameters(self.path, self._overrides)

    def set(self, parameter, value):
        """Sets "Section/Name" (e.g. "Excitation/Frequency") to value; raises
        ValueError naming the parameter, its value and the allowed range."""
        if isinstance(value, bool):
            value = "true" if value else "false"
        elif isinstance(value, float):
            value = repr(value)  # shortest exact decimal: read back to the same double
        kept = [o for o in self._overrides if o.split("=", 1)[0] != parameter]
        overrides = kept + [f"{parameter}={value}"]
        self._text = _core.scene_text(self.path, overrides)
        self._values = _core.scene_parameters(self.path, overrides)
        self._overrides = overrides
        return self

    def get(self, parameter):
        """The value of "Section/Name" after the overrides: a float where it is
        a number, else the text."""
        text = self._values.get(parameter)
        if text is None:
            raise ValueError(f"error: no parameter '{parameter}' in scene '{self.path}'")
        try:
            return float(text)
        except ValueError:
            return text

    def parameters(self):
        """Every parameter of the scene as {"Section/Name": text}."""
        return dict(self._values)

    def write(self, path):
        """Writes the scene with its overrides as a scene file (.prm) that the
        command line and Scene(path) read back exactly."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self._text)

    @property
    def name(self):
        """The scene's name, as the command line names it: the file's name
        without .prm (reports go to reports/<name>/)."""
        return os.path.splitext(os.path.basename(self.path))[0]

    def arguments(self):
        """The scene as command-line arguments: the file, then each --set."""
        args = [self.path]
        for o in self._overrides:
            args += ["--set", o]
        return args

    def __repr__(self):
        return f"Scene({self.path!r}, overrides={self._overrides!r})"


class Run:
    """One free-slider run held in this process and stepped from Python: the
    scene's model (``model="rom"`` or ``"fe"``, each at the scene's own time
    step), the slider at rest on the beam at t = 0. It is the run the command
    ``simulate`` makes, kept in memory instead of written: advanced to T, its
    ``trace`` holds the rows ``simulate`` writes to trace.csv for End time T.

    ``advance(seconds)`` and ``step(n)`` return the status ("completed", or
    "slider_at_support" once a corner reaches a support, after which the run
    takes no more steps); a failing solver raises RuntimeError with its
    message and the run keeps its last good state. Ctrl-C raises
    KeyboardInterrupt within about a thousand steps, the run intact at the
    end of a whole step: advance again to go on. Stepping releases the GIL.
    """

    def __init__(self, scene="mueller2023", model="rom"):
        if isinstance(scene, _core.Run):  # from resume()
            self._run = scene
            self.scene = Scene(scene.scene_path)
            for o in scene.overrides:
                self.scene.set(*o.split("=", 1))
            return
        if not isinstance(scene, Scene):
            scene = Scene(scene)
        self.scene = scene
        self._run = _core.Run(scene.path, list(scene._overrides), model)

    def step(self, n=1):
        """Takes n time steps (a whole number in [0, 1e11], the scene's
        limit on a run's steps); returns the status."""
        return self._run.step(_whole_number("step: n", n, 0, _MAX_TIME_STEPS))

    def advance(self, seconds):
        """Steps on by ``seconds`` of simulated time (the nearest whole number
        of time steps, at most 1e11); returns the status."""
        if isinstance(seconds, bool) or not isinstance(seconds, numbers.Real) or not 0 <= seconds < math.inf:
            raise ValueError(f"error: advance: seconds = {seconds!r} is outside the allowed range [0, inf)")
        n = round(seconds / self._run.time_step)
        if n > _MAX_TIME_STEPS:
            raise ValueError(f"error: advance: seconds = {seconds!r} is {n:.3g} time steps of "
                             f"{self._run.time_step:g} s, more than the allowed 1e11")
        return self._run.step(int(n))

    @property
    def t(self):
        """The run's time [s]."""
        return self._run.t

    @property
    def time_step(self):
        """The model's time step [s]."""
        return self._run.time_step

    @property
    def model(self):
        """The model in words (e.g. "ROM N=5, analytic")."""
        return self._run.model

    @property
    def status(self):
        """The last advance's status: completed, slider_at_support, ..."""
        return self._run.status

    @property
    def state(self):
        """The current state: t [s], q and u (the model's coordinates and
        their rates: modal for the ROM, nodal for the FE), slider_x [m],
        slider_x_over_L, slider_z [m], slider_beta [rad],
        slider_velocity (ẋ, ż [m/s], β̇ [rad/s]), contact_impulses (the last
        step's normal and tangential impulse [N s] at each corner: rows
        upper-left, upper-right, lower-left, lower-right) and
        corners_in_contact (a normal impulse in the last step); copies."""
        return self._run.state

    @property
    def trace(self):
        """The trace so far as {column: array}, the columns of trace.csv."""
        return self._run.trace

    @property
    def periods(self):
        """The closed excitation periods as {column: array}, the columns of
        periods.csv (index, times, mean slider position, amplitude, mean
        horizontal contact force, the energy balance)."""
        return self._run.periods

    def analyse(self):
        """The run so far read as ``simulate`` reads it: {"verdict": one line,
        "outcome": its class, "initial_direction", "jumped", "jump_time",
        "turned", "final_position", "final_amplitude", "adaptation_time",
        "valid"}."""
        return self._run.analyse()

    def checkpoint(self, path):
        """Writes the whole run (scene, model, state, trace) to ``path``,
        checked and renamed into place; ``Run.resume(path)`` continues it
        bit for bit."""
        data = self._run.checkpoint_bytes()
        folder = os.path.dirname(os.path.abspath(path))
        fd, temporary = tempfile.mkstemp(prefix=".checkpoint-", dir=folder)
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(data)
                f.flush()
                os.fsync(f.fileno())
            os.replace(temporary, path)
        except BaseException:
            if os.path.exists(temporary):
                os.unlink(temporary)
            raise

    @classmethod
    def resume(cls, path):
        """The run a checkpoint holds; ValueError if the file is not one, is
        damaged, or its scene file reads differently now."""
        return cls(_core.Run.resume(str(path)))

    def __repr__(self):
        return f"<beamslider Run: {self.model}, t = {self.t:g} s, {self.status}>"


# The scene's limit on a run's time steps ('Time stepping/End time').
_MAX_TIME_STEPS = 10 ** 11


def _whole_number(name, value, low, high):
    """value as an int in [low, high], else ValueError naming it and the range
    (a bool, a float or a string is not a whole number here)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or not low <= value <= high:
        raise ValueError(f"error: {name} = {value!r} is outside the allowed range: a whole number in [{low}, {high}]")
    return int(value)


def _as_scene(scene):
    return scene if isinstance(scene, Scene) else Scene(scene)


def _sparse(arrays, n):
    """CSR arrays (indptr, indices, data) as a scipy.sparse CSR matrix."""
    import scipy.sparse  # here, not at import: it costs a tenth of a second
    indptr, indices, data = arrays
    matrix = scipy.sparse.csr_matrix((data, indices, indptr), shape=(n, n))
    matrix.sort_indices()
    return matrix


class FEBeam:
    """The scene's FE beam (Hermite cubic bending, axial displacement): its
    matrices as scipy.sparse CSR over every DoF (no constraint applied;
    ``free_dofs()`` are the DoFs the bending modes leave free), its internal
    force and tangent at a displacement q, and its bending modes.
    ``elements`` (default: the scene's Number of elements) sets the mesh."""

    def __init__(self, scene="mueller2023", elements=None):
        self.scene = _as_scene(scene)
        # The mesh through the scene's own parameter, so that its range
        # ([1, 4096], at least N + 1) is checked and named as everywhere.
        overrides = list(self.scene._overrides)
        if elements is not None:
            overrides.append(f"Discretisation/Number of elements={_whole_number('elements', elements, 1, 4096)}")
        self._beam = _core.FEBeam(self.scene.path, overrides, 0)
        self.n_dofs = self._beam.n_dofs

    def mass(self):
        """The consistent mass matrix [kg, kg m, kg m²] with the scene's point bodies."""
        return _sparse(self._beam.mass_csr(), self.n_dofs)

    def stiffness(self):
        """The linear stiffness, the tangent at q = 0."""
        return self.tangent(np.zeros(self.n_dofs))

    def tangent(self, q):
        """K_t(q) = ∂f/∂q (geometric nonlinearity as the scene says)."""
        return _sparse(self._beam.tangent_csr(np.asarray(q, dtype=float)), self.n_dofs)

    def internal_force(self, q):
        """f(q) = ∂Π/∂q, the internal force at the DoF vector q [N, N m]."""
        return self._beam.internal_force(np.asarray(q, dtype=float))

    def free_dofs(self):
        """The DoFs the bending modes leave free, ascending (an int array)."""
        return np.array(self._beam.free_dofs(), dtype=int)

    def dof_kinds(self):
        """{"axial", "deflection", "slope"}: boolean masks over the DoFs."""
        return {"axial": np.array(self._beam.axial_dofs()), "deflection": np.array(self._beam.deflection_dofs()),
                "slope": np.array(self._beam.slope_dofs())}

    def nodes(self):
        """The element ends x [m], 0 to L."""
        return np.array(self._beam.nodes())

    def statics(self, line_load, steps=10):
        """The load path of a uniform dead line load ``line_load`` [N/m],
        positive downward, in ``steps`` equal steps (the command `statics`):
        {"line_load_n_per_m", "w_mid_m" (+w up), "newton_iterations",
        "displacement" (n_dofs × steps)}. A step that does not converge
        raises RuntimeError naming the load it stopped at."""
        return self._beam.statics(float(line_load), int(steps))

    def modes(self, n=7):
        """The n lowest bending modes: (frequencies [Hz], shapes), the shapes
        mass-normalised columns over every DoF (the command ``modes``)."""
        omega, shapes = self._beam.modes(int(n))
        return omega / (2 * np.pi), shapes


class ReducedModel:
    """The scene's reduced-order model as the runs build it: ``omega``
    (ω_n [rad/s]), ``damping`` (c_n = 2 D ω_n [1/s]), ``coefficients`` (the
    tensor [n, j, k, l] with f_n = Σ tensor[n, j, k, l] q_j q_k q_l),
    ``force(q)`` and ``tangent(q)`` (f and ∂f/∂q), ``shapes(x)`` (φ and φ′).
    ``modes`` (default: the scene's N) and ``coefficients`` ("analytic",
    "step", "step-condensed", "ice"; default the scene's) choose the model."""

    def __init__(self, scene="mueller2023", modes=None, coefficients=None):
        self.scene = _as_scene(scene)
        overrides = list(self.scene._overrides)
        if modes is not None:  # the scene's parameter and its range ([1, 40])
            overrides.append(f"Discretisation/Number of modes={_whole_number('modes', modes, 1, 40)}")
        self._rom = _core.ReducedModel(self.scene.path, overrides, 0, coefficients or "")
        self.omega = self._rom.omega
        self.damping = self._rom.damping
        self.length = self._rom.length

    @property
    def coefficients(self):
        return self._rom.coefficients

    def force(self, q):
        """The cubic modal force f(q)."""
        return self._rom.force(np.asarray(q, dtype=float))

    def tangent(self, q):
        """∂f/∂q at q (N × N)."""
        return self._rom.tangent(np.asarray(q, dtype=float))

    def shapes(self, x):
        """(φ, φ′) at the points x [m]: arrays len(x) × N."""
        return self._rom.shapes(np.atleast_1d(np.asarray(x, dtype=float)).tolist())

    def backbone(self, harmonics=10, max_amplitude_over_h=4.0, x_out=None):
        """The mode-1 backbone by harmonic balance, as the command ``backbone``
        computes it: {"amplitude_over_h" (first harmonic of w(x_out), default
        mid-span), "frequency_hz", "peak_over_h", "segment", "tongue",
        "completed", "message"}."""
        return self._rom.backbone(int(harmonics), float(max_amplitude_over_h),
                                  -1.0 if x_out is None else float(x_out))


class Solid:
    """The continuum model of a solid scene (Solid/Continuum "plane stress"
    or "3d": a St. Venant–Kirchhoff strip or a mesh, deal.II with PETSc and
    SLEPc on one process): ``modes(n)`` and ``coefficients(method, n)`` as
    the commands ``modes`` and ``coefficients`` compute them on that scene.
    The modes are computed once and kept for later calls."""

    def __init__(self, scene="mueller2023-solid"):
        self.scene = _as_scene(scene)
        self._solid = _core.Solid(self.scene.path, list(self.scene._overrides))
        self.dimension = self._solid.dimension
        self.n_dofs = self._solid.n_dofs

    def modes(self, n_bending=5):
        """The lowest modes until ``n_bending`` bending ones: {"frequency_hz"
        (every mode found), "shape" (bending, torsion, lateral, axial),
        "bending" (the indices of the first n_bending bending modes)}."""
        return self._solid.modes(int(n_bending))

    def coefficients(self, method="ice", n=5):
        """The cubic tensor [n, j, k, l] of the first n bending modes by
        "exact", "step", "step-relaxed" or "ice" (coefficients.csv's values
        spread over the permutations, as ReducedModel.coefficients)."""
        return self._solid.coefficients(method, int(n))

    def statics(self, line_load, steps=10):
        """The load path of a uniform dead line load ``line_load`` [N/m],
        positive downward, in ``steps`` equal steps (the command `statics`):
        {"line_load_n_per_m", "w_mid_m" (the section x = L/2's mean u_z, +z
        up), "newton_iterations"} per step. A step that does not converge
        raises RuntimeError naming it."""
        return self._solid.statics(float(line_load), int(steps))


def read_table(path):
    """A CSV file of beamslider as {column: array}: float arrays where every
    cell is a number (an empty cell is NaN), else arrays of str."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    return _columns(rows[0], rows[1:]) if rows else {}


def _columns(header, body):
    """Rows of CSV cells as {column: array}, as read_table reads them."""
    table = {}
    for i, name in enumerate(header):
        cells = [r[i] if i < len(r) else "" for r in body]
        try:
            table[name] = np.array([float(c) if c != "" else np.nan for c in cells], dtype=float)
        except ValueError:
            table[name] = np.array(cells, dtype=str)
    return table


class Result:
    """What a command wrote: ``tables`` ({file stem: {column: array}}) for every
    CSV file of its folder, ``summary`` (summary.md), ``output`` (the folder,
    or None when it was a temporary one, removed after reading)."""

    def __init__(self, folder, keep):
        self.output = folder if keep else None
        self.tables = {}
        for name in sorted(os.listdir(folder)):
            if name.endswith(".csv"):
                self.tables[name[:-4]] = read_table(os.path.join(folder, name))
        summary = os.path.join(folder, "summary.md")
        self.summary = ""
        if os.path.exists(summary):
            with open(summary, encoding="utf-8") as f:
                self.summary = f.read()

    def __getattr__(self, name):
        tables = self.__dict__.get("tables", {})
        if name in tables:
            return tables[name]
        raise AttributeError(name)

    def __repr__(self):
        return f"<beamslider result: tables {sorted(self.tables)}{', in ' + self.output if self.output else ''}>"


def _summary_line(summary, key):
    for line in summary.splitlines():
        if line.startswith(f"- {key}: "):
            return line[len(f"- {key}: "):].rstrip(".")
    return None


def _run(command, scene, options, output, progress, read=Result):
    """Runs `beamslider command scene options --output DIR` and reads DIR."""
    if not isinstance(scene, Scene):
        scene = Scene(scene)
    keep = output is not None
    folder = str(output) if keep else tempfile.mkdtemp(prefix=f"beamslider-{command}-")
    args = [command] + scene.arguments() + options + ["--output", folder]
    if progress is None:
        args.append("--quiet")
    try:
        status, errors, signal = _core.run(args, progress)
        message = next((line for line in errors.splitlines() if line.strip()), "")
        if signal:
            try:
                partial = read(folder, keep)
            except Exception:  # nothing readable was written yet
                partial = None
            raise Interrupted(message or f"interrupted by signal {signal}", partial)
        if status == 2:
            raise ValueError(message)
        if status == 3:
            # Finished and written, but a reference did not prove its
            # convergence: the results say so (convergence.csv), and so does
            # the warning.
            warnings.warn(message, NotConvergedWarning, stacklevel=3)
            return read(folder, keep)
        if status != 0:
            raise RuntimeError(message or f"beamslider {command} failed with status {status}")
        return read(folder, keep)
    finally:
        if not keep:
            shutil.rmtree(folder, ignore_errors=True)


# The options that are flags (True: given); every other option takes a value.
_FLAGS = {"full", "diagnostics", "unchecked"}


def _options(**given):
    """--name value for every option given (None: the command's default)."""
    args = []
    for name, value in given.items():
        if isinstance(value, bool) and name not in _FLAGS:
            raise ValueError(f"error: {name} = {value!r} is not a value for {name}: give a number or leave it out")
        if value is None or value is False:
            continue
        flag = "--" + name.replace("_", "-")
        if value is True:
            args.append(flag)
        elif isinstance(value, (list, tuple)):
            for v in value:
                args += [flag, str(v)]
        else:
            args += [flag, repr(value) if isinstance(value, float) else str(value)]
    return args


def modes(scene="mueller2023", modes=7, slider_at=None, elements=None, output=None, progress=None):
    """The lowest bending modes (SLEPc): ``.modes`` with frequency_hz per mode."""
    return _run("modes", scene, _options(modes=modes, slider_at=slider_at, elements=elements), output, progress)


class CoefficientsResult(Result):
    """``tensor[n, j, k, l]`` (0-based, NumPy): the cubic modal coefficients with
    f_n = Σ_jkl tensor[n, j, k, l] q_j q_k q_l, symmetric in j, k, l (each
    sorted entry of coefficients.csv, a sum over its permutations, spread
    evenly over them); ``table``: coefficients.csv as written."""

    def __init__(self, folder, keep):
        super().__init__(folder, keep)
        self.table = self.tables["coefficients"]
        index = [self.table[c].astype(int) - 1 for c in ("n", "j", "k", "l")]
        size = int(max(i.max() for i in index)) + 1 if len(index[0]) else 0
        self.tensor = np.zeros((size, size, size, size))
        for n, j, k, l, value in zip(*index, self.table["value"]):
            permutations = {(a, b, c) for a, b, c in
                            [(j, k, l), (j, l, k), (k, j, l), (k, l, j), (l, j, k), (l, k, j)]}
            for a, b, c in permutations:
                self.tensor[n, a, b, c] = value / len(permutations)


def coefficients(scene="mueller2023", method="analytic", modes=None, output=None, progress=None):
    """Cubic modal coefficients by "analytic", "step", "step-condensed" or "ice"."""
    return _run("coefficients", scene, _options(method=method, modes=modes), output, progress,
                read=CoefficientsResult)


def statics(scene="mueller2023", line_load=None, steps=None, output=None, progress=None):
    """Nonlinear statics under a uniform dead line load ``line_load`` [N/m],
    positive downward, in ``steps`` equal load steps: ``.statics`` with
    line_load_n_per_m, w_mid_m (mid-span deflection, +w up) per step."""
    if line_load is None:
        raise ValueError("statics needs line_load: the uniform load Q [N/m], positive downward")
    return _run("statics", scene, _options(line_load=line_load, steps=steps), output, progress)


def backbone(scene="mueller2023", model="rom", modes=None, harmonics=None, max_amplitude=None, output=None,
             progress=None):
    """The mode-1 backbone by harmonic balance: ``.backbone`` (amplitude_over_h,
    frequency_hz, ...), ``.eq4`` (seed Eq. 4)."""
    return _run("backbone", scene,
                _options(model=model, modes=modes, harmonics=harmonics, max_amplitude=max_amplitude),
                output, progress)


class SimulationResult(Result):
    """``trace`` and ``periods`` ({column: array}, as trace.csv and periods.csv),
    ``status`` (completed, interrupted, slider_at_support, ...) with
    ``status_message`` (the whole status line: when and where it stopped),
    ``verdict`` (the one-line trace analysis) and ``outcome`` (its class:
    signature move, trivial adaption, ...)."""

    def __init__(self, folder, keep):
        super().__init__(folder, keep)
        self.trace = self.tables.get("trace", {})
        self.periods = self.tables.get("periods", {})
        self.status_message = _summary_line(self.summary, "Status")
        self.status = self.status_message.split(":", 1)[0] if self.status_message else None
        self.verdict = _summary_line(self.summary, "Verdict")
        self.outcome = self.verdict.rsplit(": ", 1)[-1] if self.verdict else None


def simulate(scene="mueller2023", model="rom", case=None, end_time=None, output=None, progress=None,
             checkpoint_every=None, tolerance=None):
    """A free-slider adaptation run (the command `simulate`)."""
    return _run("simulate", scene,
                _options(model=model, case=case, end_time=end_time, checkpoint_every=checkpoint_every,
                         tolerance=tolerance),
                output, progress, read=SimulationResult)


class _Study:
    """A study computed in this process by its command, held in memory: its
    tables as NumPy arrays; ``save(folder)`` writes the folder the command
    writes (the same files, through the command itself)."""

    _command = None

    def __init__(self, scene, options, progress):
        if not isinstance(scene, Scene):
            scene = Scene(scene)
        self._args = [self._command] + scene.arguments() + options
        quiet = [] if progress is not None else ["--quiet"]
        status, errors, signal, study = _core.compute(self._args + quiet, progress)
        message = next((line for line in errors.splitlines() if line.strip()), "")
        if study is not None:
            self._study = study
            self._read()
        if signal:
            raise Interrupted(message or f"interrupted by signal {signal}", self if study is not None else None)
        if status == 2:
            raise ValueError(message)
        if status != 0 or study is None:
            raise RuntimeError(message or f"beamslider {self._command} failed with status {status}")
        self.output = None

    def _read(self):
        raise NotImplementedError

    def _partial(self):
        """Whether Ctrl-C stopped the study before its end."""
        return False

    def save(self, folder, progress=None):
        """Writes the command's folder (CSV files, charts, summary.md and the
        run record with the equivalent command line) into ``folder``; returns
        those files read back (a Result). A NotConvergedWarning when the
        study's reference did not prove its convergence, as the command
        exits with 3."""
        args = self._args + ["--output", str(folder)] + ([] if progress is not None else ["--quiet"])
        status, errors, signal = self._study.save(args, progress)
        message = next((line for line in errors.splitlines() if line.strip()), "")
        if signal:
            raise Interrupted(message or f"interrupted by signal {signal}")
        if status == 2:
            raise ValueError(message)
        if status == 3:
            warnings.warn(message, NotConvergedWarning, stacklevel=2)
        elif status == 1 and self._partial():
            # A study stopped by Ctrl-C: what it holds is written, and
            # run.txt says that the folder is partial.
            warnings.warn(message, PartialResultWarning, stacklevel=2)
        elif status != 0:
            raise RuntimeError(message or f"beamslider {self._command} failed to write with status {status}")
        self.output = str(folder)
        return Result(str(folder), True)

    def __repr__(self):
        return f"<beamslider {self._command}: {' '.join(self._args[1:])}>"


class Ensemble(_Study):
    """K runs differing only by a tiny start shift (the command `ensemble`),
    held in memory: ``members`` (members.csv's columns; NaN where an event
    did not happen), ``member_periods``, ``statistics``, ``comparison``
    (with ``against``, another ensemble's folder), ``convergence`` (the FE's
    check in Δt, or None), ``model``, ``wall_seconds``;
    ``compare(other)`` against another Ensemble; ``save(folder)``."""

    _command = "ensemble"

    def __init__(self, scene="mueller2023", model="rom", case=None, members=8, end_time=None, perturbation=None,
                 integrator=None, coefficients=None, against=None, unchecked=False, progress=None):
        super().__init__(scene, _options(model=model, case=case, members=members, end_time=end_time,
                                         perturbation=perturbation, integrator=integrator,
                                         coefficients=coefficients, against=against, unchecked=unchecked),
                         progress)
        if self.convergence is not None and not self.convergence["converged"]:
            warnings.warn(f"ensemble: {self.convergence['verdict']}", NotConvergedWarning, stacklevel=2)

    def _read(self):
        s = self._study
        self.members = s.members()
        self.member_periods = s.member_periods()
        self.statistics = s.statistics()
        self.comparison = s.comparison()
        self.convergence = s.convergence()
        self.model = s.model()
        self.wall_seconds = s.wall_seconds()

    def compare(self, other):
        """Each outcome of this ensemble against ``other``'s (an Ensemble):
        the columns of comparison.csv (median shift, W₁ with its 90 %
        bootstrap interval, KS D, own spread, distinguishable)."""
        return self._study.compare(other._study)


class Ladder(_Study):
    """The error ladder (the command `ladder`: report section 5.1–5.2), held
    in memory: ``rungs`` (ladder.csv's columns: each rung's model, cost and
    outcome statistics, W₁ to the reference with its interval),
    ``members`` (ladder_members.csv's), ``steps`` (ladder_steps.csv's: each
    rung against the one before), ``checks`` ({name: {"converged",
    "verdict", "trials", "claim"}}: the reference's convergence in Δt and the
    converged ROM's in N, the claims; each other ROM at half its step, a
    finding), ``front`` (the rungs on the speed–accuracy front, in ascending
    cost); ``save(folder)``. A NotConvergedWarning when a claim did not
    converge."""

    _command = "ladder"

    def __init__(self, scene="mueller2023", full=False, diagnostics=False, rung=None, members=None, end_time=None,
                 progress=None):
        super().__init__(scene, _options(full=full, diagnostics=diagnostics, rung=rung, members=members,
                                         end_time=end_time), progress)
        for name, check in self.checks.items():
            if check["claim"] and not check["converged"]:
                warnings.warn(f"ladder: {check['verdict']}", NotConvergedWarning, stacklevel=2)

    def _read(self):
        s = self._study
        self.rungs = s.ladder_rungs()
        self.members = s.ladder_members()
        self.steps = s.ladder_steps()
        self.checks = s.ladder_checks()
        self.front = s.ladder_front()


class Sweep(_Study):
    """Prescribed slider position sweeps (the command `sweep`), held in
    memory: ``pcs`` (pcs.csv's columns, the up branch first), ``resonance``,
    ``free_periods``, ``runs``; ``save(folder)``."""

    _command = "sweep"

    def __init__(self, scene="mueller2023", model="rom", case=None, step=None, from_=None, to=None,
                 settle_time=None, average_time=None, free_time=None, progress=None):
        options = _options(model=model, case=case, step=step, to=to, settle_time=settle_time,
                           average_time=average_time, free_time=free_time)
        if from_ is not None:
            options += ["--from", repr(float(from_))]
        super().__init__(scene, options, progress)

    def _read(self):
        s = self._study
        self.pcs = s.pcs()
        self.resonance = s.resonance()
        self.free_periods = s.free_periods()
        self.runs = s.runs()

    def _partial(self):
        return bool(np.any(self.runs["status"] != "completed"))


class Map(_Study):
    """The adaptation over a parameter grid (the command `map`), held in
    memory: ``map`` (map.csv's columns, one row per cell and member),
    ``cells`` and ``cells_done`` (fewer after Ctrl-C); ``save(folder)``.
    Axes as on the command line: "A:B:STEP" or one value."""

    _command = "map"

    def __init__(self, scene="mueller2023", frequency=None, acceleration=None, start=None, axis=None, model="rom",
                 members=None, end_time=None, perturbation=None, progress=None):
        super().__init__(scene, _options(frequency=frequency, acceleration=acceleration, start=start, axis=axis,
                                         model=model, members=members, end_time=end_time,
                                         perturbation=perturbation), progress)

    def _read(self):
        s = self._study
        self.map = _columns(s.map_columns(), [r for r in csv.reader(io.StringIO(s.map_rows())) if r])
        self.cells = s.map_cells()
        self.cells_done = s.map_cells_done()

    def _partial(self):
        return self.cells_done < self.cells


class Branches:
    """The held slider's slow manifold (the study of the command `branches`,
    doc/physics.md §12), computed in this process: ``attractor`` (the
    rattling held slider's probes: attractor.csv's columns), ``branches`` (the
    attached-slider model's periodic orbits along x_C: x_over_L,
    amplitude_over_h, mean_fx_N, stable, largest_multiplier,
    integration_growth), ``events``
    (turning points, period doublings, tori: (kind, x_over_L,
    amplitude_over_h, mean_fx_N) each), ``model``, ``end_reason``,
    ``wall_seconds``. The range defaults to the sweep's (the half of the beam
    holding the scene's start); about 10 s for the published ROM."""

    def __init__(self, scene="mueller2023", from_=None, to=None, probe_step=0.02, settle_periods=120):
        self.scene = _as_scene(scene)
        settle_periods = _whole_number("settle_periods", settle_periods, 0, 100000)
        for name, value in (("from_", from_), ("to", to), ("probe_step", probe_step)):
            if value is not None and (isinstance(value, bool) or not isinstance(value, numbers.Real)):
                raise ValueError(f"error: {name} = {value!r} is not a number")
        result = _core.compute_branches(self.scene.path, list(self.scene._overrides),
                                        None if from_ is None else float(from_), None if to is None else float(to),
                                        float(probe_step), settle_periods)
        self.attractor = result["attractor"]
        self.branches = result["branches"]
        self.events = result["events"]
        self.model = result["model"]
        self.end_reason = result["end_reason"]
        self.probe_stop = result["probe_stop"]
        self.wall_seconds = result["wall_seconds"]

    def turning_points(self):
        """x_C/L of the attached model's turning points along the branch."""
        return [e[1] for e in self.events if e[0] == "turning point"]


def _saved(study, output):
    if output is not None:
        study.save(output)
    return study


def ensemble(scene="mueller2023", model="rom", case=None, members=8, end_time=None, perturbation=None,
             integrator=None, coefficients=None, against=None, unchecked=False, output=None, progress=None):
    """An Ensemble, saved into ``output`` when given."""
    return _saved(Ensemble(scene, model, case, members, end_time, perturbation, integrator, coefficients, against,
                           unchecked, progress), output)


class VerificationResult(Result):
    """The report `verify` wrote: ``report`` (report.md's text), ``tables``
    (every CSV file of the report folder, by file stem), ``output``."""

    def __init__(self, folder, keep):
        super().__init__(folder, keep)
        with open(os.path.join(folder, "report.md"), encoding="utf-8") as f:
            self.report = f.read()


def verify(scene="mueller2023", full=False, diagnostics=False, section=None, output=None, progress=None):
    """The verification report (the command `verify`): sections 1–8, or
    ``section`` (a number or a list). Unlike the studies it is written as it
    goes, each section kept on disk as it finishes (a report of 16 minutes
    to hours must not lose finished sections), into ``output`` or, without
    it, a temporary folder read and removed."""
    return _run("verify", scene, _options(full=full, diagnostics=diagnostics, section=section), output, progress,
                read=VerificationResult)


def ladder(scene="mueller2023", full=False, diagnostics=False, rung=None, members=None, end_time=None, output=None,
           progress=None):
    """A Ladder, saved into ``output`` when given."""
    return _saved(Ladder(scene, full, diagnostics, rung, members, end_time, progress), output)


def sweep(scene="mueller2023", model="rom", case=None, step=None, from_=None, to=None, settle_time=None,
          average_time=None, free_time=None, output=None, progress=None):
    """A Sweep, saved into ``output`` when given."""
    return _saved(Sweep(scene, model, case, step, from_, to, settle_time, average_time, free_time, progress), output)


def map(scene="mueller2023", frequency=None, acceleration=None, start=None, axis=None, model="rom", members=None,
        end_time=None, perturbation=None, output=None, progress=None):
    """A Map, saved into ``output`` when given."""
    return _saved(Map(scene, frequency, acceleration, start, axis, model, members, end_time, perturbation, progress),
                  output)
