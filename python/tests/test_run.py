"""Runs from Python: the command line's outputs bit for bit, whole or in pieces; the state
by particle id; changes that keep the energy books; Ctrl-C, close and resume; errors."""
import filecmp
import json
import os
import signal
import threading

import numpy as np
import pytest

import regodem
from conftest import SMALL, file_text, run_cli

# Every file of a run whose numbers must match the command line's bit for bit.
COMPARED = ["time_series.csv", "regions/low.csv", "regions/under_press.csv", "regions/cup_band.csv",
            "profiles/height.csv", "bond_breaks.csv"]


def assert_same_outputs(a, b):
    for name in COMPARED:
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        assert os.path.exists(pa) == os.path.exists(pb), name
        if os.path.exists(pa):
            assert filecmp.cmp(pa, pb, shallow=False), f"{name} differs between {a} and {b}"


def summary(directory):
    with open(os.path.join(directory, "summary.json")) as f:
        return json.load(f)


def test_a_whole_run_is_the_command_lines_bit_for_bit(small_cli_run, tmp_path):
    run = regodem.Run(SMALL, output=tmp_path / "py", threads=2, quiet=True)
    assert run.status == "ready"
    assert run.run() == "completed"
    assert run.finished and "completed 2 stages" in run.final_line
    assert_same_outputs(small_cli_run, tmp_path / "py")
    a, b = summary(small_cli_run), summary(tmp_path / "py")
    for key in ("outcome", "particles", "steps", "simulated_time_s", "bonds", "lumped_walls", "measurements"):
        assert a[key] == b[key], key
    assert file_text(small_cli_run / "scenario.yaml") == file_text(tmp_path / "py" / "scenario.yaml")


def test_steps_and_stages_in_pieces_are_the_unbroken_run(small_cli_run, tmp_path):
    # On 1 thread against the command line's 2: results do not depend on the count.
    run = regodem.Run(SMALL, output=tmp_path / "py", threads=1, quiet=True)
    assert run.step(997) == "paused"
    assert run.step_count == 997
    run.particles(), run.walls(), run.sample(), run.measurements(), run.energy()  # reading changes nothing
    assert run.run_stage() == "paused"
    assert run.stage["name"] == "fill" and not run.stage["running"]
    assert run.step(1) == "paused" and run.stage["name"] == "press" and run.stage["running"]
    for _ in range(5):
        run.step(1234)
    assert run.run() == "completed"
    assert_same_outputs(small_cli_run, tmp_path / "py")


def test_the_state_by_particle_id(tmp_path):
    run = regodem.Run(SMALL, output=tmp_path / "py", threads=2, quiet=True)
    run.run_stage()
    p = run.particles()
    n = len(p["id"])
    assert n == 40  # the fill inserts 40 in its 0.3 s
    assert np.all(np.diff(p["id"].astype(np.int64)) > 0)
    for key in ("position_m", "velocity_m_per_s", "angular_velocity_rad_per_s", "force_N"):
        assert p[key].shape == (n, 3)
    assert np.allclose(p["radius_m"], 0.5e-3)
    assert np.all(np.abs(p["position_m"][:, :2]) < 4e-3) and np.all(p["position_m"][:, 2] > 0.0)
    assert "temperature_K" in p and "peak_temperature_K" in p
    assert run.material_names == ["grain"]
    walls = {w["name"]: w for w in run.walls()}
    assert walls["floor"]["thermal"] == "fixed" and walls["floor"]["temperature_K"] == pytest.approx(400.0)
    assert walls["cup"]["thermal"] == "lumped"
    assert "depth_m" in walls["press"]
    sample = run.sample()
    assert sample["time [s]"] == pytest.approx(run.time_s)
    measured = run.measurements()
    assert set(measured) == {"low", "under_press", "cup_band", "height"}
    assert measured["height"]["kind"] == "profile"


def test_set_temperatures_changes_them_and_keeps_the_ledger_closed(tmp_path):
    run = regodem.Run(SMALL, output=tmp_path / "py", threads=2, quiet=True)
    run.run_stage()
    p = run.particles()
    ids = p["id"][:5]
    before = run.energy()
    # The change the ledger must book: sum m c (T' - T), c constant (800 J/(kg K)).
    added_J = float(np.sum(p["mass_kg"][:5] * 800.0 * (300.0 - p["temperature_K"][:5])))
    run.set_temperatures(ids, 300.0)
    after = run.energy()
    assert np.all(run.particles()["temperature_K"][:5] == 300.0)
    assert after["thermal_energy_J"] - before["thermal_energy_J"] == pytest.approx(added_J, rel=1e-9)
    # Tolerance stated before the run: the imbalance stays at round-off, 1e-9 of the energy.
    assert abs(after["thermal_imbalance_J"]) < 1e-9 * after["thermal_energy_J"]
    assert run.run() == "completed"
    end = run.energy()
    assert abs(end["thermal_imbalance_J"]) < 1e-9 * end["thermal_energy_J"]


