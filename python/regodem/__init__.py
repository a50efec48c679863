"""RegoDEM from Python: scenarios, runs and their results (docs/python.md).

    import regodem
    scenario = regodem.Scenario("scenarios/demo.yaml").set("stages.heat.duration", "1 s")
    run = regodem.Run(scenario, output="out/demo-py", overwrite=True)
    run.run_stage()                     # the first stage, then it waits
    p = run.particles()                 # numpy arrays by particle id
    run.step(1000)                      # 1,000 more steps
    run.run(progress=print)             # to the end
    out = regodem.read_run("out/demo-py")
    out.time_series["time [s]"], out.summary["outcome"]

A run from Python is `regodem run`: the same output directory, checkpoints and
summary; its time series and measurement files are the command line's byte for byte.
"""
from . import _regodem
from ._regodem import InputError, SimulationError, CheckpointError
from .scenario import Scenario
from .run import Run, resume
from .outputs import RunOutputs, read_run, read_table
from .doe import ccd, fit, solve, Fit

__version__ = _regodem.version

__all__ = [
    "Scenario", "Run", "resume", "RunOutputs", "read_run", "read_table", "ccd", "fit", "solve", "Fit",
    "InputError", "SimulationError", "CheckpointError",
]
