#!/usr/bin/env python3
"""Paired, interleaved timing of two strandbench builds on the same render cases.

On a shared, noisy machine two sweeps run minutes apart drift by more than the
effects being judged (compare-runs then flags noise). This runs each case on
both binaries back to back, alternating which goes first, and prints the
median new/old ratio of the frame median and of each pass, with quartiles.

  scripts/paired-compare.py OLD_BINARY NEW_BINARY [--rounds N] [--case 'NAME=render args'] ...

Without --case, a fixed set of cases from the quick suite is used.
"""
import argparse, json, shlex, statistics, subprocess, sys

DEFAULT_CASES = {
    "osm16-gl": "--scene straight:strands=1000,points=16,head=0 --shadow osm:maps=16 --backend gl",
    "osm16-vk": "--scene straight:strands=1000,points=16,head=0 --shadow osm:maps=16 --backend vulkan",
    "dom3-gl": "--scene straight:strands=1000,points=16,head=0 --shadow dom:layers=3 --backend gl",
    "occupancy-vk": "--scene straight:strands=1000,points=16,head=0 --shadow occupancy --backend vulkan",
    "wavg-vk": "--scene clustered:strands=300,points=12,head=0,alpha=0.3 --shadow dom:layers=3 --oit wavg --backend vulkan",
    "occupancy-oit-gl": "--scene straight:strands=1000,points=16,head=0,alpha=0.5 --shadow occupancy --oit occupancy --backend gl",
    "occupancy-oit-vk": "--scene clustered:strands=300,points=12,head=0,alpha=0.3 --shadow dom:layers=3 --oit occupancy --backend vulkan",
    "peel-gl": "--scene clustered:strands=300,points=12,head=0,alpha=0.3 --shadow dom:layers=3 --oit peel --backend gl",
}
COMMON = "--size 128x128 --repeat 8 --warmup 2 --out /tmp/paired-compare.png --json"


def render(binary, args):
    out = subprocess.run([binary, "render"] + shlex.split(args) + shlex.split(COMMON),
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{binary} render {args}: exit {out.returncode}\n{out.stderr}")
    d = json.loads(out.stdout)
    return d["frame_ms"]["median"], {p["name"]: p["ms"]["median"] for p in d["passes"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--case", action="append", default=[], help="NAME=render arguments")
    a = ap.parse_args()
    if a.rounds < 2:
        sys.exit("--rounds: at least 2")
    cases = dict(c.split("=", 1) for c in a.case) if a.case else DEFAULT_CASES
    for name, args in cases.items():
        frame, passes = [], {}
        for r in range(a.rounds):
            first, second = (a.old, a.new) if r % 2 == 0 else (a.new, a.old)
            res = {first: render(first, args), second: render(second, args)}
            frame.append(res[a.new][0] / res[a.old][0])
            for p, ms in res[a.new][1].items():
                if res[a.old][1].get(p, 0) > 0:
                    passes.setdefault(p, []).append(ms / res[a.old][1][p])
        q = statistics.quantiles(frame, n=4)
        detail = "  ".join(f"{p} {statistics.median(v):.2f}" for p, v in passes.items())
        print(f"{name:18s} new/old {statistics.median(frame):.3f} "
              f"(quartiles {q[0]:.3f}..{q[2]:.3f}, {a.rounds} rounds)  {detail}", flush=True)


if __name__ == "__main__":
    main()
