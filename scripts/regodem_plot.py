#!/usr/bin/python3
"""PNG figures from RegoDEM runs: `regodem plot` runs this script.

    regodem_plot.py OUTDIR [OUTDIR...] [--labels A,B,...] [--out DIR]
                    [--section] [--section-axis z] [--section-through X,Y,Z]
                    [--section-thickness M]
    regodem_plot.py --envelope ENVELOPE_OUTDIR --threshold VALUE   (regodem envelope's map)

Reads each run's time_series.csv (header "name [unit]") and any other CSV with such a
header in the run's folder and in regions/ (region and band series), each profile in
profiles/ as one line per instant, and writes figures of
FIG_WIDTH x FIG_HEIGHT pixels into DIR (default: the first OUTDIR's plots/ folder).
Several runs are overlaid, one colour per run, labelled by --labels or their folder
names. A run with heat.time_scale_factor S != 1 is drawn against its real_time column
(simulated time x S), and the axis says so; with S = 1 against time. A figure whose columns no run has is left out, and the message says so.
--section draws the particle temperature on a plane through an axis from each run's
latest snapshot (particles.pvd), walls cut by the plane as lines, beside the temperature
of every particle along that axis. Prints the path of each figure, then (on stderr) the
folder they are in.

Exit status: 0 figures written; 2 bad input (no such run, no data, a bad option, a CSV
that cannot be read: one line "regodem plot: error: FILE:LINE: what is wrong");
3 matplotlib or numpy is missing; 1 a fault of this script (one line says where).
"""
import argparse
import csv
import math
import os
import re
import struct
import sys
import traceback
import xml.etree.ElementTree as ET
import zlib

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")  # files only, no display
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection, LineCollection
    from matplotlib.colors import BoundaryNorm, ListedColormap
except ImportError as error:
    print(f"regodem plot: error: {error}: plotting needs matplotlib and numpy for {sys.executable} "
          "(Debian: apt-get install python3-matplotlib, as scripts/setup-debian.sh does)", file=sys.stderr)
    sys.exit(3)

FIG_WIDTH, FIG_HEIGHT, DPI = 960, 600, 120  # pixels; documented in docs/outputs.md
HEADER = re.compile(r"^(.*?)\s*\[([^\[\]]*)\]$")  # "sieve[1].temperature [K]": the last [...] is the unit


class BadInput(Exception):
    pass


def is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


# ---------------------------------------------------------------------------------
# Reading runs


class Series:
    """One CSV: columns by name, each with its unit. Anything wrong with the file is a
    BadInput naming the file and line ("FILE:LINE: what"), except a last line without its
    newline that does not parse: a row a running run is still writing, left out with a note."""

    def __init__(self, path, required=()):
        self.path = path
        try:
            with open(path, "rb") as f:
                content = f.read()
        except OSError as error:
            raise BadInput(f"{path}: cannot read it: {error.strerror}")
        if not content.strip():
            raise BadInput(f"{path}:1: empty file (a CSV begins with a header line of \"name [unit]\" columns)")
        try:
            text = content.decode("utf-8")
        except UnicodeDecodeError as error:
            line = content.count(b"\n", 0, error.start) + 1
            raise BadInput(f"{path}:{line}: not text: byte 0x{content[error.start]:02x} is not UTF-8")
        if "\0" in text:
            line = text.count("\n", 0, text.index("\0")) + 1
            raise BadInput(f"{path}:{line}: holds a NUL byte (not a CSV file, or a damaged one)")
        lines = text.split("\n")
        unfinished = lines.pop()  # "" when the file ends with a newline, as RegoDEM's do
        if not lines:
            raise BadInput(f"{path}:1: the header line is incomplete (no newline at its end)")
        header = self.fields(lines[0], path, 1)
        self.names, self.units = [], {}
        if all(is_number(field) for field in header):
            raise BadInput(f"{path}:1: no header: the first line holds numbers where the column names "
                           f"(\"name [unit]\") should be")
        for k, field in enumerate(header):
            match = HEADER.match(field.strip())
            name, unit = (match.group(1).strip(), match.group(2)) if match else (field.strip(), "")
            if name == "friction_heat":  # its name before 2026-12-02
                name = "generated_heat"
            if not name or is_number(name):
                raise BadInput(f"{path}:1: column {k + 1} of the header has no name ('{field}')")
            if name in self.units:
                raise BadInput(f"{path}:1: column '{name}' appears twice in the header")
            self.names.append(name)
            self.units[name] = unit
        for name in required:
            if name not in self.units:
                raise BadInput(f"{path}:1: no '{name}' column in the header")
        width = len(self.names)
        data = []
        for number, line in enumerate(lines[1:], start=2):
            if line.strip():
                data.append(self.row(line, path, number, width))
        if unfinished.strip():
            number = len(lines) + 1
            try:
                data.append(self.row(unfinished, path, number, width))
            except BadInput:
                print(f"regodem plot: note: {path}:{number}: the last row is incomplete (no newline at its end: "
                      "a run still writing it?); left out", file=sys.stderr)
        self.data = np.array(data, dtype=float).reshape(-1, width)

    @staticmethod
    def fields(line, path, number):
        try:
            return next(csv.reader([line.rstrip("\r")]))
        except (csv.Error, StopIteration) as error:
            raise BadInput(f"{path}:{number}: not a CSV line ({error})")

    def row(self, line, path, number, width):
        fields = self.fields(line, path, number)
        if len(fields) != width:
            raise BadInput(f"{path}:{number}: {len(fields)} fields where the header has {width} "
                           "(a truncated or damaged row)")
        values = []
        for name, field in zip(self.names, fields):
            field = field.strip()
            if field == "":
                values.append(math.nan)
                continue
            try:
                values.append(float(field))
            except ValueError:
                shown = field if len(field) <= 40 else field[:37] + "..."
                raise BadInput(f"{path}:{number}: column '{name}' holds '{shown}', not a number")
        return values

    def has(self, name):
        return name in self.units

    def column(self, name):
        return self.data[:, self.names.index(name)]

    def label(self, name, quantity=None):
        unit = self.units.get(name, "")
        text = quantity or name.replace("_", " ")
        return f"{text} [{unit}]" if unit and unit != "-" else text

    def time_scale(self):
        """heat.time_scale_factor S of the run: real_time / time (1 without a real_time column)."""
        if not (self.has("time") and self.has("real_time")) or not len(self.data):
            return 1.0
        time, real = self.column("time"), self.column("real_time")
        nonzero = np.isfinite(time) & np.isfinite(real) & (time != 0)
        return float(np.median(real[nonzero] / time[nonzero])) if np.any(nonzero) else 1.0


