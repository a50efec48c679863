#!/usr/bin/python3
"""PNG figures from RegoDEM runs: `regodem plot` runs this script.

    regodem_plot.py OUTDIR [OUTDIR...] [--labels A,B,...] [--out DIR]
                    [--section] [--section-axis z] [--section-through X,Y,Z]
                    [--section-thickness M]

Reads each run's time_series.csv (header "name [unit]") and any other CSV with such a
header in the run's folder and in regions/ (region and band series), each profile in
profiles/ as one line per instant, and writes figures of
FIG_WIDTH x FIG_HEIGHT pixels into DIR (default: the first OUTDIR's plots/ folder).
Several runs are overlaid, one colour per run, labelled by --labels or their folder
names. A figure whose columns no run has is left out, and the message says so.
--section draws the particle temperature on a plane through an axis from each run's
latest snapshot (particles.pvd), walls cut by the plane as lines.

Exit status: 0 figures written; 2 bad input (no such run, no data, a bad option);
3 matplotlib or numpy is missing.
"""
import argparse
import csv
import math
import os
import re
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

try:
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")  # files only, no display
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection, LineCollection
except ImportError as error:
    print(f"regodem plot: error: {error}: plotting needs matplotlib and numpy for {sys.executable} "
          "(Debian: apt-get install python3-matplotlib, as scripts/setup-debian.sh does)", file=sys.stderr)
    sys.exit(3)

FIG_WIDTH, FIG_HEIGHT, DPI = 960, 600, 120  # pixels; documented in docs/outputs.md
HEADER = re.compile(r"^(.*?)\s*\[(.*)\]$")


class BadInput(Exception):
    pass


# ---------------------------------------------------------------------------------
# Reading runs


class Series:
    """One CSV: columns by name, each with its unit."""

    def __init__(self, path):
        self.path = path
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
        if not rows:
            raise BadInput(f"{path}: empty file")
        self.names, self.units = [], {}
        for field in rows[0]:
            match = HEADER.match(field.strip())
            name, unit = (match.group(1), match.group(2)) if match else (field.strip(), "")
            self.names.append(name)
            self.units[name] = unit
        width = len(self.names)
        data = []
        for row in rows[1:]:
            if len(row) != width:
                continue  # a row being written while we read (a run in progress)
            try:
                data.append([float(v) if v not in ("", "nan") else math.nan for v in row])
            except ValueError:
                continue
        self.data = np.array(data, dtype=float).reshape(-1, width)

    def has(self, name):
        return name in self.units

    def column(self, name):
        return self.data[:, self.names.index(name)]

    def label(self, name, quantity=None):
        unit = self.units.get(name, "")
        text = quantity or name.replace("_", " ")
        return f"{text} [{unit}]" if unit and unit != "-" else text


class Run:
    def __init__(self, directory, label):
        self.directory = directory
        self.label = label
        if not os.path.isdir(directory):
            raise BadInput(f"'{directory}' is not a directory (give the OUTDIR of a `regodem run`)")
        path = os.path.join(directory, "time_series.csv")
        self.series = Series(path) if os.path.isfile(path) else None
        self.others = {}
        for name in sorted(os.listdir(directory)):
            if name.endswith(".csv") and name != "time_series.csv":
                try:
                    self.others[name] = Series(os.path.join(directory, name))
                except (BadInput, OSError, csv.Error) as error:
                    print(f"regodem plot: skipping {os.path.join(directory, name)}: {error}", file=sys.stderr)
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


def mark_stages(ax, series):
    """Light vertical lines where a stage begins."""
    if not series.has("stage") or len(series.data) < 2:
        return
    stage, time = series.column("stage"), series.column("time")
    for k in np.nonzero(np.diff(stage))[0]:
        ax.axvline(time[k + 1], color="0.85", linewidth=0.8, zorder=0)


def runs_with(runs, *names):
    return [r for r in runs if r.series is not None and all(r.series.has(n) for n in names) and len(r.series.data)]


