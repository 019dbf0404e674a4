#!/usr/bin/env python3
"""Time, strand-data memory and error against the level of detail (lod=, lod_pixels=) and the
crowd's size (instances=) for four shadow techniques on the compute geometry path
(docs/geometry.md), on the system driver and, where drivers/mesa-25.0 is there, Mesa 25.0.7.
Writes a Markdown page (default docs/geometry-measured.md) that names the command, commit,
date and machine load.

  scripts/geometry-table.py [--out FILE] [--drivers system,mesa-25.0] [--backends gl,vulkan]
                            [--size 128x128] [--instances 1,10,100]

Per case it runs `build/strandbench render --json --reference` and reads: frame time (median of
the timed frames), memory.scene_bytes (the device's own accounting of the strand data and the
groom), the strands drawn and the shares kept (lod), the error against the exact reference of
the strands drawn (error.image.rmse) and against the full model's exact reference
(error.full_model.image.rmse; with the level of detail off the two are one reference).
"""
import argparse
import datetime
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "strandbench")
GROOM = "straight:strands=1000,points=16,head=0,alpha=0.5,guides=8,clump=0.3"
CROWD = "straight:strands=200,points=16,head=0,alpha=0.5,guides=8,clump=0.3"
SHADOWS = ["shadowmap", "osm:maps=16", "dom:layers=3", "occupancy"]
LODS = [1, 0.5, 0.25]
LOD_PIXELS = 64


def run(args):
    p = subprocess.run([CLI] + args, capture_output=True, text=True, cwd=ROOT)
    if p.returncode != 0:
        raise RuntimeError(" ".join(args) + ": exit " + str(p.returncode) + ": " + p.stderr.strip())
    return p.stdout


def render(driver, backend, scene, shadow, size):
    out = run(["render", "--driver", driver, "--scene", scene, "--shadow", shadow,
               "--backend", backend, "--geometry", "compute", "--primitive", "world",
               "--size", size, "--repeat", "3", "--reference", "--json"])
    return json.loads(out)


def full_rmse(r):
    """The error against the full model's exact reference: error.image's where nothing is left out."""
    e = r["error"]
    return (e["full_model"] if "full_model" in e else e)["image"]["rmse"]


def shares(r):
    if "lod" not in r:
        return "1 (off)"
    s = r["lod"]["share"]
    if s["min"] == s["max"]:
        return "%.3g" % s["mean"]
    return "%.3g (%.3g to %.3g)" % (s["mean"], s["min"], s["max"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "geometry-measured.md"))
    ap.add_argument("--drivers", default="system,mesa-25.0")
    ap.add_argument("--backends", default="gl,vulkan")
    ap.add_argument("--size", default="128x128")
    ap.add_argument("--instances", default="1,10,100")
    a = ap.parse_args()
    # By name under drivers/ (skipped where it is not there) or a path to one.
    drivers = [d for d in a.drivers.split(",")
               if d == "system" or os.path.isdir(os.path.join(ROOT, "drivers", d)) or
               os.path.isabs(d) and os.path.isdir(d)]
    instances = [int(n) for n in a.instances.split(",")]
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=ROOT).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                           capture_output=True, text=True, cwd=ROOT).stdout.strip()
    load = open("/proc/loadavg").read().split()[0]
    start = datetime.datetime.utcnow()
    body = []
    for driver in drivers:
        for backend in a.backends.split(","):
            device = None
            lod_rows, crowd_rows = [], []
            for shadow in SHADOWS:
                for lod in LODS:
                    r = render(driver, backend, GROOM + ",lod=" + str(lod), shadow, a.size)
                    device = device or r["device"] + ", " + r["driver"]
                    lod_rows.append("| %s | %s | %d | %.3f | %d | %.5f | %.5f |" % (
                        shadow, lod, r["scene"]["strands"], r["frame_ms"]["median"],
                        r["memory"]["scene_bytes"], r["error"]["image"]["rmse"], full_rmse(r)))
            for shadow in SHADOWS:
                for n in instances:
                    for pixels in [0, LOD_PIXELS]:
                        scene = CROWD + ",instances=" + str(n)
                        if pixels:
                            scene += ",lod_pixels=" + str(pixels)
                        r = render(driver, backend, scene, shadow, a.size)
                        crowd_rows.append("| %s | %d | %s | %s | %d | %.3f | %d | %.5f |" % (
                            shadow, n, "lod_pixels=%d" % pixels if pixels else "off", shares(r),
                            r["scene"]["strands"], r["frame_ms"]["median"],
                            r["memory"]["scene_bytes"], full_rmse(r)))
            body += ["## " + driver + ", " + backend, "", "Device: " + str(device) + ".", "",
                     "Level of detail by a fixed share (`" + GROOM + ",lod=L`, `--geometry "
                     "compute --primitive world`, " + a.size + "): strands drawn, frame ms "
                     "(median of 3), scene bytes (memory.scene_bytes), RMSE against the exact "
                     "reference of the strands drawn and against the full model's.", "",
                     "| shadow | lod | strands | frame ms | scene bytes | RMSE (strands drawn) | "
                     "RMSE (full model) |", "|---|---|---|---|---|---|---|"] + lod_rows
            body += ["", "Crowds with the level of detail by size on screen (`" + CROWD +
                     ",instances=N[,lod_pixels=" + str(LOD_PIXELS) + "]`, same settings): the "
                     "share each instance kept (mean, min to max), strands drawn, frame ms, "
                     "scene bytes, RMSE against the full crowd's exact reference.", "",
                     "| shadow | instances | level of detail | share kept | strands | frame ms | "
                     "scene bytes | RMSE (full model) |",
                     "|---|---|---|---|---|---|---|---|"] + crowd_rows + [""]
    minutes = (datetime.datetime.utcnow() - start).total_seconds() / 60
    lines = ["# Geometry: time, memory and error against lod and instances", "",
             "<!-- generated by scripts/geometry-table.py: do not edit by hand -->",
             "Generated by `scripts/geometry-table.py " + " ".join(sys.argv[1:]) + "` on " +
             commit + (" (with uncommitted changes)" if dirty else "") + ", " +
             start.strftime("%Y-%m-%d %H:%M UTC") + ", load average " + load +
             " before the run and " + open("/proc/loadavg").read().split()[0] +
             " after it (" + str(os.cpu_count()) + " cores, shared), %.0f minutes; " % minutes +
             "do not edit by hand. Scenes, paths, the rule and the level of detail: "
             "[geometry.md](geometry.md). Times on a loaded shared machine: compare within "
             "a table, not across runs.", ""] + body
    with open(a.out, "w") as f:
        f.write("\n".join(lines) + "\n")
    print("geometry-table.py: wrote " + a.out)


if __name__ == "__main__":
    main()