def compressed(scale):
    return abs(scale - 1.0) > 1e-9


def time_axis(series):
    """The time column the figures of these series use, and its label. A run with
    heat.time_scale_factor S != 1 (real_time = time x S) is drawn against real time;
    runs with S = 1, or files without a real_time column, against time as before."""
    present = [s for s in series if s is not None and s.has("time")]
    scales = sorted({round(s.time_scale(), 9) for s in present if compressed(s.time_scale())})
    if scales and all(s.has("real_time") for s in present):
        factor = f"{scales[0]:.4g}" if len(scales) == 1 else "S"
        return "real_time", f"real time [s] (simulated time × {factor})"
    return "time", "time [s]"


class Run:
    def __init__(self, directory, label):
        self.directory = directory
        self.label = label
        if not os.path.isdir(directory):
            raise BadInput(f"'{directory}' is not a directory (give the OUTDIR of a `regodem run`)")
        path = os.path.join(directory, "time_series.csv")
        self.series = Series(path, required=("time",)) if os.path.isfile(path) else None
        self.others = {}
        for name in sorted(os.listdir(directory)):
            if name.endswith(".csv") and name != "time_series.csv":
                # Not a file RegoDEM writes there: one it cannot read is skipped, not an error.
                try:
                    self.others[name] = Series(os.path.join(directory, name))
                except BadInput as error:
                    print(f"regodem plot: skipping {error}", file=sys.stderr)
        self.profiles = {}  # profiles/NAME.csv: long form, one row per bin and instant
        for sub in ("profiles", "regions"):  # the measurements' CSV files
            folder = os.path.join(directory, sub)
            if os.path.isdir(folder):
                for name in sorted(os.listdir(folder)):
                    if name.endswith(".csv"):
                        series = Series(os.path.join(folder, name))
                        if sub == "profiles" and is_profile(series):
                            self.profiles[name[: -len(".csv")]] = series
                        else:
                            self.others[f"{sub}/{name}"] = series


def is_profile(series):
    """A profile as RegoDEM writes it: time, [depth,] distance or radius, temperatures, count."""
    return series.has("time") and (series.has("distance") or series.has("radius")) and series.has("count")


# ---------------------------------------------------------------------------------
# Figures


def new_figure(rows=1):
    fig, axes = plt.subplots(rows, 1, figsize=(FIG_WIDTH / DPI, FIG_HEIGHT / DPI), dpi=DPI, sharex=True,
                             squeeze=False)
    return fig, [a[0] for a in axes]


def save(fig, out_dir, name, written):
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=DPI)  # no bbox_inches="tight": every figure has the documented size
    plt.close(fig)
    written.append(path)


def colours(n):
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return [cycle[i % len(cycle)] for i in range(n)]


def mark_stages(ax, series, time_name="time"):
    """Light vertical lines where a stage begins."""
    if not series.has("stage") or len(series.data) < 2:
        return
    stage, time = series.column("stage"), series.column(time_name)
    for k in np.nonzero(np.diff(stage))[0]:
        ax.axvline(time[k + 1], color="0.85", linewidth=0.8, zorder=0)


def runs_with(runs, *names):
    return [r for r in runs if r.series is not None and all(r.series.has(n) for n in names) and len(r.series.data)]


def plot_temperature(runs, out_dir, written):
    have = runs_with(runs, "time", "temperature_mean", "temperature_min", "temperature_max")
    if not have:
        return "particle temperature (no run has heat on)"
    fig, (ax,) = new_figure()
    time_name, time_label = time_axis([r.series for r in have])
    for run, colour in zip(have, colours(len(runs))):
        s = run.series
        t = s.column(time_name)
        ax.plot(t, s.column("temperature_mean"), color=colour, label=f"{run.label}: mean")
        ax.fill_between(t, s.column("temperature_min"), s.column("temperature_max"), color=colour, alpha=0.15,
                        label=f"{run.label}: min to max")
        mark_stages(ax, s, time_name)
    s = have[0].series
    ax.set_xlabel(time_label)
    ax.set_ylabel(s.label("temperature_mean", "particle temperature"))
    ax.set_title("Particle temperature")
    ax.legend(fontsize="small")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "temperature.png", written)


