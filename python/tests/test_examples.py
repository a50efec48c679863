"""The examples in examples/python/ run end to end on their small inputs (seconds each),
so that they keep working as the module changes."""
import os
import subprocess
import sys

from conftest import SOURCE_DIR

EXAMPLES = os.path.join(SOURCE_DIR, "examples", "python")


def run_example(name, *args, cwd):
    result = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *args], capture_output=True, text=True,
                            cwd=cwd, env={**os.environ, "OMP_NUM_THREADS": "2"})
    assert result.returncode == 0, f"{name} exited {result.returncode}:\n{result.stdout}\n{result.stderr}"
    return result.stdout


def test_the_chip_zone_figure_of_the_tiny_drill(tmp_path):
    png = run_example("chip_zone_figure.py", cwd=tmp_path).strip().splitlines()[-1]
    assert os.path.getsize(os.path.join(tmp_path, png)) > 10_000


def test_the_matching_cells_design_from_python(tmp_path):
    text = run_example("matching_cell_ccd.py", "--cell", "tiny", "-o", str(tmp_path / "ccd"), cwd=tmp_path)
    assert "T_d = " in text and "R^2" in text
    assert len([d for d in os.listdir(tmp_path / "ccd") if d.startswith("point_")]) == 11


def test_the_demo_sweep(tmp_path):
    text = run_example("demo_sweep.py", "--quick", "-o", str(tmp_path / "sweep"), cwd=tmp_path)
    assert len(text.strip().splitlines()) == 4  # a header and a row per conductivity


def test_the_step_convergence_study(tmp_path):
    text = run_example("step_convergence.py", "--fractions", "0.2,0.1", "-o", str(tmp_path / "steps"), cwd=tmp_path)
    lines = text.strip().splitlines()
    lines = lines[next(k for k, line in enumerate(lines) if line.startswith("fraction")):]  # past the log lines
    assert len(lines) == 3  # a header and a row per step
    # Half the step, twice the steps of the fastest impact (the same grains strike alike
    # early on; 5 % allows for the run's different later course).
    first, second = (float(line.split()[6]) for line in lines[1:])
    assert abs(second / first - 2.0) < 0.1
