#!/usr/bin/env python3
"""Every quick-suite technique on the mesh path against the CPU path (docs/geometry.md, "Same
image"): the all-pairs form of GeometryMesh.RepresentativePairsDrawTheCpuImageOnMesa25, which
runs one pair per kind in ctest. On Mesa 25.0.7's lavapipe (drivers/mesa-25.0), each shadow and
transparency technique of the quick suite (suites/quick.json's axes and the techniques' own
quick cases) in shadow + transparency pairs, one render on each path; a technique the mesh path
refuses (its unit.json's mesh_refusal) is counted, not compared. Prints each pair's difference;
exit 1 when a pair differs by more than the tolerance at any pixel, 2 on bad input or a missing
driver. Minutes: scripts/nightly.sh runs it.

  scripts/mesh-parity.py [--tolerance 1e-4] [--size 24x24]
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


def refused(spec):
    """Whether the technique declares a mesh_refusal (its unit.json). A name both families use
    (none, occupancy, rt) refuses in both or in neither."""
    name = spec.split(":")[0]
    for path in glob.glob(os.path.join(ROOT, "techniques", "*", "unit.json")):
        t = json.load(open(path)).get(name)
        if t and t.get("capabilities", {}).get("mesh_refusal"):
            return True
    return False


def render(geometry, shadow, oit, size, out):
    args = [CLI, "render", "--driver", "mesa-25.0", "--backend", "vulkan", "--geometry", geometry,
            "--scene", GROOM, "--shadow", shadow, "--oit", oit, "--size", size, "--repeat", "1",
            "--warmup", "0", "--out", out]
    p = subprocess.run(args, capture_output=True, text=True, cwd=ROOT)
    if p.returncode != 0:
        sys.exit("mesh-parity.py: " + " ".join(args[1:]) + ": exit " + str(p.returncode) + ": " +
                 p.stderr.strip())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tolerance", type=float, default=1e-4)
    ap.add_argument("--size", default="24x24")
    a = ap.parse_args()
    if not os.access(CLI, os.X_OK):
        sys.exit("mesh-parity.py: " + CLI + " missing: run scripts/setup.sh")
    if not os.path.isdir(os.path.join(ROOT, "drivers", "mesa-25.0")):
        sys.exit("mesh-parity.py: drivers/mesa-25.0 missing (scripts/drivers.sh): the mesh path "
                 "needs Mesa 25.0.7's lavapipe")
    shadows, oits = quick_specs()
    runs = {f: [s for s in specs if not refused(s)]
            for f, specs in (("shadow", shadows), ("transparency", oits))}
    skipped = len(shadows) + len(oits) - len(runs["shadow"]) - len(runs["transparency"])
    pairs = max(len(runs["shadow"]), len(runs["transparency"]))
    worst, failed = 0.0, []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(pairs):
            shadow = runs["shadow"][i % len(runs["shadow"])]
            oit = runs["transparency"][i % len(runs["transparency"])]
            images = [os.path.join(tmp, g + ".exr") for g in ("mesh", "cpu")]
            render("mesh", shadow, oit, a.size, images[0])
            render("cpu", shadow, oit, a.size, images[1])
            p = subprocess.run([CLI, "compare"] + images, capture_output=True, text=True)
            if p.returncode != 0:
                sys.exit("mesh-parity.py: compare: " + p.stderr.strip())
            e = json.loads(p.stdout)
            print("%s + %s: max %.3g, RMSE %.3g" % (shadow, oit, e["max_abs"], e["rmse"]),
                  flush=True)
            worst = max(worst, e["max_abs"])
            if e["max_abs"] > a.tolerance:
                failed.append(shadow + " + " + oit)
    print("mesh-parity.py: %d shadow and %d transparency techniques in %d pairs, %d refused by "
          "the mesh path; largest difference %.3g (tolerance %g)" %
          (len(runs["shadow"]), len(runs["transparency"]), pairs, skipped, worst, a.tolerance))
    if failed:
        print("mesh-parity.py: over the tolerance: " + ", ".join(failed), file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
