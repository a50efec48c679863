#!/usr/bin/python3
"""Reads a RegoDEM run's ParaView files back with VTK itself and checks them.

    check_vtk_snapshots.py OUTDIR [--expected EXPECTED.json] [--summary summary.json]

Checks that particles.pvd and walls.pvd parse, list every .vtp in OUTDIR/vtk/ once,
with times that increase; that VTK's own vtkXMLPolyDataReader reads each file without
an error, with one vertex cell per particle; and, given EXPECTED.json (what the C++
side wrote), that counts, field names and every value agree exactly. Given
summary.json, that the last snapshot holds the run's final particle count and time.
Exit status: 0 all good, 1 a check failed, 77 python3-vtk9 is not installed.
"""
import argparse
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    import numpy as np
except ImportError as error:  # the test is skipped, not failed, without VTK
    print(f"python3-vtk9 (or numpy) is not installed: {error}; apt-get install python3-vtk9")
    sys.exit(77)

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
    return condition


def read_collection(outdir, name):
    path = os.path.join(outdir, name)
    if not check(os.path.isfile(path), f"{name} is missing"):
        return []
    root = ET.parse(path).getroot()
    check(root.tag == "VTKFile" and root.get("type") == "Collection", f"{name}: not a VTK collection")
    entries = [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]
    times = [t for t, _ in entries]
    check(all(b > a for a, b in zip(times, times[1:])), f"{name}: times do not increase: {times}")
    prefix = name.split(".")[0] + "_"
    on_disk = sorted(f"vtk/{f}" for f in os.listdir(os.path.join(outdir, "vtk")) if f.startswith(prefix))
    check(sorted(f for _, f in entries) == on_disk,
          f"{name} does not list every file once: {[f for _, f in entries]} vs {on_disk}")
    return entries


class ErrorCatcher:
    def __init__(self):
        self.messages = []

    def __call__(self, caller, event):
        self.messages.append(event)


def read_polydata(path):
    reader = vtk.vtkXMLPolyDataReader()
    catcher = ErrorCatcher()
    reader.AddObserver("ErrorEvent", catcher)
    reader.GetExecutive().AddObserver("ErrorEvent", catcher)
    reader.SetFileName(path)
    reader.Update()
    check(not catcher.messages and reader.GetErrorCode() == 0, f"{path}: VTK reported an error")
    return reader.GetOutput()


def array_names(data):
    return sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))


def strings(field, name):
    array = field.GetAbstractArray(name)
    if array is None:
        return None
    return [array.GetValue(i) for i in range(array.GetNumberOfValues())]


def field_value(polydata, name):
    array = polydata.GetFieldData().GetArray(name)
    return None if array is None else array.GetValue(0)


def as_float(values):
    return np.array([math.nan if v is None else v for v in values], dtype=float)


def check_particles(outdir, entries, expected):
    if expected is not None:
        check(len(entries) == len(expected), f"particles.pvd lists {len(entries)} snapshots, the run wrote {len(expected)}")
    last = None
    for k, (time, file) in enumerate(entries):
        path = os.path.join(outdir, file)
        data = read_polydata(path)
        n = data.GetNumberOfPoints()
        check(data.GetNumberOfVerts() == n, f"{file}: {data.GetNumberOfVerts()} vertex cells for {n} points")
        check(field_value(data, "TimeValue") == time, f"{file}: TimeValue {field_value(data, 'TimeValue')} != pvd {time}")
        last = (time, n)
        if expected is None or k >= len(expected):
            continue
        e = expected[k]
        check(time == e["time"], f"{file}: time {time} != {e['time']}")
        check(n == e["count"], f"{file}: {n} points, expected {e['count']}")
        names = sorted(e["fields"].keys() if e["fields"]["temperature"] else
                       [f for f in e["fields"] if f != "temperature"])
        got = array_names(data.GetPointData())
        check(got == names, f"{file}: point data {got}, expected {names}")
        check("intact_bonds" not in got, f"{file}: intact_bonds written without bonds")
        if n > 0:
            points = vtk_to_numpy(data.GetPoints().GetData())
            check(np.array_equal(points, np.array(e["points"], dtype=float)), f"{file}: positions differ")
        for name, values in e["fields"].items():
            if not values or n == 0:
                continue
            array = data.GetPointData().GetArray(name)
            if not check(array is not None, f"{file}: no '{name}'"):
                continue
            got_values = vtk_to_numpy(array)
            want = np.array(values, dtype=got_values.dtype)
            check(np.array_equal(got_values, want), f"{file}: '{name}' differs from what the simulation had")
        check(strings(data.GetFieldData(), "material_names") == e["material_names"], f"{file}: material_names")
        check(strings(data.GetFieldData(), "region_names") == e["region_names"], f"{file}: region_names")
        check(data.GetPointData().GetArray("velocity").GetNumberOfComponents() == 3, f"{file}: velocity not 3-vector")
    return last


def check_walls(outdir, entries, expected):
    if expected is not None:
        check(len(entries) == len(expected), f"walls.pvd lists {len(entries)} snapshots, the run wrote {len(expected)}")
    for k, (time, file) in enumerate(entries):
        data = read_polydata(os.path.join(outdir, file))
        cells = data.GetNumberOfCells()
        check(cells == data.GetNumberOfPolys() and cells > 0, f"{file}: {cells} cells, {data.GetNumberOfPolys()} triangles")
        check(field_value(data, "TimeValue") == time, f"{file}: TimeValue differs from the pvd's")
        if expected is None or k >= len(expected):
            continue
        e = expected[k]
        check(cells == e["triangles"], f"{file}: {cells} triangles, expected {e['triangles']}")
        with_heat = bool(e["body_temperature"])
        names = sorted(["wall", "force"] + (["temperature", "thermal_mode"] if with_heat else []))
        check(array_names(data.GetCellData()) == names, f"{file}: cell data {array_names(data.GetCellData())}")
        check(strings(data.GetFieldData(), "wall_names") == e["wall_names"], f"{file}: wall_names")
        bodies = vtk_to_numpy(data.GetCellData().GetArray("wall"))
        check(np.array_equal(bodies, np.array(e["body_of_triangle"])), f"{file}: wall index per triangle")
        if with_heat:
            temperature = vtk_to_numpy(data.GetCellData().GetArray("temperature"))
            want = as_float(e["body_temperature"])[bodies]
            check(np.array_equal(temperature, want, equal_nan=True), f"{file}: wall temperatures differ")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("outdir")
    parser.add_argument("--expected")
    parser.add_argument("--summary")
    args = parser.parse_args()
    expected = json.load(open(args.expected)) if args.expected else None
    particles = read_collection(args.outdir, "particles.pvd")
    walls = read_collection(args.outdir, "walls.pvd")
    check(len(particles) >= 2, f"only {len(particles)} particle snapshots")
    last = check_particles(args.outdir, particles, expected["particles"] if expected else None)
    check_walls(args.outdir, walls, expected["walls"] if expected else None)
    if args.summary and last is not None:
        summary = json.load(open(args.summary))
        check(last[1] == summary["particles"], f"last snapshot has {last[1]} particles, the run ended with {summary['particles']}")
        check(last[0] == summary["simulated_time_s"], f"last snapshot at {last[0]} s, the run ended at {summary['simulated_time_s']} s")
    if failures:
        print("\n".join(failures))
        return 1
    print(f"ok: {len(particles)} particle and {len(walls)} wall snapshots read back with VTK {vtk.vtkVersion.GetVTKVersion()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
