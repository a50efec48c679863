#!/usr/bin/env python3
"""The paper's sieve calibration (Zhao et al. 2023, Sections 3-4, Tables 3-4, Eq. 6-7)
driven from Python: what `regodem calibrate scenarios/paper/matching-cell-calibration.yaml`
does, step by step, on numpy arrays.

1. the beds: the sieve cell's and W0's (no sieve), poured and settled;
2. W0 heated until T_in reaches 446.8 K: its heating time and its T_in, T_d are the targets;
3. the paper's central composite design over the sieve's specific heat C_wall
   (1200 +- 600 J/(kg K)) and conductivity lambda_wall (300 +- 200 W/(m K)), rotatable,
   3 centre points: 11 sieve runs heated for W0's time, each giving T_in and T_d;
4. quadratic surfaces (T_in without C_wall^2 and the interaction, as the paper fits it);
5. solved the paper's way: T_d for lambda_wall at C_wall = 1200, then T_in for C_wall.

    PYTHONPATH=build/release/python python3 examples/python/matching_cell_ccd.py [--cell tiny|paper] [-o DIR]

--cell tiny (the default) uses the 6 mm cell of scenarios/paper/tiny/ (seconds; for the
tests, not for results); --cell paper the paper's cell (hours on two cores).
"""
import argparse
import json
import os
import sys

import numpy as np

import regodem

HERE = os.path.dirname(os.path.abspath(__file__))
PAPER = os.path.join(HERE, "..", "..", "scenarios", "paper")


def summary_of(directory):
    with open(os.path.join(directory, "summary.json")) as f:
        return json.load(f)


def band_final(summary, band):
    return summary["measurements"]["bands"][band]["final"]


def run_to_end(scenario, directory, threads):
    with regodem.Run(scenario, output=directory, overwrite=True, threads=threads, quiet=True) as run:
        run.run()
    return summary_of(directory)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--cell", choices=["tiny", "paper"], default="tiny")
    parser.add_argument("-o", "--output", default="out/matching-cell-ccd")
    parser.add_argument("--threads", type=int, default=None)
    args = parser.parse_args()
    folder = os.path.join(PAPER, "tiny") if args.cell == "tiny" else PAPER
    out = os.path.abspath(args.output)

    # 1-2. The beds, and W0 to its target.
    bed, w0_bed = os.path.join(out, "bed"), os.path.join(out, "w0-bed")
    run_to_end(regodem.Scenario(os.path.join(folder, "matching-cell-bed.yaml")), bed, args.threads)
    w0_bed_file = os.path.join(folder, "matching-cell-w0-bed.yaml")
    if os.path.exists(w0_bed_file):
        run_to_end(regodem.Scenario(w0_bed_file), w0_bed, args.threads)
    else:  # the tiny cell's W0 starts from the sieve cell's bed
        w0_bed = bed
    w0 = run_to_end(regodem.Scenario(os.path.join(folder, "matching-cell-w0.yaml"))
                    .set("initial_state.checkpoint", w0_bed), os.path.join(out, "w0"), args.threads)
    heating_s = next(s["duration_s"] for s in w0["stages"] if s["name"] == "heat")
    target = band_final(w0, "sieve_plane")
    print(f"W0: heated {heating_s:.4g} s; T_in = {target['T_in_K']:.2f} K, T_d = {target['T_d_K']:.2f} K",
          file=sys.stderr)

    # 3. The design and its runs.
    design = regodem.ccd({"C_wall": (1200.0, 600.0, "J/(kg K)"), "lambda_wall": (300.0, 200.0, "W/(m K)")},
                         alpha="rotatable", centre_points=3)
    responses = []
    for k, (c_wall, lambda_wall) in enumerate(design["actual"], start=1):
        scenario = (regodem.Scenario(os.path.join(folder, "matching-cell.yaml"))
                    .set("initial_state.checkpoint", bed)
                    .set("stages.heat.duration", f"{heating_s!r} s")
                    .set("walls.sieve.thermal.specific_heat", f"{c_wall!r} J/(kg K)")
                    .set("walls.sieve.thermal.conductivity", f"{lambda_wall!r} W/(m K)"))
        final = band_final(run_to_end(scenario, os.path.join(out, f"point_{k:02d}"), args.threads), "sieve")
        responses.append((final["T_in_K"], final["T_d_K"]))
        print(f"point {k:2d}: C_wall {c_wall:7.1f}, lambda_wall {lambda_wall:6.1f} -> "
              f"T_in {final['T_in_K']:.2f} K, T_d {final['T_d_K']:.2f} K", file=sys.stderr)
    t_in, t_d = np.array(responses).T

    # 4. The surfaces.
    factors = design["factors"]
    fit_d = regodem.fit(design["actual"], t_d, factors, response="T_d")
    fit_in = regodem.fit(design["actual"], t_in, factors, terms="C_wall,lambda_wall,lambda_wall^2", response="T_in")
    for fit in (fit_d, fit_in):
        print(f"{fit.equation(5)}   (R^2 {fit.r_squared:.4f}, adjusted {fit.adjusted_r_squared:.4f}, "
              f"predicted {fit.predicted_r_squared:.4f})")

    # 5. The paper's sequential solve.
    roots = fit_d.solve_for(target["T_d_K"], "lambda_wall", [1200.0, 0.0])
    if not roots:
        print(f"T_d = {target['T_d_K']:.2f} K is out of the surface's reach at C_wall = 1200: no calibration "
              "(as docs/calibration.md reports for the corrected model)")
        return
    for lambda_wall in roots:
        c_roots = fit_in.solve_for(target["T_in_K"], "C_wall", [0.0, lambda_wall])
        for c_wall in c_roots:
            print(f"solution: lambda_wall = {lambda_wall:.1f} W/(m K), C_wall = {c_wall:.1f} J/(kg K)")
        if not c_roots:
            print(f"lambda_wall = {lambda_wall:.1f} W/(m K): T_in = {target['T_in_K']:.2f} K has no C_wall")


if __name__ == "__main__":
    main()