def plot_temperature(runs, out_dir, written):
    have = runs_with(runs, "time", "temperature_mean", "temperature_min", "temperature_max")
    if not have:
        return "particle temperature (no run has heat on)"
    fig, (ax,) = new_figure()
    for run, colour in zip(have, colours(len(runs))):
        s = run.series
        t = s.column("time")
        ax.plot(t, s.column("temperature_mean"), color=colour, label=f"{run.label}: mean")
        ax.fill_between(t, s.column("temperature_min"), s.column("temperature_max"), color=colour, alpha=0.15,
                        label=f"{run.label}: min to max")
        mark_stages(ax, s)
    s = have[0].series
    ax.set_xlabel(s.label("time"))
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
    for r, (run, colour) in enumerate(zip(runs, colours(len(runs)))):
        s = run.series
        if s is None or not s.has("time") or not len(s.data):
            continue
        walls = [n for n in s.names if n.endswith(".temperature")]
        for k, name in enumerate(walls):
            ax.plot(s.column("time"), s.column(name), color=colour if len(runs) > 1 else None,
                    linestyle=styles[k % len(styles)] if len(runs) > 1 else "-",
                    label=f"{run.label}: {name[: -len('.temperature')]}" if len(runs) > 1 else name[: -len(".temperature")])
            any_line = True
            unit_source = s
            unit_name = name
    if not any_line:
        plt.close(fig)
        return "wall temperatures (no fixed or lumped wall)"
    ax.set_xlabel("time [s]")
    ax.set_ylabel(unit_source.label(unit_name, "wall temperature"))
    ax.set_title("Wall temperatures")
    ax.legend(fontsize="x-small", ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "wall_temperatures.png", written)


def plot_energy_balance(runs, out_dir, written):
    have = runs_with(runs, "time", "thermal_energy", "boundary_heat_in", "friction_heat", "energy_imbalance")
    if not have:
        return "energy balance (no run has heat on)"
    fig, (top, bottom) = new_figure(2)
    for run, colour in zip(have, colours(len(runs))):
        s = run.series
        t = s.column("time")
        energy = s.column("thermal_energy")
        top.plot(t, energy - energy[0], color=colour, label=f"{run.label}: change of thermal energy")
        top.plot(t, s.column("boundary_heat_in") + s.column("friction_heat"), color=colour, linestyle="--",
                 label=f"{run.label}: heat in (fixed walls + friction)")
        bottom.plot(t, s.column("energy_imbalance"), color=colour, label=run.label)
        mark_stages(top, s)
        mark_stages(bottom, s)
    s = have[0].series
    top.set_ylabel(s.label("thermal_energy", "energy"))
    top.set_title("Energy balance")
    top.legend(fontsize="x-small")
    bottom.set_ylabel("relative imbalance [-]")
    bottom.set_xlabel(s.label("time"))
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "energy_balance.png", written)


def plot_wall_forces(runs, out_dir, written):
    fig, (top, bottom) = new_figure(2)
    any_line = False
    for run, colour in zip(runs, colours(len(runs))):
        s = run.series
        if s is None or not s.has("time") or not len(s.data):
            continue
        t = s.column("time")
        walls = [n[: -len(".force_x")] for n in s.names if n.endswith(".force_x")]
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
    bottom.set_xlabel("time [s]")
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
    for run, colour in zip(have, colours(len(runs))):
        s = run.series
        t = s.column("time")
        kinetic = s.column("kinetic_energy")
        top.plot(t, np.where(kinetic > 0, kinetic, np.nan), color=colour, label=run.label)
        bottom.plot(t, s.column("coordination_number"), color=colour, label=run.label)
        mark_stages(top, s)
    s = have[0].series
    if np.any(np.concatenate([r.series.column("kinetic_energy") for r in have]) > 0):
        top.set_yscale("log")
    top.set_ylabel(s.label("kinetic_energy", "kinetic energy"))
    bottom.set_ylabel(s.label("coordination_number", "coordination number"))
    bottom.set_xlabel(s.label("time"))
    top.set_title("Kinetic energy and coordination number")
    top.legend(fontsize="small")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out_dir, "mechanics.png", written)


