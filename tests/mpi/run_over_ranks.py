#!/usr/bin/env python3
"""`mpirun -np N regodem run` (issue 19): the same scenario on 1, 2 and 3 ranks.

Usage: run_over_ranks.py REGODEM MPIEXEC WORK_DIRECTORY

Bounds, stated before the runs:
- the particles are stepped bit for bit alike on every rank count, and the samples,
  regions and profiles are each rank's own particles summed exactly (core/exact_sum.hpp)
  and merged over the ranks (gathered only at every 10th sample, insertion attempts,
  snapshots and stage ends): every particle snapshot (.vtp),
  region table and profile is byte for byte the same, and so is every time-series column
  but the walls' totals and energy_imbalance (below);
- the walls' forces, torques and heat flows (and the heat they brought in, the ledger's
  boundary_heat_in) and the contacts' totals (stored, dissipated and generated energy,
  the energy audit built on them) are sums over the ranks' contacts, added in rank order
  (Communicator::sum_in_rank_order): they agree within 1e-9 of the column's largest
  magnitude (one rounding per pass, 1e-16 relative, over < 1e5 passes); energy_imbalance,
  (E - E_0 - heat in - heat made) / |E|, takes its heat in from them, so it agrees within
  1e-9 of the largest heat in and made, over the smallest |E|;
- the heat books close within 1e-9 of the heat on every rank count (a gather that lost
  or doubled heat would not);
- grains that leave the domain (over_ranks_spill.yaml: most of its 160) are removed alike
  on every rank count, with the same bounds;
- the tiny drilling model (bonds, a turning auger, a lumped sieve, lost grains) breaks
  the same bonds at the same instants on every rank count (bond_breaks.csv byte for byte);
- a run that cannot start on one rank stops every rank with its message, exit status 2,
  within the timeout (no rank waits for one that stopped);
- a study (`envelope --ranks-per-run 2`) runs each point over 2 ranks, with the responses
  of the runs in one process (runs.csv byte for byte: one grain, stepped alike).
"""
import csv
import filecmp
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

REGODEM, MPIEXEC, WORK = sys.argv[1], sys.argv[2], Path(sys.argv[3])
REPOSITORY = Path(__file__).resolve().parents[2]
SCENARIOS = REPOSITORY / "tests" / "data" / "scenarios"
SCENARIO = SCENARIOS / "over_ranks_small.yaml"  # 240 grains, all kept
# Columns that are sums over the ranks' contacts (the walls' and the contacts' totals).
SUMMED_OVER_RANKS = (".force_", ".torque_", ".heat_flow", ".heat_to_particles", ".thrust", ".drive_torque",
                     "elastic_energy", "spring_source", "dissipated_energy", "generated_heat", "wall_work",
                     "mechanical_imbalance", "boundary_heat_in")
TIMEOUT_S = 900  # a run takes seconds alone; oversubscribed ranks beside a build take minutes
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def mpirun(ranks, *arguments):
    # Ranks that wait yield their core: more ranks than cores otherwise spin against each other.
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1",
               OMPI_MCA_mpi_yield_when_idle="1")
    command = [MPIEXEC, "-np", str(ranks), "--oversubscribe", REGODEM, *arguments]
    return subprocess.run(command, capture_output=True, text=True, env=env, timeout=TIMEOUT_S)


def run_on_ranks(label, scenario, rank_counts, *arguments):
    """Runs `scenario` on each rank count into WORK/<label><ranks>; returns the folders by rank count."""
    outs = {}
    for ranks in rank_counts:
        out = WORK / f"{label}{ranks}"
        result = mpirun(ranks, "run", str(scenario), "-o", str(out), "--overwrite", *arguments)
        check(result.returncode == 0, f"{label} on {ranks} ranks: exit status {result.returncode}\n"
                                      f"{result.stderr[-2000:]}")
        outs[ranks] = out
    return outs


def last_value(out, column):
    header, table = rows(out / "time_series.csv")
    return float(table[-1][header.index(column)])


def rows(path):
    with open(path, newline="") as f:
        table = list(csv.reader(f))
    return table[0], table[1:]


def unresolved_impact_noticed(run):
    return any("a Hertz contact of" in n for n in json.loads((run / "summary.json").read_text()).get("notices", []))


