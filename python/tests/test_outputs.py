"""A run's output files read into numpy columns (and pandas, where installed)."""
import numpy as np
import pytest

import regodem


def test_a_runs_outputs_read_as_columns(small_cli_run):
    out = regodem.read_run(small_cli_run)
    series = out.time_series
    time = series["time"]
    assert series.unit("time") == "s"
    assert np.all(np.diff(time) >= 0.0)  # a stage boundary is sampled by both stages
    assert time[-1] == pytest.approx(0.8, abs=1e-3)
    assert np.array_equal(series["time [s]"], time)
    assert out.summary["outcome"] == "completed"
    assert len(series) == len(time)
    assert set(out.regions) == {"low", "under_press", "cup_band"}
    assert set(out.profiles) == {"height"}
    with pytest.raises(KeyError, match="no column"):
        series["no such column"]


def test_pandas_frames_where_pandas_is_installed(small_cli_run):
    pytest.importorskip("pandas")
    frame = regodem.read_run(small_cli_run).time_series.to_pandas()
    assert "time [s]" in frame.columns


def test_a_folder_without_a_run_is_refused(tmp_path):
    with pytest.raises(FileNotFoundError):
        regodem.read_run(tmp_path)


def test_one_csv_reads_alone(small_cli_run):
    table = regodem.read_table(small_cli_run / "regions" / "low.csv")
    assert "time" in table and len(table) > 0
    assert table.as_dict().keys() == set(table.headers)
