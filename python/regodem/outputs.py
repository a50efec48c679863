"""A finished (or running) run's output files as numpy columns, and as pandas
DataFrames where pandas is installed (docs/outputs.md describes the files)."""
import csv
import json
import os
import re

import numpy as np

_HEADER = re.compile(r"^(.*) \[(.*)\]$")


class Table:
    """One CSV of a run: its columns by name, each a numpy array.

    table["time"] or table["time [s]"]: a column; table.names, table.units; len(table)
    rows; table.to_pandas() a DataFrame with the CSV's headers ("time [s]")."""

    def __init__(self, path, headers, columns):
        self.path = path
        self.headers = headers
        self.names = []
        self.units = []
        for header in headers:
            match = _HEADER.match(header)
            self.names.append(match.group(1) if match else header)
            self.units.append(match.group(2) if match else "")
        self._columns = columns

    def __getitem__(self, key):
        if key in self.headers:
            return self._columns[self.headers.index(key)]
        if key in self.names:
            return self._columns[self.names.index(key)]
        raise KeyError(f"{self.path} has no column '{key}' (it has {', '.join(self.names)})")

    def __contains__(self, key):
        return key in self.headers or key in self.names

    def __len__(self):
        return len(self._columns[0]) if self._columns else 0

    def unit(self, name):
        return self.units[self.names.index(name)] if name in self.names else self.units[self.headers.index(name)]

    def as_dict(self):
        return dict(zip(self.headers, self._columns))

    def to_pandas(self):
        import pandas  # not a dependency of RegoDEM: installed by whoever wants DataFrames
        return pandas.DataFrame(self.as_dict())

    def __repr__(self):
        return f"Table({os.path.basename(self.path)!r}, {len(self)} rows, {len(self.headers)} columns)"


def read_table(path):
    """Reads one of a run's CSV files (numbers in every column)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{path} is empty: no header row")
    headers = rows[0]
    data = np.array([[float(v) for v in row] for row in rows[1:] if row], dtype=float).reshape(-1, len(headers))
    return Table(os.fspath(path), headers, [data[:, c].copy() for c in range(len(headers))])


def _tables_in(folder):
    if not os.path.isdir(folder):
        return {}
    return {name[:-4]: read_table(os.path.join(folder, name)) for name in sorted(os.listdir(folder))
            if name.endswith(".csv")}


class RunOutputs:
    """What a run wrote in its directory: time_series (a Table), regions and profiles
    ({name: Table}), bond_breaks (a Table or None), summary (summary.json as a dict, None
    while the run has not ended)."""

    def __init__(self, directory):
        self.directory = os.fspath(directory)
        series = os.path.join(self.directory, "time_series.csv")
        if not os.path.isfile(series):
            raise FileNotFoundError(f"'{self.directory}' holds no time_series.csv: not a run's output directory")
        self.time_series = read_table(series)
        self.regions = _tables_in(os.path.join(self.directory, "regions"))
        self.profiles = _tables_in(os.path.join(self.directory, "profiles"))
        breaks = os.path.join(self.directory, "bond_breaks.csv")
        self.bond_breaks = read_table(breaks) if os.path.isfile(breaks) else None
        summary = os.path.join(self.directory, "summary.json")
        self.summary = None
        if os.path.isfile(summary):
            with open(summary) as f:
                self.summary = json.load(f)

    def __repr__(self):
        status = self.summary["outcome"] if self.summary else "no summary"
        return f"RunOutputs({self.directory!r}, {status}, {len(self.time_series)} samples)"


def read_run(directory):
    """Reads a run's outputs (see RunOutputs)."""
    return RunOutputs(directory)