def compare_runs(reference, other, label):
    for folder in ("regions", "profiles"):
        if not (reference / folder).exists():
            continue
        common = sorted(p.name for p in (reference / folder).iterdir())
        check(common == sorted(p.name for p in (other / folder).iterdir()), f"{label}: {folder}/ holds other files")
        for name in common:
            check(filecmp.cmp(reference / folder / name, other / folder / name, shallow=False),
                  f"{label}: {folder}/{name} differs")
    snapshots = sorted((reference / "vtk").glob("particles_*.vtp"))
    check(len(snapshots) >= 3, f"{label}: {len(snapshots)} particle snapshots")
    for snapshot in snapshots:
        check(filecmp.cmp(snapshot, other / "vtk" / snapshot.name, shallow=False), f"{label}: {snapshot.name} differs")
    header, a = rows(reference / "time_series.csv")
    other_header, b = rows(other / "time_series.csv")
    check(header == other_header and len(a) == len(b), f"{label}: the time series has other columns or rows")
    for column, name in enumerate(header):
        values_a = [r[column] for r in a]
        values_b = [r[column] for r in b]
        if name == "energy_imbalance [-]" and "boundary_heat_in [J]" in header:
            # (E - E_0 - heat in - heat made) / |E|: its heat in comes from the walls' sums,
            # which agree with one process within round-off (summed in rank order), so this
            # ratio does within the summed columns' 1e-9 of the heat that entered, over |E|.
            heat = [max(abs(float(r[header.index(c)])) for r in a)
                    for c in ("boundary_heat_in [J]", "generated_heat [J]") if c in header]
            energy = min(abs(float(r[header.index("thermal_energy [J]")])) for r in a)
            worst = max(abs(float(x) - float(y)) for x, y in zip(values_a, values_b))
            check(worst <= 1e-9 * sum(heat) / energy, f"{label}: column '{name}' differs by {worst:.3g}")
            continue
        if not any(marker in name for marker in SUMMED_OVER_RANKS):
            check(values_a == values_b, f"{label}: column '{name}' differs")
            continue
        scale = max(abs(float(v)) for v in values_a) or 1.0
        worst = max(abs(float(x) - float(y)) for x, y in zip(values_a, values_b))
        check(worst <= 1e-9 * scale, f"{label}: column '{name}' differs by {worst:.3g} (largest value {scale:.3g})")
    summary = json.loads((other / "summary.json").read_text())
    expected = json.loads((reference / "summary.json").read_text())["particles"]
    check(summary["outcome"] == "completed" and summary["particles"] == expected,
          f"{label}: summary says {summary['outcome']} with {summary['particles']} particles, not {expected}")


runs = {}
for ranks in (1, 2, 3):
    out = WORK / f"ranks{ranks}"
    # Periodic checkpoints on 2 ranks: taken at the run's own gathers, they change nothing.
    every = ["--checkpoint-every", "0.3s"] if ranks == 2 else []
    result = mpirun(ranks, "run", str(SCENARIO), "-o", str(out), "--overwrite", *every)
    check(result.returncode == 0, f"{ranks} ranks: exit status {result.returncode}\n{result.stderr[-2000:]}")
    lines = result.stdout.strip().splitlines()
    check(len(lines) == 1 and lines[0].startswith("regodem: completed 2 stages"),
          f"{ranks} ranks: stdout is {result.stdout!r} (one final line, from rank 0 alone)")
    runs[ranks] = out
    recorded = json.loads((out / "summary.json").read_text()).get("mpi_ranks")
    check(recorded == ranks, f"{ranks} ranks: summary.json says mpi_ranks {recorded}")
    header, table = rows(out / "time_series.csv")
    column = header.index("energy_imbalance [-]")
    worst = max(abs(float(r[column])) for r in table)
    check(worst <= 1e-9, f"{ranks} ranks: the heat books are out by {worst:.3g} of the heat (more than 1e-9)")
for ranks in (2, 3):
    compare_runs(runs[1], runs[ranks], f"{ranks} ranks against 1")

# A stage that ends on a measurement (its target tested every 64 steps, each test a
# merge of the ranks' sums, nothing gathered) ends at the same step on every rank count.
measured = run_on_ranks("measured_end", SCENARIO, (1, 2, 3), "--set",
                        "stages.press={name: press, until: {measurement: low, quantity: mean, rises_to: 370 K}, "
                        "max_duration: 0.4 s}")
