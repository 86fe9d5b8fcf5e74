#!/usr/bin/env bash
# The spinning cube through the estep command: energy-stepping conserves the terraced energy
# and the three angular-momentum components to 1e-11 relative over a short run, with the
# seed's mesh counts and initial kinetic energy; explicit Newmark at dt = 0.0381 is reported
# unstable (status, message, exit code 2) and at dt = 0.0082 its energy drift is reported; the
# second material (chosen by name) conserves the same way; field output writes the end time too.
set -u
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
prm="$ESTEP_SOURCE_DIR/parameter_files/spinning_cube.prm"
failures=0

"$ESTEP" "$prm" -s "Output directory=es" -s "Time integration/End time=4" \
  -s "Postprocessors/List=history, step histogram, progress, field output" -s "Postprocessors/Field output/Interval=2" > es.log 2>&1 || { cat es.log; failures=$((failures + 1)); }
"$ESTEP" "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube_newmark_0.0381.prm" \
  -s "Output directory=unstable" -s "Time integration/End time=250" > unstable.log 2>&1
rc=$?
[[ $rc == 2 ]] || { echo "Newmark at dt = 0.0381: exit code $rc, expected 2"; failures=$((failures + 1)); }
"$ESTEP" "$ESTEP_SOURCE_DIR/parameter_files/spinning_cube_newmark_0.0082.prm" \
  -s "Output directory=stable" -s "Time integration/End time=4" > stable.log 2>&1 ||
  { cat stable.log; failures=$((failures + 1)); }

# The second material by name: the same cube, neo-Hookean with a quadratic volumetric term.
"$ESTEP" "$prm" -s "Output directory=quadratic" -s "Time integration/End time=4" \
  -s "Material/Model=neo-Hookean quadratic volume" -s "Postprocessors/List=history" \
  > quadratic.log 2>&1 || { cat quadratic.log; failures=$((failures + 1)); }

# Field output in HDF5/XDMF, the same run as es/: every snapshot in the series, the same
# mesh and values as the vtu files (checked in the Python below).
"$ESTEP" "$prm" -s "Output directory=h5" -s "Time integration/End time=4" \
  -s "Postprocessors/List=history, field output" -s "Postprocessors/Field output/Interval=2" \
  -s "Postprocessors/Field output/Format=hdf5" > h5.log 2>&1 || { cat h5.log; failures=$((failures + 1)); }
[[ $(grep -c "Time Value" h5/solution.xdmf) == 3 ]] || { echo "solution.xdmf does not list 3 times"; failures=$((failures + 1)); }

# A snapshot at the end time, off the grid (1.2 with an interval of 0.5), or within round-off of
# it (0.3 = 3 x 0.1, none twice); a resumed run to a later end time goes on along the grid.
times() { grep -o 'timestep="[^"]*"' "$1/solution.pvd" | sed 's/timestep="\(.*\)"/\1/' | tr '\n' ' '; }
small=(-s "Elastic body/Mesh/Subdivisions=2" -s "Postprocessors/List=field output")
"$ESTEP" "$prm" "${small[@]}" -s "Output directory=end" -s "Time integration/End time=1.2" \
  -s "Postprocessors/Field output/Interval=0.5" > end.log 2>&1 || { cat end.log; failures=$((failures + 1)); }
[[ $(times end) == "0 0.5 1 1.2 " ]] || { echo "snapshots at $(times end), expected 0 0.5 1 1.2"; failures=$((failures + 1)); }
"$ESTEP" "$prm" "${small[@]}" -s "Output directory=end" -s "Time integration/End time=2" --resume \
  -s "Postprocessors/Field output/Interval=0.5" > resumed.log 2>&1 || { cat resumed.log; failures=$((failures + 1)); }
[[ $(times end) == "0 0.5 1 1.2 1.5 2 " ]] || { echo "resumed: snapshots at $(times end), expected 0 0.5 1 1.2 1.5 2"; failures=$((failures + 1)); }
"$ESTEP" "$prm" "${small[@]}" -s "Output directory=tenths" -s "Time integration/End time=0.3" \
  -s "Postprocessors/Field output/Interval=0.1" > tenths.log 2>&1 || { cat tenths.log; failures=$((failures + 1)); }