def plot_wall_temperatures(runs, out_dir, written):
    fig, (ax,) = new_figure()
    any_line = False
    styles = ["-", "--", ":", "-."]
    time_name, time_label = time_axis([r.series for r in runs])
    for r, (run, colour) in enumerate(zip(runs, colours(len(runs)))):
        s = run.series
        if s is None or not s.has("time") or not len(s.data):
            continue
        walls = [n for n in s.names if n.endswith(".temperature")]
        for k, name in enumerate(walls):
            ax.plot(s.column(time_name), s.column(name), color=colour if len(runs) > 1 else None,
                    linestyle=styles[k % len(styles)] if len(runs) > 1 else "-",
                    label=f"{run.label}: {name[: -len('.temperature')]}" if len(runs) > 1 else name[: -len(".temperature")])
            any_line = True
            unit_source = s
            unit_name = name
    if not any_line:
        plt.close(fig)
        return "wall temperatures (no fixed or lumped wall)"
    ax.set_xlabel(time_label)
    ax.set_ylabel(unit_source.label(unit_name, "wall temperature"))
    ax.set_title("Wall temperatures")
    ax.legend(fontsize="x-small", ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "wall_temperatures.png", written)


def plot_energy_balance(runs, out_dir, written):
    have = runs_with(runs, "time", "thermal_energy", "boundary_heat_in", "generated_heat", "energy_imbalance")
    if not have:
        return "energy balance (no run has heat on)"
    fig, (top, bottom) = new_figure(2)
    time_name, time_label = time_axis([r.series for r in have])
    for run, colour in zip(have, colours(len(runs))):
        s = run.series
        t = s.column(time_name)
        energy = s.column("thermal_energy")
        top.plot(t, energy - energy[0], color=colour, label=f"{run.label}: change of thermal energy")
        top.plot(t, s.column("boundary_heat_in") + s.column("generated_heat"), color=colour, linestyle="--",
                 label=f"{run.label}: heat in (fixed walls + generated)")
        bottom.plot(t, s.column("energy_imbalance"), color=colour, label=run.label)
        mark_stages(top, s, time_name)
        mark_stages(bottom, s, time_name)
    s = have[0].series
    top.set_ylabel(s.label("thermal_energy", "energy"))
    top.set_title("Energy balance")
    top.legend(fontsize="x-small")
    bottom.set_ylabel("relative imbalance [-]")
    bottom.set_xlabel(time_label)
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "energy_balance.png", written)


def plot_wall_forces(runs, out_dir, written):
    fig, (top, bottom) = new_figure(2)
    any_line = False
    time_name, time_label = time_axis([r.series for r in runs])
    for run, colour in zip(runs, colours(len(runs))):
        s = run.series
        if s is None or not s.has("time") or not len(s.data):
            continue
        t = s.column(time_name)
        walls = [n[: -len(".force_x")] for n in s.names if n.endswith(".force_x")]
        walls = [w for w in walls if all(s.has(f"{w}.{q}_{a}") for q in ("force", "torque") for a in "xyz")]
        for wall in walls:
            force = np.sqrt(sum(s.column(f"{wall}.force_{a}") ** 2 for a in "xyz"))
            torque = np.sqrt(sum(s.column(f"{wall}.torque_{a}") ** 2 for a in "xyz"))
            if not np.any(force > 0) and not np.any(torque > 0):
                continue  # a wall nothing touched
            label = f"{run.label}: {wall}" if len(runs) > 1 else wall
            top.plot(t, force, label=label)
            bottom.plot(t, torque, label=label)
            any_line = True
            unit_source = s
            unit_wall = wall
    if not any_line:
        plt.close(fig)
        return "wall forces (no particle touched a wall)"
    top.set_ylabel(unit_source.label(f"{unit_wall}.force_x", "force on the wall"))
    bottom.set_ylabel(unit_source.label(f"{unit_wall}.torque_x", "torque on the wall"))
    bottom.set_xlabel(time_label)
    top.set_title("Wall forces and torques (magnitude)")
    top.legend(fontsize="x-small", ncol=2)
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "wall_forces.png", written)


def plot_mechanics(runs, out_dir, written):
    have = runs_with(runs, "time", "kinetic_energy", "coordination_number")
    if not have:
        return "kinetic energy (no time series)"
    fig, (top, bottom) = new_figure(2)
    time_name, time_label = time_axis([r.series for r in have])
    for run, colour in zip(have, colours(len(runs))):
        s = run.series
        t = s.column(time_name)
        kinetic = s.column("kinetic_energy")
        top.plot(t, np.where(kinetic > 0, kinetic, np.nan), color=colour, label=run.label)
        bottom.plot(t, s.column("coordination_number"), color=colour, label=run.label)
        mark_stages(top, s, time_name)
    s = have[0].series
    if np.any(np.concatenate([r.series.column("kinetic_energy") for r in have]) > 0):
        top.set_yscale("log")
    top.set_ylabel(s.label("kinetic_energy", "kinetic energy"))
    bottom.set_ylabel(s.label("coordination_number", "coordination number"))
    bottom.set_xlabel(time_label)
    top.set_title("Kinetic energy and coordination number")
    top.legend(fontsize="small")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "mechanics.png", written)


