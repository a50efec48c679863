"""Runs: whole, stage by stage or N steps at a time, with the state between calls."""
import os
import re

import numpy as np

from . import _regodem
from .scenario import Scenario

_WALL_UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}


def _seconds(duration):
    """10, "90 s", "10min", "2 h": a wall-clock duration in seconds (None: 0, never)."""
    if duration is None:
        return 0.0
    if isinstance(duration, (int, float)):
        seconds = float(duration)
    else:
        match = re.fullmatch(r"\s*([0-9.eE+-]+)\s*(s|min|h)\s*", str(duration))
        if not match:
            raise _regodem.InputError(f"checkpoint_every: '{duration}' is not a duration such as 90 s, 10min, 2 h")
        seconds = float(match.group(1)) * _WALL_UNITS[match.group(2)]
    if not seconds > 0.0:
        raise _regodem.InputError(f"checkpoint_every must be a positive duration, got {duration!r}")
    return seconds


def _ids(ids):
    ids = np.atleast_1d(np.asarray(ids))
    if ids.ndim != 1 or (ids.size and (not np.issubdtype(ids.dtype, np.integer) or ids.min() < 0)):
        raise _regodem.InputError("particle ids must be a 1-d sequence of integers >= 0")
    return ids.astype(np.uint64)


def _rows(values, shape, name):
    """`values` as a float array of `shape`: one value (or one row) for all, or one per id."""
    values = np.asarray(values, dtype=float)
    try:
        return np.ascontiguousarray(np.broadcast_to(values, shape))
    except ValueError:
        raise _regodem.InputError(f"{name} of shape {values.shape} does not fit {shape[0]} ids "
                                  f"(give one value for all, or {shape})") from None


