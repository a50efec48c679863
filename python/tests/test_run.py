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
    run = regodem.Run(SMALL, output=tmp_path / "py", threads=2, quiet=True)
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
    with pytest.raises(regodem.InputError, match="does not fit"):
        run.set_velocities(ids, np.zeros((2, 3)))


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


@pytest.fixture(scope="module")
def tiny_drill_bed(tmp_path_factory):
    """The tiny drilling bed (scenarios/paper/tiny/drill-bed.yaml), poured once."""
    from conftest import SOURCE_DIR
    bed = tmp_path_factory.mktemp("drill") / "bed"
    run_cli("run", os.path.join(SOURCE_DIR, "scenarios", "paper", "tiny", "drill-bed.yaml"), "-o", str(bed))
    return bed


def tiny_drill(bed):
    from conftest import SOURCE_DIR
    path = os.path.join(SOURCE_DIR, "scenarios", "paper", "tiny", "drill-heat.yaml")
    return path, ["initial_state.checkpoint=" + str(bed)]


def test_the_heated_tiny_drill_in_pieces_is_the_command_lines(tiny_drill_bed, tmp_path):
    # A mesh drill that feeds and turns, bonds that break, the drill as a 5-slice rod that
    # radiates: stepped from Python in pieces, against one command-line run.
    path, values = tiny_drill(tiny_drill_bed)
    run_cli("run", path, "-o", str(tmp_path / "cli"), "--threads", "2", *[a for v in values for a in ("--set", v)])
    run = regodem.Run(regodem.Scenario(path, set=values), output=tmp_path / "py", threads=2, quiet=True)
    while run.step(4321) == "paused":
        pass
    assert run.status == "completed"
    for name in ("time_series.csv", "regions/chip_zone.csv", "profiles/radial_2mm.csv", "bond_breaks.csv"):
        a, b = tmp_path / "cli" / name, tmp_path / "py" / name
        assert a.exists() == b.exists(), name
        if a.exists():
            assert filecmp.cmp(a, b, shallow=False), name


def test_the_drills_pose_follows_its_motion(tiny_drill_bed, tmp_path):
    path, values = tiny_drill(tiny_drill_bed)
    run = regodem.Run(regodem.Scenario(path, set=values), output=tmp_path / "py", threads=2, quiet=True)
    run.step(2000)
    drill = next(w for w in run.walls() if w["name"] == "drill")
    t = run.time_s
    # Stated before the run: the pose is the motion's (feed -40 mm/s, spin -16000 rpm about
    # z from t = 0) to 1e-9 m and 1e-9 in each entry of the rotation. The pose maps the mesh
    # as placed at the start (its 12 mm placement included) to now.
    theta = -16000.0 * 2.0 * np.pi / 60.0 * t
    expected = np.array([[np.cos(theta), -np.sin(theta), 0.0], [np.sin(theta), np.cos(theta), 0.0], [0.0, 0.0, 1.0]])
    assert np.max(np.abs(drill["rotation"] - expected)) < 1e-9
    assert abs(drill["position_m"][2] - (-40e-3 * t)) < 1e-9
    assert len(drill["segment_temperatures_K"]) == 5


def test_checkpoint_every_takes_durations_and_refuses_others(tmp_path):
    assert regodem.run._seconds("10min") == 600.0 and regodem.run._seconds("2 h") == 7200.0
    assert regodem.run._seconds(90) == 90.0 and regodem.run._seconds(None) == 0.0
    for bad in ("soon", "-5 s", 0):
        with pytest.raises(regodem.InputError):
            regodem.Run(SMALL, output=tmp_path / "py", checkpoint_every=bad, quiet=True)


def test_resume_with_its_own_threads_and_names(small_cli_run, tmp_path):
    directory = tmp_path / "py"
    run = regodem.Run(SMALL, output=directory, threads=2, quiet=True)
    assert run.region_names and run.material_names == ["grain"]
    run.step(20000)
    run.close()
    resumed = regodem.resume(directory, threads=1, quiet=True)
    assert resumed.threads == 1 and resumed.step_count == run.step_count
    resumed.run()
    assert_same_outputs(small_cli_run, directory)
    with pytest.raises(regodem.InputError, match="has completed"):
        regodem.resume(directory, quiet=True)
    with pytest.raises(regodem.InputError, match="not a run's output directory"):
        regodem.resume(tmp_path / "nothing", quiet=True)


def test_the_ledger_books_a_temperature_change_through_c_of_T(tmp_path):
    # c(T) = 500 + 2.5 (T - 200 K) J/(kg K) between 200 and 400 K: the change the ledger
    # must book is m [500 (T - 200) + 1.25 (T - 200)^2] from T0 to 300 K, to 1e-9.
    scenario = regodem.Scenario(SMALL).set("materials.grain.specific_heat",
                                           {"temperature": ["200 K", "400 K"], "value": [500, 1000]})
    run = regodem.Run(scenario, output=tmp_path / "py", threads=2, quiet=True)
    run.run_stage()
    p = run.particles()
    h = lambda T: 500.0 * (T - 200.0) + 1.25 * (T - 200.0) ** 2
    assert np.all((p["temperature_K"][:4] > 200.0) & (p["temperature_K"][:4] < 400.0))
    expected_J = float(np.sum(p["mass_kg"][:4] * (h(300.0) - h(p["temperature_K"][:4]))))
    before = run.energy()
    run.set_temperatures(p["id"][:4], [300.0, 300.0, 300.0, 300.0])
    after = run.energy()
    assert after["thermal_energy_J"] - before["thermal_energy_J"] == pytest.approx(expected_J, rel=1e-9)
    assert after["thermal_reference_J"] - before["thermal_reference_J"] == pytest.approx(expected_J, rel=1e-9)
    assert np.all(run.particles()["peak_temperature_K"][:4] >= 300.0)


def test_a_change_to_a_resumed_run_is_the_state_it_goes_on_from(tmp_path):
    directory = tmp_path / "py"
    run = regodem.Run(SMALL, output=directory, threads=2, quiet=True)
    run.step(20000)  # inside the press stage
    run.close()
    resumed = regodem.resume(directory, quiet=True)
    ids = resumed.particles()["id"][:3]
    resumed.set_temperatures(ids, 1000.0)
    assert np.all(resumed.particles()["temperature_K"][:3] == 1000.0)
    resumed.step(1)
    # One step of conduction moves a grain by far less than the 700 K it was raised by.
    assert np.all(resumed.particles()["temperature_K"][:3] > 900.0)
    resumed.run()
    assert abs(resumed.energy()["thermal_imbalance_J"]) < 1e-9 * resumed.energy()["thermal_energy_J"]


def test_run_stage_after_the_last_stage_ends_the_run(tmp_path):
    run = regodem.Run(SMALL, output=tmp_path / "py", threads=2, quiet=True)
    assert run.run_stage() == "paused"
    assert run.run_stage() == "completed" and run.finished
    assert summary(tmp_path / "py")["outcome"] == "completed"


def test_the_callback_cannot_step_the_run(tmp_path):
    scenario = regodem.Scenario(SMALL).set("stages.press.duration", "20 s")
    run = regodem.Run(scenario, output=tmp_path / "py", threads=2, quiet=True)
    with pytest.raises(regodem.InputError, match="stepping already"):
        run.run(progress=lambda info: run.step(10))
    assert run.status == "interrupted"
    assert "progress callback" in run.final_line