[[ $(ls tenths/fields | wc -l) == 4 ]] || { echo "to t = 0.3 every 0.1: snapshots at $(times tenths)"; failures=$((failures + 1)); }
# Each snapshot time is start + k interval, not a running sum of intervals: to t = 1 every 0.1 the
# last is 1 itself (the sum gives 0.99999999999999989, and then a snapshot at 1 is missing).
"$ESTEP" "$prm" "${small[@]}" -s "Output directory=grid" -s "Time integration/End time=1" \
  -s "Postprocessors/Field output/Interval=0.1" > grid.log 2>&1 || { cat grid.log; failures=$((failures + 1)); }
[[ $(times grid) == *" 0.90000000000000002 1 " && $(ls grid/fields | wc -l) == 11 ]] ||
  { echo "to t = 1 every 0.1: snapshots at $(times grid)"; failures=$((failures + 1)); }
# An interval far longer than the run: the start and the end.
"$ESTEP" "$prm" "${small[@]}" -s "Output directory=long" -s "Time integration/End time=0.02" \
  -s "Postprocessors/Field output/Interval=1e300" > long.log 2>&1 || { cat long.log; failures=$((failures + 1)); }
[[ $(times long) == "0 0.02 " ]] || { echo "an interval of 1e300: snapshots at $(times long), expected 0 0.02"; failures=$((failures + 1)); }

/usr/bin/python3 - <<'PY' || failures=$((failures + 1))
import csv, json, sys
bad = []
es = json.load(open("es/summary.json"))
p = es["problem"]
if (p["cells"], p["vertices"]) != (12288, 2969):
    bad.append(f"mesh counts {p['cells']}, {p['vertices']}")
T0 = es["energies"]["initial kinetic"]
if abs(T0 - 8.43099e-3) > 5e-9:
    bad.append(f"initial kinetic energy {T0}")
Lz0 = es["initial momenta"]["angular"][2]
rows = list(csv.DictReader(open("es/history.csv")))
E0 = float(rows[0]["terraced_total_energy"])
worst_E = max(abs(float(r["terraced_total_energy"]) - E0) for r in rows) / abs(E0)
L0 = [float(rows[0][f"angular_momentum_{c}"]) for c in "xyz"]
worst_L = max(abs(float(r[f"angular_momentum_{c}"]) - L0[i]) for r in rows
              for i, c in enumerate("xyz")) / abs(Lz0)
print(f"energy-stepping: {es['counters']['steps']} steps, terraced energy drift {worst_E:.2e}, "
      f"angular momentum drift {worst_L:.2e} (relative to |Lz| = {abs(Lz0):.7g})")
if abs(abs(Lz0) - 1.686198e-2) > 5e-9:
    bad.append(f"|Lz| = {abs(Lz0)}")
if worst_E > 1e-11 or worst_L > 1e-11:
    bad.append("energy or angular momentum not conserved to 1e-11")
import os
if not os.path.exists("es/solution.pvd") or not os.path.exists("es/fields/solution-00002.vtu"):
    bad.append("no field output")
