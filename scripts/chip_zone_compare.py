#!/usr/bin/python3
"""Chip-removal zone temperature of drilling runs compared: a table and a figure.

    scripts/chip_zone_compare.py REFERENCE_OUTDIR OUTDIR... [--labels A,B,...]
                                 [--depth 50mm] [--window 2mm] [--region chip_zone]
                                 [--plot FILE.png] [--title TEXT]

Reads regions/REGION.csv of each run (written with `every_depth`, the Fig. 14 series of
Zhao et al. 2023) and prints a Markdown table: at 20, 40, 60, 80 and 100 % of the depth,
each run's mean chip-zone temperature (degC) and its difference from the first run, the
reference (K). A value is the mean of the samples within +-window of that depth (the zone
holds a few dozen grains, so one sample is noisy); below the table, the spread (max - min)
over the runs other than the reference at each of those depths. With --plot, also a
figure of every run's chip-zone mean temperature against depth (as the paper's Fig. 14),
drawn with Debian's python3-matplotlib.
"""
import csv
import math
import os
import sys


def parse_length_m(text):
    text = text.strip()
    for unit, factor in (("mm", 1e-3), ("cm", 1e-2), ("m", 1.0)):
        if text.endswith(unit):
            return float(text[: -len(unit)]) * factor
    return float(text)


def read_series(outdir, region):
    path = os.path.join(outdir, "regions", region + ".csv")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or "depth [m]" not in rows[0]:
        sys.exit(f"{path}: no 'depth [m]' column (sample the region with every_depth)")
    series = []
    for row in rows:
        value = float(row["temperature_mean [K]"])
        if not math.isnan(value):
            series.append((float(row["depth [m]"]), value, int(row["count [-]"])))
    return series


def mean_near(series, depth_m, window_m):
    values = [t for d, t, _ in series if abs(d - depth_m) <= window_m + 1e-12]
    return sum(values) / len(values) if values else float("nan")


def main(argv):
    args, labels, depth_m, window_m, region, plot, title = [], None, 0.05, 0.002, "chip_zone", None, None
    i = 0
    while i < len(argv):
        if argv[i] in ("--labels", "--depth", "--window", "--region", "--plot", "--title"):
            if i + 1 >= len(argv):
                sys.exit(f"{argv[i]} needs a value")
            key, value = argv[i], argv[i + 1]
            if key == "--labels":
                labels = value.split(",")
            elif key == "--depth":
                depth_m = parse_length_m(value)
            elif key == "--window":
                window_m = parse_length_m(value)
            elif key == "--plot":
                plot = value
            elif key == "--title":
                title = value
            else:
                region = value
            i += 2
        else:
            args.append(argv[i])
            i += 1
    if len(args) < 2:
        sys.exit(__doc__)
    labels = labels or [os.path.basename(os.path.normpath(a)) for a in args]
    if len(labels) != len(args):
        sys.exit("--labels: one per OUTDIR")
    series = [read_series(a, region) for a in args]
    print(f"| depth | " + " | ".join(f"{l} [°C]" for l in labels) + " | "
          + " | ".join(f"{l} − {labels[0]} [K]" for l in labels[1:]) + " |")
    print("|---" * (2 * len(labels)) + "|")
    for percent in (20, 40, 60, 80, 100):
        d = depth_m * percent / 100.0
        values = [mean_near(s, d, window_m) for s in series]
        cells = [f"{v - 273.15:.1f}" for v in values] + [f"{v - values[0]:+.1f}" for v in values[1:]]
        print(f"| {percent} % ({d * 1e3:.0f} mm) | " + " | ".join(cells) + " |")
    if len(series) > 2:
        spreads = []
        for percent in (20, 40, 60, 80, 100):
            others = [mean_near(s, depth_m * percent / 100.0, window_m) for s in series[1:]]
            spreads.append(f"{percent} %: {max(others) - min(others):.1f} K")
        print(f"\nSpread (max - min) over {', '.join(labels[1:])}: " + ", ".join(spreads))
    if plot:
        draw(series, labels, plot, title or f"{region}: mean temperature against drilling depth")


def draw(series, labels, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(8, 5), dpi=120)
    for s, label in zip(series, labels):
        ax.plot([d * 1e3 for d, _, _ in s], [t - 273.15 for _, t, _ in s], label=label, lw=1.5)
    ax.set_xlabel("drilling depth [mm]")
    ax.set_ylabel("chip-removal zone mean temperature [°C]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)
    print(f"wrote {path}")


if __name__ == "__main__":
    main(sys.argv[1:])