def plot_other_csvs(runs, out_dir, written):
    """Profiles and region series: every further CSV, its columns against its first (against
    real time where the first is time and the run's time was compressed). real_time, a copy
    of time x S, is not drawn as a line of its own."""
    names = sorted({name for run in runs for name in run.others})
    for name in names:
        fig, (ax,) = new_figure()
        any_line = False
        time_name, time_label = time_axis([run.others.get(name) for run in runs])
        for run, colour in zip(runs, colours(len(runs))):
            s = run.others.get(name)
            if s is None or len(s.names) < 2 or not len(s.data):
                continue
            x = s.names[0]
            ys = [y for y in s.names[1:] if y != "real_time"]
            if x == "time":
                x = time_name
                ys = [y for y in ys if y != "time"]
            for k, y in enumerate(ys):
                ax.plot(s.column(x), s.column(y), color=colour if len(runs) > 1 else None,
                        linestyle=["-", "--", ":", "-."][k % 4] if len(runs) > 1 else "-",
                        label=f"{run.label}: {y}" if len(runs) > 1 else y)
                any_line = True
            ax.set_xlabel(time_label if x == time_name else s.label(x))
            units = {s.units[y] for y in ys}
            ax.set_ylabel(f"value [{units.pop()}]" if len(units) == 1 else "value (see legend for units)")
        if not any_line:
            plt.close(fig)
            continue
        ax.set_title(name)
        ax.legend(fontsize="x-small", ncol=2)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        save(fig, out_dir, re.sub(r"[^A-Za-z0-9_.-]", "_", name[: -len(".csv")]) + ".png", written)


def plot_profiles(runs, out_dir, written):
    """Each profile: mean temperature (count without heat) against distance or radius, one
    line per instant, labelled by its depth where it has one (Fig. 13a), else its time."""
    names = sorted({name for run in runs for name in run.profiles})
    for name in names:
        fig, (ax,) = new_figure()
        any_line = False
        styles = ["-", "--", ":", "-."]
        for run, colour in zip(runs, colours(len(runs))):
            s = run.profiles.get(name)
            if s is None or not len(s.data):
                continue
            x = "radius" if s.has("radius") else "distance"
            y = "temperature_mean" if s.has("temperature_mean") else "count"
            key = "depth" if s.has("depth") else time_axis([s])[0]
            instants = list(dict.fromkeys(s.column("time")))
            for k, t in enumerate(instants):
                rows = s.column("time") == t
                tag = f"{key.replace('_', ' ')} {s.column(key)[rows][0]:.4g} {s.units[key]}"
                ax.plot(s.column(x)[rows], s.column(y)[rows], marker=".",
                        color=colour if len(runs) > 1 else None,
                        linestyle=styles[k % len(styles)] if len(runs) > 1 else "-",
                        label=f"{run.label}: {tag}" if len(runs) > 1 else tag)
                any_line = True
            ax.set_xlabel(s.label(x))
            ax.set_ylabel(s.label(y))
        if not any_line:
            plt.close(fig)
            continue
        ax.set_title(f"profile {name}")
        ax.legend(fontsize="x-small", ncol=2)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        save(fig, out_dir, "profiles_" + re.sub(r"[^A-Za-z0-9_.-]", "_", name) + ".png", written)


# ---------------------------------------------------------------------------------
# Snapshots (the .vtp files RegoDEM writes: raw appended data, optionally zlib)

VTK_TYPES = {"Float64": "d", "Float32": "f", "Int32": "i", "Int64": "q", "UInt8": "B", "UInt16": "H",
             "UInt32": "I", "UInt64": "Q", "Int8": "b", "Int16": "h"}


def read_vtp(path):
    """Arrays of a RegoDEM .vtp by name: 'Points', point data, cell data ('cell:NAME'),
    'Polys' (triangles, n x 3), field strings ('field:NAME')."""
    with open(path, "rb") as f:
        content = f.read()
    start = content.find(b"<AppendedData")
    marker = content.find(b"_", start)
    if start < 0 or marker < 0:
        raise BadInput(f"{path}: not a RegoDEM snapshot (no raw appended data)")
    root = ET.fromstring(content[:start] + b"</VTKFile>")
    data = content[marker + 1:]
    header = "<Q" if root.get("header_type", "UInt32") == "UInt64" else "<I"
    size = struct.calcsize(header)
    compressed = root.get("compressor") is not None
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        raise BadInput(f"{path}: big-endian snapshots are not supported here")

    def block(offset):
        if not compressed:
            (n,) = struct.unpack_from(header, data, offset)
            return data[offset + size: offset + size + n]
        blocks, _, _ = struct.unpack_from("<" + header[1] * 3, data, offset)
        sizes = struct.unpack_from("<" + header[1] * blocks, data, offset + 3 * size)
        at = offset + (3 + blocks) * size
        out = b""
        for s in sizes:
            out += zlib.decompress(data[at: at + s])
            at += s
        return out

    arrays = {}
    for parent in root.iter():
        for element in parent:
            if element.tag not in ("DataArray", "Array") or element.get("format") != "appended":
                continue
            raw = block(int(element.get("offset")))
            kind = element.get("type")
            place = parent.tag
            if kind == "String":
                arrays[f"field:{element.get('Name')}"] = raw.decode().split("\0")[:-1]
                continue
            values = np.frombuffer(raw, dtype=np.dtype("<" + VTK_TYPES[kind]))
            components = int(element.get("NumberOfComponents", "1"))
            if components > 1:
                values = values.reshape(-1, components)
            name = element.get("Name")
            if place == "CellData":
                name = f"cell:{name}"
            elif place in ("Polys", "Verts"):
                name = f"{place}:{name}"
            arrays[name] = values
    if "Polys:connectivity" in arrays:
        arrays["Polys"] = arrays["Polys:connectivity"].reshape(-1, 3)
    return arrays