def plot_other_csvs(runs, out_dir, written):
    """Profiles and region series: every further CSV, its columns against its first."""
    names = sorted({name for run in runs for name in run.others})
    for name in names:
        fig, (ax,) = new_figure()
        any_line = False
        for run, colour in zip(runs, colours(len(runs))):
            s = run.others.get(name)
            if s is None or len(s.names) < 2 or not len(s.data):
                continue
            x = s.names[0]
            for k, y in enumerate(s.names[1:]):
                ax.plot(s.column(x), s.column(y), color=colour if len(runs) > 1 else None,
                        linestyle=["-", "--", ":", "-."][k % 4] if len(runs) > 1 else "-",
                        label=f"{run.label}: {y}" if len(runs) > 1 else y)
                any_line = True
            ax.set_xlabel(s.label(x))
            units = {s.units[y] for y in s.names[1:]}
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
            key = "depth" if s.has("depth") else "time"
            instants = list(dict.fromkeys(s.column("time")))
            for k, t in enumerate(instants):
                rows = s.column("time") == t
                tag = f"{key} {s.column(key)[rows][0]:.4g} {s.units[key]}"
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


def plot_section(run, args, out_dir, written, name):
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
    fig, (ax,) = new_figure()
    if "temperature" in particles:
        values, label, cmap = particles["temperature"][cut], "temperature [K]", "turbo"
    else:
        values, label, cmap = particles["region"][cut].astype(float), "region (heat is off)", "tab10"
    offsets = np.column_stack([points[cut, across], points[cut, axis]])
    disks = EllipseCollection(2 * shown_r, 2 * shown_r, np.zeros_like(shown_r), units="xy", offsets=offsets,
                              transOffset=ax.transData, cmap=cmap, linewidths=0)
    disks.set_array(values)
    ax.add_collection(disks)
    if len(values):
        fig.colorbar(disks, ax=ax, label=label)
    _, wall_path = latest_snapshot(run, "walls.pvd")
    extent = [offsets - shown_r[:, None], offsets + shown_r[:, None]] if len(offsets) else []
    if wall_path:
        segments = draw_wall_cuts(ax, read_vtp(wall_path), normal, through[normal], across, axis)
        if len(segments):
            extent.append(segments.reshape(-1, 2))
    if extent:  # the particles and the walls they sit in
        corners = np.concatenate(extent)
        low, high = corners.min(axis=0), corners.max(axis=0)
        pad = 0.03 * max(high - low)
        ax.set_xlim(low[0] - pad, high[0] + pad)
        ax.set_ylim(low[1] - pad, high[1] + pad)
    ax.set_aspect("equal")
    names = "xyz"
    ax.set_xlabel(f"{names[across]} [m]")
    ax.set_ylabel(f"{names[axis]} [m]")
    where = f"{names[normal]} = {through[normal]:g} m"
    ax.set_title(f"{run.label}: section through the {names[axis]} axis ({where}), t = {time:.6g} s, "
                 f"{int(cut.sum())} particles")
    fig.tight_layout()
    save(fig, out_dir, name, written)


def draw_wall_cuts(ax, walls, normal, level, across, axis):
    """The lines where the plane cuts the wall triangles."""
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
    if segments:
        ax.add_collection(LineCollection(segments, colors="0.2", linewidths=1.0))
    return np.array(segments, dtype=float)


# ---------------------------------------------------------------------------------


def parse_point(text):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3:
        raise BadInput(f"--section-through takes three numbers in metres, e.g. 0,0,0; got '{text}'")
    return values


def main(argv):
    parser = argparse.ArgumentParser(prog="regodem plot", description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", metavar="OUTDIR")
    parser.add_argument("--labels", help="comma-separated, one per OUTDIR")
    parser.add_argument("--out", help="folder for the PNG files (default: FIRST_OUTDIR/plots)")
    parser.add_argument("--section", action="store_true")
    parser.add_argument("--section-axis", choices=["x", "y", "z"], default="z")
    parser.add_argument("--section-through", default="0,0,0")
    parser.add_argument("--section-thickness", type=float, default=0.0)
    args = parser.parse_args(argv)
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
    for path in written:
        print(path)
    if missing:
        print("not drawn: " + "; ".join(missing), file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