else:
    # The first snapshot decoded with the standard library (base64, zlib): vertex fields
    # on the 2,969 shared vertices, the rigid rotation's velocity w x (X - c), J = 1.
    import re, sys
    sys.path.insert(0, os.path.join(os.environ["ESTEP_SOURCE_DIR"], "tests"))
    from vtu_arrays import arrays
    text = open("es/fields/solution-00000.vtu").read()
    snapshot = arrays("es/fields/solution-00000.vtu")
    def array(name):
        return snapshot[name or "points"]
    n = re.search(r'NumberOfPoints="(\d+)" NumberOfCells="(\d+)"', text)
    X, u, v, J = array(""), array("displacement"), array("velocity"), array("J")
    conn = array("connectivity")
    if (int(n.group(1)), int(n.group(2))) != (2969, 12288) or len(conn) != 4 * 12288:
        bad.append(f"VTU mesh {n.groups()}, {len(conn)} connectivity entries")
    worst_v = max(max(abs(v[3 * i] + (X[3 * i + 1] - 0.5)), abs(v[3 * i + 1] - (X[3 * i] - 0.5)),
                      abs(v[3 * i + 2])) for i in range(2969))
    if max(map(abs, u)) > 0 or max(abs(j - 1) for j in J) > 1e-6 or worst_v > 1e-6:
        bad.append(f"VTU fields at t = 0: |u| {max(map(abs, u))}, |J - 1| "
                   f"{max(abs(j - 1) for j in J)}, velocity error {worst_v}")
    # HDF5 output of the same run: the mesh exactly, the values as in the vtu files (which
    # store them as 32-bit floats), and every data item of solution.xdmf a dataset of its size.
    import h5py, numpy, xml.etree.ElementTree as ET
    with h5py.File("h5/fields/mesh.h5") as mesh:
        if (not numpy.array_equal(mesh["body1/cells"][:].ravel(), conn) or
                numpy.abs(mesh["body1/points"][:].ravel() - X).max() > 1e-7):
            bad.append("HDF5 mesh differs from the vtu mesh")
    for k in (0, 2):
        snapshot = arrays(f"es/fields/solution-0000{k}.vtu")
        with h5py.File(f"h5/fields/solution-0000{k}.h5") as h5:
            if h5.attrs["time"] != 2.0 * k:
                bad.append(f"HDF5 snapshot {k}: time {h5.attrs['time']}")
            for name in ("displacement", "velocity", "J", "strain_energy_density",
                         "cauchy_stress", "von_mises_stress"):
                ours, theirs = h5["body1/" + name][:].ravel(), numpy.array(array(name))
                scale = max(numpy.abs(ours).max(), 1e-300)
                if ours.shape != theirs.shape or not numpy.abs(ours - theirs).max() <= 1e-6 * scale:
                    bad.append(f"HDF5 snapshot {k}: {name} differs from the vtu file")
    items = list(ET.parse("h5/solution.xdmf").getroot().iter("DataItem"))
    print(f"HDF5 output: the mesh and 6 fields of 2 snapshots as in the vtu files, "
          f"{len(items)} data items in solution.xdmf")
    for item in items:
        file, path = item.text.split(":")
        with h5py.File("h5/" + file) as h5:
            dims = tuple(int(d) for d in item.get("Dimensions").split())
            if h5[path].shape != dims:
                bad.append(f"solution.xdmf: {item.text} is {h5[path].shape}, not {dims}")
qv = json.load(open("quadratic/summary.json"))
if (qv["status"] != "completed" or qv["problem"]["material"] != "neo-Hookean quadratic volume"
        or qv["energies"]["terraced energy drift"] > 1e-11
        or qv["angular momentum drift"] > 1e-11 * abs(Lz0)):
    bad.append(f"the quadratic-volume material's run: {qv['status']}, {qv['problem']['material']}, "
               f"drifts {qv['energies']['terraced energy drift']}, {qv['angular momentum drift']}")
print(f"neo-Hookean quadratic volume: {qv['counters']['steps']} steps to t = 4, terraced energy "
      f"drift {qv['energies']['terraced energy drift']:.1e}")
un = json.load(open("unstable/summary.json"))
if un["status"] != "unstable" or "stab" not in un["message"]:
    bad.append("Newmark at dt = 0.0381 not reported unstable")
print(f"Newmark dt = 0.0381: {un['status']} at t = {un['final time']:.4g}: {un['message']}")
st = json.load(open("stable/summary.json"))
if st["status"] != "completed" or "total energy drift" not in st["energies"]:
    bad.append("Newmark at dt = 0.0082 did not complete with its energy drift")
print(f"Newmark dt = 0.0082: energy drift {st['energies']['total energy drift']:.3e} to t = 4")
print("\n".join(bad) or "all checks passed")
sys.exit(1 if bad else 0)
PY
echo "$((failures == 0 ? 1 : 0)) passed, $failures failed"
[[ $failures == 0 ]]
