#!/usr/bin/env bash
# The work counters measured: the quick suite run twice (every case's counters, run to run),
# GL against Vulkan case by case, and bench-shadows' OSM 16 / DOM 3 frame on both APIs, pass
# by pass, work beside time (the same work, different time: the driver, not the technique).
# Writes its numbers as JSON to $SB_DOCS_RESULTS (or out/work-counters.json):
# `scripts/docs-record.sh work-counters scripts/work-counters.sh`, then
# `build/strandbench docs refresh` renders docs/work-counters-measured.md.
# Usage: scripts/work-counters.sh     Needs build/strandbench (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${SB_DOCS_RESULTS:-out/work-counters.json}
mkdir -p "$(dirname "$out")"
cli=build/strandbench
[ -x "$cli" ] || { echo "work-counters.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for run in 1 2; do
  "$cli" sweep suites/quick.json --out "$tmp/quick-$run" > "$tmp/quick-$run.log"
done
# bench-shadows' scene and size (cli/bench_command.cpp), three timed frames.
bench=(render --scene straight:strands=20000,points=16,head=0 --size 512x512 --warmup 1
       --repeat 3 --json)
for backend in gl vulkan; do
  for shadow in osm:maps=16 dom:layers=3; do
    "$cli" "${bench[@]}" --backend "$backend" --shadow "$shadow" > "$tmp/$backend-${shadow%%:*}.json"
  done
done
python3 - "$tmp" "$out" "${bench[*]}" <<'PY'
import json, os, re, sys
tmp, out, bench = sys.argv[1:]
def results(run):
    return {r["case"]["id"]: r for r in json.load(open(os.path.join(tmp, run, "results.json")))["results"]}
def work(r):
    return {p["name"]: p["work"] for p in r.get("passes", [])}
a, b = results("quick-1"), results("quick-2")
passes = sum(len(r.get("passes", [])) for r in a.values())
differ = [{"case": cid, "pass": name} for cid in a for name, w in work(a[cid]).items()
          if work(b.get(cid, {})).get(name) != w]
pairs, api = 0, []
for cid, r in a.items():
    if r.get("backend") != "gl":
        continue
    other = a.get(re.sub(r"backend=gl", "backend=vulkan", cid))
    if other is None:
        continue
    pairs += 1
    g, v = work(r), work(other)
    for name in sorted(set(g) | set(v)):
        for key in sorted(set(g.get(name, {})) | set(v.get(name, {}))):
            if key != "resources" and g.get(name, {}).get(key) != v.get(name, {}).get(key):
                api.append({"case": cid, "pass": name, "key": key,
                            "gl": str(g.get(name, {}).get(key)), "vulkan": str(v.get(name, {}).get(key))})
rows, frames = [], []
for backend in ("gl", "vulkan"):
    ms = {}
    for shadow in ("osm", "dom"):
        r = json.load(open(os.path.join(tmp, f"{backend}-{shadow}.json")))
        ms[shadow] = r["frame_ms"]["median"]
        for p in r["passes"]:
            w, t = p["work"], p["ms"]["median"]
            frag = w["fragment_invocations"] or 0
            row = {"backend": backend, "shadow": r["shadow"], "pass": p["name"],
                   "executions": p["executions"], "fragments": frag,
                   "bytes_written": w["bytes_written"], "bytes_read": w["bytes_read"], "ms": t}
            if frag:
                row["ns_per_fragment"] = {"ns": 1e6 * t / frag}
            rows.append(row)
    frames.append({"backend": backend, "dom_ms": ms["dom"], "osm_ms": ms["osm"],
                   "dom_over_osm": ms["dom"] / ms["osm"]})
data = {"bench": bench, "cases": len(a), "passes": passes, "run_to_run": {"count": len(differ), "first": differ[:20]},
        "api_pairs": pairs, "api": {"count": len(api), "first": api[:20]}, "passes_table": rows,
        "frames": frames}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
print("wrote", out)
PY