ends = [json.loads((measured[r] / "summary.json").read_text())["stages"][1].get("end_time_s") for r in (1, 2, 3)]
check(ends[0] is not None and 0.31 < ends[0] < 0.69, f"the measured end: the press stage ended at {ends[0]} s, "
                                                      "not before its max_duration")
for ranks in (2, 3):
    compare_runs(measured[1], measured[ranks], f"measured end on {ranks} ranks against 1")

# Grains lost over the edge of a table are removed on the rank that held them, the same
# grains on every rank count, and leave the books of every rank alike.
spills = run_on_ranks("spill", SCENARIOS / "over_ranks_spill.yaml", (1, 2, 3))
lost = last_value(spills[1], "particles_lost [-]")
check(lost >= 100, f"the spill lost {lost:.0f} of its 160 grains, not most of them")
for ranks in (2, 3):
    compare_runs(spills[1], spills[ranks], f"spill on {ranks} ranks against 1")
# Sampled every step (each sample merged over the ranks, the particles split), with a
# snapshot (a gather) every 16 steps: the build after a gather, where each rank still
# holds every grain as its own when one leaves, must still count it once.
every_step = run_on_ranks("spill_every_step", SCENARIOS / "over_ranks_spill.yaml", (1, 2),
                          "--set", "output.interval=1e-9 s", "--set", "output.snapshots.every_steps=16",
                          "--set", "stages.pour.duration=0.2 s")
check(last_value(every_step[1], "particles_lost [-]") >= 20, "the spill sampled every step lost too few grains")
compare_runs(every_step[1], every_step[2], "spill sampled every step on 2 ranks against 1")

# The tiny drilling model: bonds formed over the bed (many across the bricks), a turning
# auger mesh, a lumped sieve, grains lost: the same bonds broken (bond_breaks.csv byte for
# byte), and everything else as above, on 1, 2 and 3 ranks.
bed = WORK / "tiny_bed"
result = subprocess.run([REGODEM, "run", str(REPOSITORY / "scenarios/paper/tiny/drill-bed.yaml"), "-o", str(bed),
                         "--overwrite", "--threads", "1"], capture_output=True, text=True, timeout=TIMEOUT_S)
check(result.returncode == 0, f"the tiny bed: exit status {result.returncode}\n{result.stderr[-2000:]}")
drills = run_on_ranks("drill", REPOSITORY / "scenarios/paper/tiny/drill-sieve.yaml", (1, 2, 3),
                      "--set", f"initial_state.checkpoint={bed}",
                      "--set", "output={interval: 0.01 s, snapshots: {every_steps: 400}}")
broken = last_value(drills[1], "bonds_broken [-]")
check(broken >= 50, f"the drill broke {broken:.0f} bonds, too few to test their breaks over ranks")
check(unresolved_impact_noticed(drills[1]), "the tiny drill: one process gave no unresolved-impact notice")
for ranks in (2, 3):
    compare_runs(drills[1], drills[ranks], f"drill on {ranks} ranks against 1")
    # Another rank's impact reaches rank 0 at the next gather: noticed then.
    check(unresolved_impact_noticed(drills[ranks]), f"drill on {ranks} ranks: no unresolved-impact notice")
    check(filecmp.cmp(drills[1] / "bond_breaks.csv", drills[ranks] / "bond_breaks.csv", shallow=False),
          f"drill on {ranks} ranks: bond_breaks.csv differs")

# A checkpoint written over 2 ranks (one process's, gathered) resumed on 1 and on 3: the
# last checkpoint taken away, the newest before it; the run goes on as it was.
for ranks in (1, 3):
    copy = WORK / f"resumed_on_{ranks}"
    shutil.rmtree(copy, ignore_errors=True)
    shutil.copytree(runs[2], copy)
    checkpoints = sorted((copy / "checkpoints").glob("checkpoint_*.rgck"))
    written = int(checkpoints[-1].stem.split("_")[1])  # numbered from 1; the oldest are pruned
    check(written > 2, f"the run over 2 ranks wrote {written} checkpoints, none periodic")
    checkpoints[-1].unlink()  # the end of the last stage: resume from the newest before it
    result = mpirun(ranks, "resume", str(copy))
    check(result.returncode == 0, f"resumed on {ranks} ranks: exit status {result.returncode}\n{result.stderr[-2000:]}")
    compare_runs(runs[1], copy, f"resumed on {ranks} ranks")

