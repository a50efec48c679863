#!/usr/bin/env python3
"""A drilling run's chip zone in one figure: the chip-removal zone's mean and hottest
grain temperature against the drill's depth, beside the drill's own temperature (when it
is a thermal body), from a run's output directory.

    PYTHONPATH=build/release/python python3 examples/python/chip_zone_figure.py [OUTDIR] [--png FILE]

Without OUTDIR it runs the tiny drill with its heat (scenarios/paper/tiny/drill-bed.yaml,
then drill-heat.yaml; seconds, not results) into out/chip-zone-example and draws that.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import regodem  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TINY = os.path.join(HERE, "..", "..", "scenarios", "paper", "tiny")


def run_tiny_drill(out, threads):
    bed, drill = os.path.join(out, "bed"), os.path.join(out, "drill")
    with regodem.Run(os.path.join(TINY, "drill-bed.yaml"), output=bed, overwrite=True, threads=threads,
                     quiet=True) as run:
        run.run()
    scenario = regodem.Scenario(os.path.join(TINY, "drill-heat.yaml")).set("initial_state.checkpoint", bed)
    with regodem.Run(scenario, output=drill, overwrite=True, threads=threads, quiet=True) as run:
        run.run(progress=lambda p: print(f"\r t = {p['time_s']:.3f} s", end="", file=sys.stderr))
    print(file=sys.stderr)
    return drill


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("outdir", nargs="?")
    parser.add_argument("--png", default=None, help="the figure's file (default OUTDIR/chip_zone.png)")
    parser.add_argument("--threads", type=int, default=None)
    args = parser.parse_args()
    directory = args.outdir or run_tiny_drill(os.path.abspath("out/chip-zone-example"), args.threads)

    out = regodem.read_run(directory)
    if "chip_zone" not in out.regions:
        sys.exit(f"{directory} has no chip_zone region measurement (regions/chip_zone.csv)")
    zone = out.regions["chip_zone"]
    depth_mm = zone["depth"] * 1e3 if "depth" in zone else zone["time"]
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(depth_mm, zone["temperature_mean"], label="chip zone, mean")
    ax.plot(depth_mm, zone["temperature_max"], label="chip zone, hottest grain")
    # The drill's slices when it is a thermal body (drill[1] is the tip), against its depth.
    series = out.time_series
    if "drill.depth" in series:
        drill_depth_mm = series["drill.depth"] * 1e3
        for name in series.names:
            if name.startswith("drill[") and name.endswith("].temperature"):
                ax.plot(drill_depth_mm, series[name], "--", lw=0.9, label=name)
    ax.axhline(203.15, color="grey", lw=0.8, ls=":", label="-70 °C (ice sublimation in vacuum)")
    ax.set_xlabel("drill depth [mm]" if "depth" in zone else "time [s]")
    ax.set_ylabel("temperature [K]")
    ax.legend(fontsize=8)
    ax.set_title(os.path.basename(os.path.normpath(directory)))
    png = args.png or os.path.join(directory, "chip_zone.png")
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    print(png)


if __name__ == "__main__":
    main()
