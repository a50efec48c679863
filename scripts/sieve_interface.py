#!/usr/bin/env python3
"""How a bed meets a plane: the matching cell's sieve disk, or W0's plane where the disk
would be (docs/paper-scenarios.md, "The beds").

    scripts/sieve_interface.py SCENARIO BED HEIGHT_MM

SCENARIO is a heat run's file (matching-cell.yaml, matching-cell-w0.yaml) whose
`initial_state.checkpoint` is replaced by BED (a run's output directory); HEIGHT_MM is
the disk's (or the plane's) distance from the plate. Printed, on each side of the plane:
the grains centred within 2 mm of it (the paper's bands, Eq. 3-5) and the grains whose
sphere reaches across it (for a disk: the grains touching it); the particle pairs that
overlap across the plane (W0's contacts through it; across a disk such pairs are kept out
of the neighbour lists, src/geometry/wall_primitive.hpp, and do not touch); and the same
two counts at the plate, the floor the bed was poured on, for comparison. Geometry only: a grain touches
when its sphere overlaps the plane, a pair when the spheres overlap.

Needs the Python module (build/release/python on PYTHONPATH, or installed).
"""
import os
import sys
import tempfile

import numpy as np

import regodem


def load_particles(scenario, bed):
    scenario = regodem.Scenario(scenario, set=[f"initial_state.checkpoint={os.path.abspath(bed)}"])
    with tempfile.TemporaryDirectory() as output:
        with regodem.Run(scenario, output=output, overwrite=True, quiet=True, threads=1) as run:
            return run.particles()


def pairs_across(position, radius, height):
    """Pairs in contact whose centres lie on either side of the plane z = height."""
    near = np.abs(position[:, 2] - height) < 2.0 * radius.max()
    p, r = position[near], radius[near]
    below, above = np.where(p[:, 2] < height)[0], np.where(p[:, 2] >= height)[0]
    count = 0
    for i in below:
        gap = np.linalg.norm(p[above] - p[i], axis=1) - (r[above] + r[i])
        count += int((gap < 0.0).sum())
    return count


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__)
    particles = load_particles(argv[1], argv[2])
    height = float(argv[3]) * 1e-3
    z, r = particles["position_m"][:, 2], particles["radius_m"]
    band = 2e-3
    below = z < height
    print(f"plane {height * 1e3:g} mm from the plate, {len(z)} particles")
    print(f"  below: {int((below & (z >= height - band)).sum())} grains within 2 mm, "
          f"{int((below & (z + r > height)).sum())} reaching across")
    print(f"  above: {int((~below & (z < height + band)).sum())} grains within 2 mm, "
          f"{int((~below & (z - r < height)).sum())} reaching across")
    print(f"  pairs overlapping across it (in contact unless a disk parts them): {pairs_across(particles['position_m'], r, height)}")
    print(f"plate: {int((z < band).sum())} grains within 2 mm, {int((z - r < 0.0).sum())} touching")


if __name__ == "__main__":
    main(sys.argv)