def latest_snapshot(run, collection):
    path = os.path.join(run.directory, collection)
    if not os.path.isfile(path):
        return None, None
    entries = [(float(d.get("timestep")), d.get("file")) for d in ET.parse(path).getroot().iter("DataSet")]
    if not entries:
        return None, None
    time, file = entries[-1]
    return time, os.path.join(run.directory, file)


MM = 1e3  # the section is drawn in millimetres


def plot_section(run, args, out_dir, written, name):
    """The particles cut by a plane through an axis, coloured by temperature, with the walls
    the plane cuts as lines; beside it, every particle's temperature along that axis (mean
    and range of each region's particles in bins), on the same scale. The view spans the
    bed along the axis and the particles and walls across it; the panels are sized to fill
    the figure, and the title is wrapped to fit it."""
    time, path = latest_snapshot(run, "particles.pvd")
    if path is None:
        raise BadInput(f"{run.directory}: no particles.pvd: --section needs snapshots "
                       "(output.snapshots in the scenario, see docs/scenario-format.md)")
    particles = read_vtp(path)
    axis = "xyz".index(args.section_axis)
    across, normal = (axis + 1) % 3, (axis + 2) % 3  # the plane holds the axis and `across`
    through = args.section_through
    points = particles["Points"].reshape(-1, 3)
    radius = particles["radius"]
    distance = points[:, normal] - through[normal]
    slab = args.section_thickness / 2 if args.section_thickness else None
    # A sphere cut by the plane shows a disk of radius sqrt(R^2 - d^2); a thicker slab
    # shows every particle within it at its full radius.
    cut = np.abs(distance) < (slab if slab else radius)
    shown_r = radius[cut] if slab else np.sqrt(np.maximum(radius[cut] ** 2 - distance[cut] ** 2, 0.0))
    heat = "temperature" in particles
    region_names = particles.get("field:region_names", [])
    if heat:
        colour_by, cmap = particles["temperature"], plt.get_cmap("turbo")
        norm = plt.Normalize(float(np.nanmin(colour_by)), float(np.nanmax(colour_by))) if len(colour_by) else None
    else:  # each region in its colour of the profile beside it (C0, C1, ...)
        colour_by = particles["region"].astype(float)
        count = max(len(region_names), int(colour_by.max()) + 1 if len(colour_by) else 1)
        cmap = ListedColormap([f"C{k % 10}" for k in range(count)])
        norm = BoundaryNorm(np.arange(count + 1) - 0.5, count)
    offsets = np.column_stack([points[cut, across], points[cut, axis]])
    _, wall_path = latest_snapshot(run, "walls.pvd")
    segments = wall_cuts(read_vtp(wall_path), normal, through[normal], across, axis) if wall_path else \
        np.zeros((0, 2, 2))

    # The view: along the axis, the bed (every particle); across it, the cut particles and
    # the walls the plane cuts.
    if len(points):
        along = (float((points[:, axis] - radius).min()), float((points[:, axis] + radius).max()))
    elif len(segments):
        along = (float(segments[:, :, 1].min()), float(segments[:, :, 1].max()))
    else:
        along = (-1e-3, 1e-3)
    xs = [offsets[:, 0] - shown_r, offsets[:, 0] + shown_r] if len(offsets) else []
    if len(segments):
        xs.append(segments[:, :, 0].ravel())
    if not xs and len(points):
        xs = [points[:, across] - radius, points[:, across] + radius]
    xs = np.concatenate(xs) if xs else np.array([-1e-3, 1e-3])
    size = max(float(xs.max() - xs.min()), along[1] - along[0], 1e-9)
    pad = 0.03 * size
    xlim = ((float(xs.min()) - pad) * MM, (float(xs.max()) + pad) * MM)
    ylim = ((along[0] - pad) * MM, (along[1] + pad) * MM)
    # A bed wider than its panel may show the walls above it (a cup, a lid, a drill) up to their top.
    y_top = max(ylim[1], (float(segments[:, :, 1].max()) + pad) * MM) if len(segments) else ylim[1]

    fig = plt.figure(figsize=(FIG_WIDTH / DPI, FIG_HEIGHT / DPI), dpi=DPI)
    ax = fig.add_axes([0.1, 0.1, 0.5, 0.8])
    cax = fig.add_axes([0.62, 0.1, 0.02, 0.8])
    profile = fig.add_axes([0.75, 0.1, 0.2, 0.8])
    disks = EllipseCollection(2 * shown_r * MM, 2 * shown_r * MM, np.zeros_like(shown_r), units="xy",
                              offsets=offsets * MM, transOffset=ax.transData, cmap=cmap, norm=norm, linewidths=0)
    disks.set_array(colour_by[cut])  # on the whole bed's scale
    ax.add_collection(disks)
    if len(segments):
        ax.add_collection(LineCollection(segments * MM, colors="0.2", linewidths=1.0))
    names = "xyz"
    ax.set_xlabel(f"{names[across]} [mm]")
    ax.set_ylabel(f"{names[axis]} [mm]")
    if heat:
        fig.colorbar(disks, cax=cax, label="temperature [K]")
    else:
        bar = fig.colorbar(disks, cax=cax, label="region (heat is off)", ticks=np.arange(cmap.N))
        bar.ax.set_yticklabels([region_names[k] if k < len(region_names) else f"region {k}" for k in range(cmap.N)])
    draw_profile(profile, particles, points[:, axis] * MM, radius * MM, heat, names[axis])
    profile.tick_params(labelleft=False)
    profile.grid(alpha=0.3)

    where = f"{names[normal]} = {through[normal]:g} m"
    if slab:
        where += f", a slab {args.section_thickness:g} m thick"
    # The title's pieces: the label may break between its words, the rest between pieces.
    words = run.label.split()
    if words:
        words[-1] += ":"
    pieces = words + [p.replace(" ", "\u00a0") for p in (
        f"{'temperature' if heat else 'region'} on the section", f"through the {names[axis]} axis",
        f"at {where},", f"t = {time:.4g} s,", f"{int(cut.sum())} particles cut;",
        f"right: all {len(radius)} particles", f"by {names[axis]}")]
    layout_section(fig, ax, cax, profile, pieces, xlim, ylim, y_top)
    save(fig, out_dir, name, written)