class Run:
    """A run of a scenario into its output directory, as `regodem run` makes it.

    Run(scenario, output=None, threads=None, overwrite=False, checkpoint_every=None,
    quiet=False): `scenario` a Scenario or a file's path; `output` the directory
    (default out/<name>); `threads` as --threads (default: the cores other processes
    leave free); `quiet` hides the progress lines on stderr. The directory is checked and
    prepared at once; nothing runs until step(), run_stage() or run().

    Between those calls the run waits at a step boundary: its state can be read
    (particles(), walls(), sample(), measurements(), energy()) and changed
    (set_temperatures(), set_velocities()), and it goes on exactly as an unbroken run
    would. Ctrl-C (or an exception from the progress callback) stops it as on the command
    line: a checkpoint and summary.json, resumable with regodem.resume(directory) or
    `regodem resume`. A run left unfinished is stopped that way when closed (close(), the
    end of a `with` block, or when Python drops it).
    """

    def __init__(self, scenario, output=None, threads=None, overwrite=False, checkpoint_every=None, quiet=False,
                 _core=None):
        if _core is not None:
            self._core = _core
            return
        if not isinstance(scenario, Scenario):
            scenario = Scenario(scenario)
        self._core = _regodem.Run(scenario.path, scenario.text, list(scenario.overrides),
                                  os.fspath(output) if output is not None else "", int(threads or 0),
                                  bool(overwrite), _seconds(checkpoint_every), bool(quiet))

    # Running.
    def step(self, steps, progress=None):
        """Runs `steps` more time steps (mechanical ones, or a static-bed stage's heat
        steps), fewer if the run ends first. Returns the status: "paused", "completed",
        "interrupted"; raises SimulationError if a stage failed (the outputs are written)."""
        steps = int(steps)
        if steps < 0:
            raise _regodem.InputError(f"step: a number of steps must be >= 0, got {steps}")
        return self._core.advance(steps, False, progress)

    def run_stage(self, progress=None):
        """Runs until the stage now running (or the next one) ends; the run then waits
        between stages (after the last stage it ends: status "completed")."""
        return self._core.advance(2**64 - 1, True, progress)

    def run(self, progress=None):
        """Runs to the end. `progress(info)` is called about every half second with a dict
        (stage, stage_index, stages, time_s, step, particles, wall_s, particle_steps_per_s,
        estimated_remaining_s)."""
        return self._core.advance(2**64 - 1, False, progress)

    def close(self):
        """Stops a run that has not ended (as Ctrl-C does: checkpoint, summary)."""
        self._core.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    # Where it stands.
    status = property(lambda self: self._core.status, doc='"ready", "paused", "completed", "failed", "interrupted"')
    finished = property(lambda self: self._core.finished)
    directory = property(lambda self: self._core.directory, doc="The output directory")
    threads = property(lambda self: self._core.threads)
    time_s = property(lambda self: self._core.time_s, doc="Simulated time")
    step_count = property(lambda self: self._core.step, doc="Mechanical steps taken since the start")
    stage = property(lambda self: self._core.stage,
                     doc="The stage running or last run: name, index, count, start_time_s, running (None before the first)")
    final_line = property(lambda self: self._core.final_line, doc="What `regodem run` prints at the end")
    message = property(lambda self: self._core.message, doc="Why the run stopped, when it did not complete")
    material_names = property(lambda self: self._core.material_names)
    region_names = property(lambda self: self._core.region_names)

    # The state, by particle id.
    def particles(self):
        """The particles as numpy arrays in order of id: id, radius_m, mass_kg,
        position_m (N, 3), velocity_m_per_s, angular_velocity_rad_per_s, force_N,
        material and region (indices into material_names and region_names), and with heat
        temperature_K, peak_temperature_K and time_above_threshold_s (when tracked)."""
        return self._core.particles()

    def walls(self):
        """Each wall body: name, force_N, torque_N_m, displacement_m, its pose (position_m
        and rotation, x = R x0 + position for a point x0 of a mesh wall as placed at the
        start), depth_m
        (fed walls), work_J (with the energy audit), thermal mode and temperature_K,
        peak_temperature_K, segment_temperatures_K and heat flows (thermal walls)."""
        return self._core.walls()

    def sample(self):
        """The time series' latest row as {"name [unit]": value}."""
        return self._core.sample()

    def measurements(self):
        """Each measurement's latest rows: {name: {"kind", "columns", "rows"}}."""
        return self._core.measurements()

    def energy(self):
        """The energy books now: thermal energy and its ledger (heat on), kinetic energy,
        and the mechanical audit (when kept)."""
        return self._core.energy()

    def set_temperatures(self, ids, temperatures_K):
        """Sets the temperatures of the particles with these ids. The energy ledger books
        the change (its reference takes it, as for an inserted particle), so the run's
        energy balance stays closed."""
        ids = _ids(ids)
        self._core.set_temperatures(ids, _rows(temperatures_K, (ids.size,), "temperatures_K"))

    def set_velocities(self, ids, velocities_m_per_s, angular_velocities_rad_per_s=None):
        """Sets the velocities (N, 3), and the spins if given, of the particles with these
        ids; the energy audit books the change of kinetic energy as exchanged."""
        ids = _ids(ids)
        v = _rows(velocities_m_per_s, (ids.size, 3), "velocities_m_per_s")
        w = None
        if angular_velocities_rad_per_s is not None:
            w = _rows(angular_velocities_rad_per_s, (ids.size, 3), "angular_velocities_rad_per_s")
        self._core.set_velocities(ids, v, w)

    def outputs(self):
        """The run's output files as read_run() reads them."""
        from .outputs import read_run
        return read_run(self.directory)

    def __repr__(self):
        return f"Run({self.directory!r}, {self.status})"


def resume(directory, threads=None, checkpoint_every=None, quiet=False):
    """Continues the run in `directory` from its newest usable checkpoint, as
    `regodem resume` does; returns a Run that waits for step(), run_stage() or run()."""
    core = _regodem.Run.resume(os.fspath(directory), int(threads or 0), _seconds(checkpoint_every), bool(quiet))
    return Run(None, _core=core)
