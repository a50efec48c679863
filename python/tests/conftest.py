"""Shared set-up of the Python module's tests: where the sources and the `regodem`
program are (ctest passes them; by hand: PYTHONPATH=build/ci/python python3 -m pytest python/tests)."""
import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("REGODEM_SOURCE_DIR", os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
BINARY = os.environ.get("REGODEM_BINARY", os.path.join(SOURCE_DIR, "build", "ci", "regodem"))
# The checkpoint tests' small run: a rate insertion, heat with a fixed floor and a lumped
# cup, a press that comes down and turns, bonds formed at the second stage, measurements
# of every kind and snapshots (tests/data/scenarios/checkpoint_small.yaml).
SMALL = os.path.join(SOURCE_DIR, "tests", "data", "scenarios", "checkpoint_small.yaml")


def data_scenario(name):
    return os.path.join(SOURCE_DIR, "tests", "data", "scenarios", name)


def run_cli(*args, check=True):
    result = subprocess.run([BINARY, *args], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"regodem {' '.join(args)} exited {result.returncode}:\n{result.stderr}")
    return result


def file_text(path):
    with open(path) as f:
        return f.read()


@pytest.fixture
def small_cli_run(tmp_path_factory):
    """The small scenario run once by the command line, on 2 threads."""
    directory = tmp_path_factory.mktemp("cli") / "small"
    run_cli("run", SMALL, "-o", str(directory), "--threads", "2")
    return directory