def draw_profile(ax, particles, along, radius, heat, axis_name):
    """Each region's particles in bins along the axis (1.5 of its median diameters wide):
    mean temperature and its range, or with heat off the particles per bin."""
    region = particles.get("region")
    region_names = particles.get("field:region_names", [])
    groups = []  # name, colour (the section's with heat off), which particles
    if region is not None and len(region):
        for code in np.unique(region):
            name = region_names[code] if code < len(region_names) else f"region {code}"
            groups.append((name, f"C{code % 10}", region == code))
    elif len(along):
        groups.append(("all particles", "C0", np.ones(len(along), dtype=bool)))
    ax.set_xlabel("temperature [K]" if heat else "particles per bin")
    if not groups:
        return
    low, high = float((along - radius).min()), float((along + radius).max())
    for name, colour, chosen in groups:
        width = max(3 * float(np.median(radius[chosen])), (high - low) / 60, 1e-9)
        edges = np.arange(low, high + width, width)
        index = np.clip(np.digitize(along[chosen], edges) - 1, 0, len(edges) - 2)
        values = particles["temperature"][chosen] if heat else None
        centres, mean, lowest, highest, count = [], [], [], [], []
        for k in range(len(edges) - 1):
            inside = index == k
            if not inside.any():
                continue
            centres.append((edges[k] + edges[k + 1]) / 2)
            count.append(int(inside.sum()))
            if heat:
                mean.append(float(np.mean(values[inside])))
                lowest.append(float(np.min(values[inside])))
                highest.append(float(np.max(values[inside])))
        tag = f"{name} ({int(chosen.sum())})"
        if heat:
            ax.plot(mean, centres, marker=".", color=colour, label=tag)
            ax.fill_betweenx(centres, lowest, highest, color=colour, alpha=0.15, linewidth=0)
        else:
            ax.plot(count, centres, marker=".", color=colour, label=tag)
    ax.legend(fontsize="x-small", loc="best", title_fontsize="x-small",
              title=f"by {axis_name}: mean, min to max" if heat else f"by {axis_name}")