# A directory in use: rank 0 refuses it, and every rank stops.
refused = mpirun(2, "run", str(SCENARIO), "-o", str(runs[1]))
check(refused.returncode == 2, f"a used directory: exit status {refused.returncode}")
check(refused.stderr.count("regodem: error:") == 1 and "is not empty" in refused.stderr,
      f"a used directory: the error not once on stderr:\n{refused.stderr}")

# A scenario that cannot be read is refused on every rank, its message once.
bad = mpirun(2, "run", str(SCENARIOS / "unknown_key.yaml"), "-o", str(WORK / "bad"), "--overwrite")
check(bad.returncode == 2 and bad.stderr.count("regodem: error:") == 1,
      f"a bad scenario: exit status {bad.returncode}, stderr:\n{bad.stderr}")
check(not (WORK / "bad").exists(), "a bad scenario: the refused run left its directory")

# A study whose runs go over ranks (`envelope --ranks-per-run 2`, each run started as
# `MPIEXEC --oversubscribe -np 2 regodem run ...`, and once as `MPIEXEC --oversubscribe -n 2`
# from `--mpirun "... -n {ranks}"`): every run says it ran over 2 ranks, and
# the responses equal those of runs in one process (the grain on a plate: one grain, its
# temperature stepped bit for bit alike; runs.csv byte for byte).
CALIBRATE = SCENARIOS / "calibrate"
study = WORK / "envelope"
shutil.rmtree(study, ignore_errors=True)
study.mkdir(parents=True)
for name in ("plate.yaml", "grain.csv", "plate_envelope.yaml"):
    shutil.copy(CALIBRATE / name, study / name)
study_env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1",
                 OMPI_MCA_mpi_yield_when_idle="1")
one = subprocess.run([REGODEM, "envelope", "plate_envelope.yaml", "-o", "one", "--processes", "1"], cwd=study,
                     capture_output=True, text=True, env=study_env, timeout=TIMEOUT_S)
two = subprocess.run([REGODEM, "envelope", "plate_envelope.yaml", "-o", "two", "--processes", "1", "--ranks-per-run",
                      "2", "--mpirun", f"{MPIEXEC} --oversubscribe"], cwd=study, capture_output=True, text=True,
                     env=study_env, timeout=TIMEOUT_S)
# The same with a launcher that is told where the count goes (as `srun -n {ranks}` would be).
placed = subprocess.run([REGODEM, "envelope", "plate_envelope.yaml", "-o", "placed", "--processes", "1",
                         "--ranks-per-run", "2", "--mpirun", f"{MPIEXEC} --oversubscribe -n {{ranks}}"], cwd=study,
                        capture_output=True, text=True, env=study_env, timeout=TIMEOUT_S)
check(one.returncode == 0, f"envelope in one process: exit status {one.returncode}\n{one.stdout[-2000:]}{one.stderr[-2000:]}")
for name, result, launched in (("two", two, "--oversubscribe -np 2"), ("placed", placed, "--oversubscribe -n 2")):
    check(result.returncode == 0,
          f"envelope over ranks ({name}): exit status {result.returncode}\n{result.stdout[-2000:]}{result.stderr[-2000:]}")
    if one.returncode != 0 or result.returncode != 0:
        continue
    check("over 2 MPI ranks" in result.stdout and launched in result.stdout,
          f"envelope over ranks ({name}): the progress does not say '{launched}'")
    logs = sorted((study / name / "logs").glob("*.log"))
    check(len(logs) > 0 and all("over 2 MPI ranks" in log.read_text() for log in logs),
          f"envelope over ranks ({name}): not every run of {len(logs)} ran over 2 ranks")
    check(filecmp.cmp(study / "one" / "runs.csv", study / name / "runs.csv", shallow=False),
          f"envelope over ranks ({name}): runs.csv differs from the runs in one process")

print("run over ranks:", "FAILED" if failures else "passed", f"({len(failures)} failures)")
sys.exit(1 if failures else 0)
