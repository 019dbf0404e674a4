#!/usr/bin/env bash
# The model error measured (docs/physics-reference.md "The model error"): suites/physics.json
# run twice into fresh folders with one cache folder; the first run path-traces the reference
# (once per scene and view: every case shares it), the second takes it from the cache (its
# time shows it). Writes docs/physics-measured.md (or the file given): per shading model and
# shadow technique the RMSE against the rasterized exact reference (the technique's error) and
# against the path-traced reference (technique plus model), the latter also without the
# reference's own noise; the exact reference's row is its own distance from physics.
# Usage: scripts/physics-reference.sh [OUT.md]   Needs build/strandbench and ../shared/models.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/physics-measured.md}
cli=build/strandbench
[ -x "$cli" ] || { echo "physics-reference.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
[ -f ../shared/models/straight.hair ] || {
  echo "physics-reference.sh: ../shared/models/straight.hair missing" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SB_PBR_CACHE="$tmp/cache"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
t0=$(date +%s.%N)
"$cli" sweep suites/physics.json --out "$tmp/first" > "$tmp/first.log" 2>&1
t1=$(date +%s.%N)
"$cli" sweep suites/physics.json --out "$tmp/second" > "$tmp/second.log" 2>&1
t2=$(date +%s.%N)
python3 - "$tmp" "$out" "$load_before" "$(cut -d' ' -f1-3 /proc/loadavg)" "$t0" "$t1" "$t2" <<'PY'
import json, os, subprocess, sys, datetime
tmp, out, load0, load1, t0, t1, t2 = sys.argv[1:]
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], capture_output=True,
                       text=True).stdout.strip()
commit += " (with uncommitted changes)" if dirty else ""
def load(run):
    return json.load(open(os.path.join(tmp, run, "results.json")))["results"]
first, second = load("first"), load("second")
def pbr(r):
    return r["error"]["pbr"]
def ms(rs, key):
    return sum(pbr(r)["reference"]["pbr"][key] for r in rs if not pbr(r)["reference"]["cached"])
hits = lambda rs: sum(1 for r in rs if pbr(r)["reference"]["pbr"]["cache"]["hit"])
renders = lambda rs: sum(1 for r in rs if not pbr(r)["reference"]["cached"] and not pbr(r)["reference"]["pbr"]["cache"]["hit"])
p0 = pbr(first[0])
ref = p0["reference"]
lines = [
    "# The model error, measured",
    "",
    "Written by `scripts/physics-reference.sh` (suite `suites/physics.json`, GL on llvmpipe). "
    f"Commit {commit}, {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, "
    f"load {load0} before, {load1} after.",
    "",
    "```sh",
    "scripts/physics-reference.sh   # = build/strandbench sweep suites/physics.json --out DIR, twice",
    "```",
    "",
    f"The path-traced reference: `{ref['spec']}` on `{first[0]['scene']['spec']}` at "
    f"{ref['size'][0]}x{ref['size'][1]}, strands {ref['pbr']['width']} width "
    f"({ref['pbr']['thickness_source']}, mean {ref['pbr']['thickness']:.3g}), {ref['pbr']['spp']} samples "
    f"per pixel; its own noise: RMSE {p0['noise']['rmse']:.4f} (the root mean square of the "
    f"per-pixel standard error; mean standard error {p0['noise']['mean_stderr']:.4f}).",
    "",
    f"Cache: the first run path-traced it {renders(first)} time(s) ({ms(first, 'render_ms') / 1000:.2f} s of "
    f"rendering) and took it from the disk cache {hits(first)} time(s); the second run path-traced it "
    f"{renders(second)} time(s) and took it from the cache {hits(second)} time(s). Wall time of the whole "
    f"sweep: first {float(t1) - float(t0):.1f} s, second {float(t2) - float(t1):.1f} s.",
    "",
    "RMSE of the image (linear RGB): against the rasterized exact reference (the technique's error), "
    "against the path-traced reference (technique plus model), and the latter with the reference's noise "
    "taken out (sqrt(rmse^2 - noise^2)). The row `exact` is the rasterized exact reference itself: its "
    "distance from physics is the model's error alone.",
    "",
    f"Brightness: the path-traced image's mean (over pixels and RGB, linear) is "
    f"{p0['mean']['reference']:.4f}; each row's own mean is in the last column. A model whose mean is far "
    "from it is off by a scale (its radiometry) as much as by its shadows.",
    "",
    "| shading | shadow | vs exact | vs path traced | vs path traced, noise removed | mean |",
    "|---|---|---|---|---|---|",
]
for r in first:
    e = r["error"]
    lines.append(f"| {r['case']['params']['shading']} | {r['case']['params']['shadow']} | "
                 f"{e['image']['rmse']:.4f} | {e['pbr']['rmse']:.4f} | {e['pbr']['noise']['rmse_without_noise']:.4f} | "
                 f"{e['pbr']['mean']['image']:.4f} |")
open(out, "w").write("\n".join(lines) + "\n")
print("wrote", out)
PY