def layout_section(fig, ax, cax, profile, pieces, xlim, ylim, y_top):
    """Places the title (`pieces` joined by spaces, broken into lines between pieces to fit
    the width), the section (its limits `xlim` and `ylim`, in a box as wide for a
    millimetre as it is tall), the colour bar and the profile, in pixels, measuring the
    labels as drawn, so that together they fill the figure's width and nothing crosses
    its edges. The profile keeps at least 30 % of the width; a section too wide for the
    rest shows more above the bed, up to `y_top`, and is otherwise centred in the height."""
    width, height = FIG_WIDTH, FIG_HEIGHT
    margin, gap, bar_width = 8.0, 12.0, 16.0
    renderer = fig.canvas.get_renderer()
    text = fig.text(0.5, 1 - margin / height, "", ha="center", va="top")
    for size in (11, 10, 9, 8):  # smaller only when a piece alone is wider than the figure
        text.set_fontsize(size)
        lines = [""]
        for piece in pieces:
            candidate = f"{lines[-1]} {piece}".strip()
            text.set_text(candidate)
            if lines[-1] and text.get_window_extent(renderer).width > width - 2 * margin:
                lines.append(piece)
            else:
                lines[-1] = candidate
        text.set_text("\n".join(lines))
        box = text.get_window_extent(renderer)
        if box.width <= width - 2 * margin:
            break
    top = height - margin - box.height - gap

    def decorations(axes):
        """The pixels the labels of `axes` take beyond its box: left, bottom, right, top."""
        tight = axes.get_tightbbox(renderer)
        frame = axes.get_window_extent(renderer)
        return (max(frame.x0 - tight.x0, 0.0), max(frame.y0 - tight.y0, 0.0), max(tight.x1 - frame.x1, 0.0),
                max(tight.y1 - frame.y1, 0.0))

    for _ in range(3):  # place, measure the labels as drawn, place again
        ax.set_xlim(*xlim)
        ax.set_ylim(*ylim)
        profile.set_ylim(*ylim)
        fig.canvas.draw()
        left_ax, bottom_ax, right_ax, top_ax = decorations(ax)
        left_profile, bottom_profile, right_profile, top_profile = decorations(profile)
        right_bar = decorations(cax)[2]
        bottom = margin + max(bottom_ax, bottom_profile)
        room_h = top - max(top_ax, top_profile) - bottom
        room_w = (width - 2 * margin - left_ax - right_ax - gap - bar_width - right_bar - 2 * gap - left_profile -
                  right_profile)
        section_w = min(room_h * (xlim[1] - xlim[0]) / (ylim[1] - ylim[0]), 0.7 * room_w)
        section_h = section_w * (ylim[1] - ylim[0]) / (xlim[1] - xlim[0])
        if section_h < room_h and ylim[1] < y_top:  # room above the bed: show the walls there
            ylim = (ylim[0], min(y_top, ylim[0] + (ylim[1] - ylim[0]) * room_h / section_h))
            section_h = section_w * (ylim[1] - ylim[0]) / (xlim[1] - xlim[0])
        y0 = bottom + (room_h - section_h) / 2
        x0 = margin + left_ax
        bar_x = x0 + section_w + right_ax + gap
        profile_x = bar_x + bar_width + right_bar + 2 * gap + left_profile
        ax.set_position([x0 / width, y0 / height, section_w / width, section_h / height])
        cax.set_position([bar_x / width, y0 / height, bar_width / width, section_h / height])
        profile.set_position([profile_x / width, y0 / height, (room_w - section_w) / width, section_h / height])
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    profile.set_ylim(*ylim)


def wall_cuts(walls, normal, level, across, axis):
    """The segments (n x 2 x 2: across, along) where the plane cuts the wall triangles."""
    points = walls.get("Points")
    triangles = walls.get("Polys")
    if points is None or triangles is None:
        return np.zeros((0, 2, 2))
    points = points.reshape(-1, 3)
    segments = []
    for tri in triangles:
        corners = points[tri]
        height = corners[:, normal] - level
        crossing = []
        for a, b in ((0, 1), (1, 2), (2, 0)):
            if (height[a] < 0) != (height[b] < 0):
                t = height[a] / (height[a] - height[b])
                p = corners[a] + t * (corners[b] - corners[a])
                crossing.append((p[across], p[axis]))
        if len(crossing) == 2:
            segments.append(crossing)
    return np.array(segments, dtype=float).reshape(-1, 2, 2)


# ---------------------------------------------------------------------------------


def parse_point(text):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3:
        raise BadInput(f"--section-through takes three numbers in metres, e.g. 0,0,0; got '{text}'")
    return values


