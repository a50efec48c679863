#!/usr/bin/env python3
"""A parameter sweep of the demo (scenarios/demo.yaml) from Python: the thermal sieve's
conductivity at three values, each a full run into its own directory, and at the end of
each the sieve segments' temperatures and the grains' mean temperature, side by side.

    PYTHONPATH=build/release/python python3 examples/python/demo_sweep.py [--quick] [-o out/demo-sweep]

--quick: 300 fine and 20 coarse grains and 2 s of heating instead of 1,500, 60 and 30 s
(seconds a run instead of a minute; for the tests, not for results).
"""
import argparse
import os
import sys

import numpy as np

import regodem

HERE = os.path.dirname(os.path.abspath(__file__))
DEMO = os.path.join(HERE, "..", "..", "scenarios", "demo.yaml")
CONDUCTIVITIES_W_PER_MK = [50.0, 144.0, 400.0]  # 144: the paper's calibrated sieve


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("-o", "--output", default="out/demo-sweep")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--threads", type=int, default=None)
    args = parser.parse_args()

    rows = []
    for conductivity in CONDUCTIVITIES_W_PER_MK:
        scenario = regodem.Scenario(DEMO).set("walls.sieve.thermal.conductivity", f"{conductivity} W/(m K)")
        if args.quick:
            scenario.set("insertions.fine.count", 300).set("insertions.coarse.count", 20)
            scenario.set("stages.heat.duration", "2 s")
        directory = os.path.join(args.output, f"sieve_{conductivity:g}")
        with regodem.Run(scenario, output=directory, overwrite=True, threads=args.threads, quiet=True) as run:
            run.run()
            sieve = [w for w in run.walls() if w["name"].startswith("sieve")]
            grains = run.particles()
            rows.append((conductivity, [w["temperature_K"] for w in sieve], float(np.mean(grains["temperature_K"])),
                         run.time_s))
        print(f"sieve at {conductivity:g} W/(m K): done ({directory})", file=sys.stderr)

    print("lambda_sieve [W/(m K)]  mean grain T [K]  sieve segment T [K], bottom to top   t [s]")
    for conductivity, segments, mean_T, t in rows:
        print(f"{conductivity:22g}  {mean_T:16.2f}  {'  '.join(f'{T:6.1f}' for T in segments)}   {t:.3f}")


if __name__ == "__main__":
    main()