def test_set_velocities_books_the_kinetic_energy_as_exchanged(tmp_path):
    scenario = regodem.Scenario(SMALL).set("output.energy_audit", True)
    run = regodem.Run(scenario, output=tmp_path / "py", threads=2, quiet=True)
    run.run_stage()
    p = run.particles()
    ids = p["id"][:3]
    v_new = np.array([[0.0, 0.0, 0.05]] * 3)
    change_J = float(np.sum(0.5 * p["mass_kg"][:3] * (np.sum(v_new**2, axis=1) - np.sum(p["velocity_m_per_s"][:3]**2, axis=1))))
    before = run.energy()
    run.set_velocities(ids, v_new)
    after = run.energy()
    assert np.array_equal(run.particles()["velocity_m_per_s"][:3], v_new)
    assert after["exchanged_J"] - before["exchanged_J"] == pytest.approx(change_J, rel=1e-9, abs=1e-18)
    assert after["mechanical_imbalance_J"] == pytest.approx(before["mechanical_imbalance_J"], abs=1e-15)


def test_close_leaves_a_run_that_resumes_to_the_same_end(small_cli_run, tmp_path):
    directory = tmp_path / "py"
    run = regodem.Run(SMALL, output=directory, threads=2, quiet=True)
    run.step(3000)
    run.close()
    assert run.status == "interrupted"
    assert summary(directory)["outcome"] == "interrupted"
    assert os.listdir(directory / "checkpoints")
    resumed = regodem.resume(directory, quiet=True)
    assert resumed.run() == "completed"
    assert_same_outputs(small_cli_run, directory)
    # The command line continues a Python run too: it has completed, nothing to resume.
    assert "has completed" in run_cli("resume", str(directory)).stdout


def test_ctrl_c_stops_the_run_with_a_checkpoint(tmp_path):
    # Long enough to be stepping when the signal comes: the press stage for 20 s.
    scenario = regodem.Scenario(SMALL).set("stages.press.duration", "20 s")
    directory = tmp_path / "py"
    run = regodem.Run(scenario, output=directory, threads=2, quiet=True)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        run.run()
    timer.join()
    assert run.status == "interrupted"
    assert "interrupted by KeyboardInterrupt" in run.final_line
    assert summary(directory)["outcome"] == "interrupted"
    assert regodem.resume(directory, quiet=True).status == "ready"


def test_progress_reaches_the_callback_and_its_exception_stops_the_run(tmp_path):
    scenario = regodem.Scenario(SMALL).set("stages.press.duration", "20 s")
    run = regodem.Run(scenario, output=tmp_path / "py", threads=2, quiet=True)
    seen = []

    def progress(info):
        seen.append(info)
        run.particles()  # refused while the run steps

    with pytest.raises(regodem.InputError, match="stepping"):
        run.run(progress=progress)
    assert seen and seen[0]["stages"] == 2 and seen[0]["time_s"] > 0.0
    assert run.status == "interrupted"


def test_a_failed_stage_raises_simulation_error(tmp_path):
    # 1,000 grains at 400 /s cannot be placed in the fill's 0.3 s: the stage fails.
    scenario = regodem.Scenario(SMALL).set("insertions.fill.count", 1000)
    run = regodem.Run(scenario, output=tmp_path / "py", threads=2, quiet=True)
    with pytest.raises(regodem.SimulationError, match="insertion 'fill'"):
        run.run()
    assert run.status == "failed"
    assert summary(tmp_path / "py")["outcome"] == "failed"


def test_bad_calls_are_input_errors(tmp_path):
    run = regodem.Run(SMALL, output=tmp_path / "py", threads=2, quiet=True)
    run.run_stage()
    with pytest.raises(regodem.InputError, match="no particle has id 4000"):
        run.set_temperatures([4000], 300.0)
    with pytest.raises(regodem.InputError, match="above 0 K"):
        run.set_temperatures(run.particles()["id"][:1], -1.0)
    with pytest.raises(regodem.InputError):
        run.step(-1)
    run.run()
    with pytest.raises(regodem.InputError, match="has ended"):
        run.set_temperatures(run.particles()["id"][:1], 300.0)
    # The directory holds a run now: a new one there needs overwrite.
    with pytest.raises(regodem.InputError):
        regodem.Run(SMALL, output=tmp_path / "py", quiet=True)
    assert regodem.Run(SMALL, output=tmp_path / "py", overwrite=True, quiet=True).status == "ready"