def plot_envelope(directory, threshold):
    """`regodem envelope`'s map: the fitted response over the two mapped factors (map.csv,
    a grid), the threshold contour in black, the region beyond the design's circle
    hatched (the surface extrapolates there), the design points (runs.csv) marked, filled
    where the measured response reached the threshold. Written as DIRECTORY/envelope_map.png."""
    grid = Series(os.path.join(directory, "map.csv"))
    if len(grid.names) != 4 or not len(grid.data):
        raise BadInput(f"{grid.path}: expected four columns (x, y, response, inside_design) and a grid of rows")
    xn, yn, rn, inside_name = grid.names
    x, y, z = grid.column(xn), grid.column(yn), grid.column(rn)
    nx = len(np.unique(x))
    if nx * (len(x) // nx) != len(x):
        raise BadInput(f"{grid.path}: the rows are not a full grid")
    X, Y, Z, inside = (a.reshape(-1, nx) for a in (x, y, z, grid.column(inside_name)))
    fig, (ax,) = new_figure()
    filled = ax.contourf(X, Y, Z, levels=20, cmap="coolwarm")
    fig.colorbar(filled, ax=ax, label=grid.label(rn, rn + " (fitted)"))
    if Z.min() < threshold < Z.max():
        line = ax.contour(X, Y, Z, levels=[threshold], colors="black", linewidths=2.0)
        ax.clabel(line, fmt=lambda v: f"{v:.4g}", fontsize="small")
    if (inside < 0.5).any():  # beyond every design point: the surface extrapolates there
        ax.contourf(X, Y, inside, levels=[-0.5, 0.5], colors="none", hatches=["//"])
        ax.contour(X, Y, inside, levels=[0.5], colors="grey", linewidths=0.8, linestyles="dashed")
    points = []
    with open(os.path.join(directory, "runs.csv"), newline="") as f:
        rows = list(csv.reader(f))
    head = [HEADER.match(h).group(1).strip() if HEADER.match(h) else h.strip() for h in rows[0]]
    for row in rows[1:]:
        if len(row) == len(head):
            points.append((float(row[head.index(xn)]), float(row[head.index(yn)]), float(row[head.index(rn)])))
    if points:
        px, py, pz = (np.array(c) for c in zip(*points))
        hot = pz >= threshold
        ax.scatter(px[~hot], py[~hot], marker="o", facecolors="white", edgecolors="black", zorder=3,
                   label=f"design point, measured below {threshold:.4g}")
        if hot.any():
            ax.scatter(px[hot], py[hot], marker="o", color="black", zorder=3,
                       label=f"design point, measured at or above {threshold:.4g}")
        ax.legend(fontsize="x-small", loc="best")
    ax.set_xlabel(grid.label(xn, xn))
    ax.set_ylabel(grid.label(yn, yn))
    unit = f" {grid.units[rn]}" if grid.units.get(rn) else ""
    ax.set_title(f"{rn}: the threshold {threshold:.4g}{unit} (black line) over {xn} x {yn}")
    fig.tight_layout()
    written = []
    save(fig, directory, "envelope_map.png", written)
    return written


def main(argv):
    parser = argparse.ArgumentParser(prog="regodem plot", description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="*", metavar="OUTDIR")
    parser.add_argument("--envelope", metavar="ENVELOPE_OUTDIR", help="draw `regodem envelope`'s map there")
    parser.add_argument("--threshold", type=float, default=float("nan"))
    parser.add_argument("--labels", help="comma-separated, one per OUTDIR")
    parser.add_argument("--out", help="folder for the PNG files (default: FIRST_OUTDIR/plots)")
    parser.add_argument("--section", action="store_true")
    parser.add_argument("--section-axis", choices=["x", "y", "z"], default="z")
    parser.add_argument("--section-through", default="0,0,0")
    parser.add_argument("--section-thickness", type=float, default=0.0)
    args = parser.parse_args(argv)
    if args.envelope:
        try:
            for path in plot_envelope(args.envelope, args.threshold):
                print(path)
        except BadInput as error:
            print(f"regodem plot: error: {error}", file=sys.stderr)
            return 2
        return 0
    if not args.runs:
        parser.error("give at least one OUTDIR")
    try:
        args.section_through = parse_point(args.section_through)
        if args.section_thickness < 0 or not math.isfinite(args.section_thickness):
            raise BadInput(f"--section-thickness must be 0 (cut spheres) or a positive length in metres")
        labels = [os.path.basename(os.path.normpath(r)) for r in args.runs]
        if args.labels is not None:
            labels = [l.strip() for l in args.labels.split(",")]
            if len(labels) != len(args.runs):
                raise BadInput(f"--labels gives {len(labels)} labels for {len(args.runs)} runs")
        runs = [Run(d, l) for d, l in zip(args.runs, labels)]
        if not any(r.series is not None or r.others or r.profiles for r in runs) and not args.section:
            raise BadInput("no time_series.csv or other CSV in " + ", ".join(f"'{r}'" for r in args.runs))
        out_dir = args.out or os.path.join(args.runs[0], "plots")
        os.makedirs(out_dir, exist_ok=True)
        written, missing = [], []
        for plot in (plot_temperature, plot_wall_temperatures, plot_energy_balance, plot_wall_forces,
                     plot_mechanics):
            reason = plot(runs, out_dir, written)
            if reason:
                missing.append(reason)
        plot_other_csvs(runs, out_dir, written)
        plot_profiles(runs, out_dir, written)
        if args.section:
            for run in runs:
                name = "section.png" if len(runs) == 1 else f"section_{re.sub(r'[^A-Za-z0-9_.-]', '_', run.label)}.png"
                plot_section(run, args, out_dir, written, name)
    except BadInput as error:
        print(f"regodem plot: error: {error}", file=sys.stderr)
        return 2
    except Exception as error:  # a fault of this script: one line that says where, not a traceback
        frame = traceback.extract_tb(error.__traceback__)[-1]
        print(f"regodem plot: error: unexpected {type(error).__name__} at {frame.filename}:{frame.lineno} "
              f"({frame.name}): {error}; please report it with the run's files", file=sys.stderr)
        return 1
    for path in written:
        print(path)
    sys.stdout.flush()  # the paths, then the lines on stderr, in that order on a terminal
    if missing:
        print("not drawn: " + "; ".join(missing), file=sys.stderr)
    scales = sorted({round(r.series.time_scale(), 9) for r in runs if r.series is not None} - {1.0})
    if scales:
        print("regodem plot: note: time axes in real time: the simulated time x heat.time_scale_factor S = "
              + ", ".join(f"{x:.4g}" for x in scales), file=sys.stderr)
    snapshots = [os.path.join(r.directory, "particles.pvd") for r in runs
                 if os.path.isfile(os.path.join(r.directory, "particles.pvd"))]
    print(f"regodem plot: {len(written)} figure{'' if len(written) == 1 else 's'} in "
          f"{os.path.join(out_dir, '')}" + (f"; for ParaView: {', '.join(snapshots)}" if snapshots else ""),
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
