#!/usr/bin/env python3
"""Time, strand-data memory and error against the level of detail (lod=, lod_pixels=) and the
crowd's size (instances=) for four shadow techniques (docs/geometry.md), per run: a driver, an
API and a geometry path. By default the system driver on GL and Vulkan (compute path) and Mesa
25.0.7's lavapipe on Vulkan (mesh path; left out where drivers/mesa-25.0 is absent). Prints the
rows; with SB_DOCS_RESULTS set, writes them there as JSON for the results store
(docs/measured-pages.md), rendered into docs/geometry-measured.md:

  scripts/docs-record.sh geometry-table scripts/geometry-table.py

  scripts/geometry-table.py [--runs system:gl:compute,...] [--size 64x64] [--instances 1,10,100]

Per case it runs `build/strandbench render --json --reference` and keeps: frame time (median of
the timed frames), memory.scene_bytes (the device's own accounting of the strand data and the
groom), the strands drawn and the shares kept (lod), the error against the exact reference of
the strands drawn (error.image.rmse) and against the full model's exact reference
(error.full_model.image.rmse; with the level of detail off the two are one reference).
"""
import argparse
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "strandbench")
GROOM = "straight:strands=1000,points=16,head=0,alpha=0.5,guides=8,clump=0.3"
CROWD = "straight:strands=200,points=16,head=0,alpha=0.5,guides=8,clump=0.3"
SHADOWS = ["shadowmap", "osm:maps=16", "dom:layers=3", "occupancy"]
LODS = [1, 0.5, 0.25]
LOD_PIXELS = 64
REPEAT = 3
RUNS = "system:gl:compute,system:vulkan:compute,mesa-25.0:vulkan:mesh"


def render(driver, backend, geometry, scene, shadow, size):
    args = ["render", "--driver", driver, "--scene", scene, "--shadow", shadow, "--backend",
            backend, "--geometry", geometry, "--primitive", "world", "--size", size, "--repeat",
            str(REPEAT), "--reference", "--json"]
    p = subprocess.run([CLI] + args, capture_output=True, text=True, cwd=ROOT)
    if p.returncode != 0:
        sys.exit("geometry-table.py: " + " ".join(args) + ": exit " + str(p.returncode) + ": " +
                 p.stderr.strip())
    return json.loads(p.stdout)


def row(r, shadow):
    """The numbers of one render, raw (the template formats them)."""
    e = r["error"]
    share = r["lod"]["share"] if "lod" in r else {"min": 1, "mean": 1, "max": 1}
    return {"shadow": shadow, "strands": r["scene"]["strands"],
            "frame_ms": r["frame_ms"]["median"], "scene_bytes": r["memory"]["scene_bytes"],
            "rmse": e["image"]["rmse"],
            "rmse_full": (e["full_model"] if "full_model" in e else e)["image"]["rmse"],
            "share": share}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", default=RUNS, help="driver:backend:geometry,... (default " + RUNS +
                    "); a driver by name under drivers/ is left out where it is not there")
    ap.add_argument("--size", default="64x64")
    ap.add_argument("--instances", default="1,10,100")
    a = ap.parse_args()
    runs = []
    for spec in a.runs.split(","):
        parts = spec.split(":")
        if len(parts) != 3 or parts[2] not in ("cpu", "compute", "mesh"):
            sys.exit("geometry-table.py: --runs: '" + spec + "' is not driver:backend:geometry "
                     "(geometry cpu, compute or mesh)")
        if parts[0] == "system" or os.path.isdir(os.path.join(ROOT, "drivers", parts[0])):
            runs.append(parts)
        else:
            print("geometry-table.py: drivers/" + parts[0] + " is not there: " + spec +
                  " left out", file=sys.stderr)
    instances = [int(n) for n in a.instances.split(",")]
    start = time.time()
    data = {"groom": GROOM, "crowd": CROWD, "size": a.size, "repeat": REPEAT,
            "lod_pixels": LOD_PIXELS, "runs": []}
    for driver, backend, geometry in runs:
        run = {"driver": driver, "backend": backend, "geometry": geometry, "lod": [], "crowd": []}
        for shadow in SHADOWS:
            for lod in LODS:
                r = render(driver, backend, geometry, GROOM + ",lod=" + str(lod), shadow, a.size)
                run["device"] = r["device"] + ", " + r["driver"]
                run["lod"].append(dict(row(r, shadow), lod=lod))
                print(driver, backend, geometry, json.dumps(run["lod"][-1]), flush=True)
        for shadow in SHADOWS:
            for n in instances:
                for pixels in [0, LOD_PIXELS]:
                    scene = CROWD + ",instances=" + str(n)
                    if pixels:
                        scene += ",lod_pixels=" + str(pixels)
                    r = render(driver, backend, geometry, scene, shadow, a.size)
                    run["crowd"].append(dict(row(r, shadow), instances=n,
                                             level=("lod_pixels=%d" % pixels) if pixels else "off"))
                    print(driver, backend, geometry, json.dumps(run["crowd"][-1]), flush=True)
        data["runs"].append(run)
    data["seconds"] = round(time.time() - start)
    out = os.environ.get("SB_DOCS_RESULTS")
    if out:
        with open(out, "w") as f:
            json.dump(data, f, indent=1)


if __name__ == "__main__":
    main()
