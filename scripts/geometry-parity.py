#!/usr/bin/env python3
"""Every quick-suite technique on the generated paths against the CPU path (docs/geometry.md,
"Same image"): the all-pairs form of GeometryMesh.RepresentativePairsDrawTheCpuImageOnMesa25 and
GeometryCompute, which run a few pairs in ctest. Each shadow and transparency technique of the
quick suite (suites/quick.json's axes and the techniques' own quick cases) in shadow +
transparency pairs, one render on each path:
- compute: on the system driver, GL and Vulkan, every pair; the arithmetic is the CPU path's, so
  the bound is --compute-tolerance (0: the same image to the bit);
- mesh: on Mesa 25.0.7's lavapipe (drivers/mesa-25.0; skipped with the reason where it is
  absent), Vulkan; a technique the mesh path refuses (its unit.json's mesh_refusal) is counted,
  not compared; the bound is --tolerance.
Prints each pair's difference; exit 1 when a pair differs by more than its bound at any pixel,
2 on bad input or a missing program. Minutes: scripts/nightly.sh runs it.

  scripts/geometry-parity.py [--tolerance 1e-4] [--compute-tolerance 0] [--size 24x24]
                             [--paths compute,mesh]
"""
import argparse
import glob
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "strandbench")
# The test's groom: 2 instances of 4-strand guides (tests/test_geometry_mesh.cpp).
GROOM = "curly:strands=40,points=8,head=0,alpha=0.5,guides=4,clump=0.3,instances=2"


def quick_specs():
    shadows, oits = set(), set()

    def collect(groups):
        for g in groups:
            for key, into in (("shadow", shadows), ("oit", oits)):
                into.update(g.get("axes", {}).get(key, []))

    collect(json.load(open(os.path.join(ROOT, "suites", "quick.json")))["groups"])
    for cases in glob.glob(os.path.join(ROOT, "techniques", "*", "cases.json")):
        collect(json.load(open(cases)).get("quick", []))
    return sorted(shadows), sorted(oits)


def fail(msg):
    """Bad input, a missing program or a render that failed: the message and exit 2 (the
    docstring's contract; sys.exit(text) would exit 1, which means a pair over its bound)."""
    print("geometry-parity.py: " + msg, file=sys.stderr)
    sys.exit(2)


def refused(spec):
    """Whether the technique declares a mesh_refusal (its unit.json). A name both families use
    (none, occupancy, rt) refuses in both or in neither."""
    name = spec.split(":")[0]
    for path in glob.glob(os.path.join(ROOT, "techniques", "*", "unit.json")):
        t = json.load(open(path)).get(name)
        if t and t.get("capabilities", {}).get("mesh_refusal"):
            return True
    return False


def render(run, geometry, shadow, oit, size, out):
    driver, backend = run
    args = [CLI, "render"] + (["--driver", driver] if driver else []) + [
        "--backend", backend, "--geometry", geometry, "--scene", GROOM, "--shadow", shadow,
        "--oit", oit, "--size", size, "--repeat", "1", "--warmup", "0", "--out", out]
    p = subprocess.run(args, capture_output=True, text=True, cwd=ROOT)
    if p.returncode != 0:
        fail(" ".join(args[1:]) + ": exit " + str(p.returncode) + ": " + p.stderr.strip())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tolerance", type=float, default=1e-4, help="the mesh path's bound")
    ap.add_argument("--compute-tolerance", type=float, default=0.0, help="the compute path's bound")
    ap.add_argument("--size", default="24x24")
    ap.add_argument("--paths", default="compute,mesh")
    a = ap.parse_args()
    paths = a.paths.split(",")
    if not paths or any(p not in ("compute", "mesh") for p in paths):
        fail("--paths: compute, mesh or both")
    if not os.access(CLI, os.X_OK):
        fail(CLI + " missing: run scripts/setup.sh")
    shadows, oits = quick_specs()
    # (path, (driver, backend), bound, techniques per family)
    plans = []
    if "compute" in paths:
        for backend in ("gl", "vulkan"):
            plans.append(("compute", ("", backend), a.compute_tolerance,
                          {"shadow": shadows, "transparency": oits}))
    if "mesh" in paths:
        if os.path.isdir(os.path.join(ROOT, "drivers", "mesa-25.0")):
            plans.append(("mesh", ("mesa-25.0", "vulkan"), a.tolerance,
                          {f: [s for s in specs if not refused(s)]
                           for f, specs in (("shadow", shadows), ("transparency", oits))}))
        else:
            print("geometry-parity.py: mesh path skipped: drivers/mesa-25.0 missing "
                  "(scripts/drivers.sh; the mesh path needs Mesa 25.0.7's lavapipe)")
    failed = []
    with tempfile.TemporaryDirectory() as tmp:
        for path, run, bound, runs in plans:
            skipped = len(shadows) + len(oits) - len(runs["shadow"]) - len(runs["transparency"])
            pairs = max(len(runs["shadow"]), len(runs["transparency"]))
            worst = 0.0
            label = "%s (%s%s)" % (path, run[1], ", " + run[0] if run[0] else "")
            for i in range(pairs):
                shadow = runs["shadow"][i % len(runs["shadow"])]
                oit = runs["transparency"][i % len(runs["transparency"])]
                images = [os.path.join(tmp, g + ".exr") for g in (path, "cpu")]
                render(run, path, shadow, oit, a.size, images[0])
                render(run, "cpu", shadow, oit, a.size, images[1])
                p = subprocess.run([CLI, "compare"] + images, capture_output=True, text=True)
                if p.returncode != 0:
                    fail("compare: " + p.stderr.strip())
                e = json.loads(p.stdout)
                print("%s: %s + %s: max %.3g, RMSE %.3g" % (label, shadow, oit, e["max_abs"],
                                                             e["rmse"]), flush=True)
                worst = max(worst, e["max_abs"])
                if e["max_abs"] > bound:
                    failed.append(label + ": " + shadow + " + " + oit)
            print("geometry-parity.py: %s: %d shadow and %d transparency techniques in %d pairs, "
                  "%d refused; largest difference %.3g (bound %g)" %
                  (label, len(runs["shadow"]), len(runs["transparency"]), pairs, skipped, worst,
                   bound), flush=True)
    if failed:
        print("geometry-parity.py: over the bound: " + ", ".join(failed), file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
