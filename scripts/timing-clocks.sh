#!/usr/bin/env bash
# The two clocks of per-pass timing side by side, on this machine's drivers: the CPU clock
# around each pass (the default on llvmpipe and lavapipe) and the APIs' GPU timestamps (GL
# glQueryCounter, Vulkan vkCmdWriteTimestamp; the default on GPUs), for one frame of DOM
# shadows and weighted blended transparency. Writes its numbers as JSON to $SB_DOCS_RESULTS
# (or out/timing-clocks.json): `scripts/docs-record.sh timing-clocks scripts/timing-clocks.sh`
# then `build/strandbench docs refresh` renders docs/timing-clocks.md.
# Usage: scripts/timing-clocks.sh     Needs build/strandbench (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${SB_DOCS_RESULTS:-out/timing-clocks.json}
mkdir -p "$(dirname "$out")"
cli=build/strandbench
[ -x "$cli" ] || { echo "timing-clocks.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(render --scene curly:strands=20000,points=32,seed=7 --shadow dom --oit wboit
      --size 512x512 --warmup 2 --repeat 7 --json)
for backend in gl vulkan; do
  up=$(echo "$backend" | tr a-z A-Z)
  env "SB_${up}_CPU_TIMING=1" "$cli" "${args[@]}" --backend "$backend" > "$tmp/$backend-cpu.json"
  env "SB_${up}_GPU_TIMING=1" "$cli" "${args[@]}" --backend "$backend" > "$tmp/$backend-gpu.json"
done
python3 - "$tmp" "$out" "${args[*]}" <<'PY'
import json, sys, os
tmp, out, args = sys.argv[1:]
runs = {f"{b}-{m}": json.load(open(os.path.join(tmp, f"{b}-{m}.json"))) for b in ("gl", "vulkan") for m in ("cpu", "gpu")}
spread = []  # |timestamps / CPU - 1| of the passes over 5 ms
backends = []
for b in ("gl", "vulkan"):
    cpu, gpu = runs[f"{b}-cpu"], runs[f"{b}-gpu"]
    g = {p["name"]: p["ms"]["median"] for p in gpu["passes"]}
    rows = []
    for p in cpu["passes"] + [{"name": "frame", "ms": cpu["frame_ms"]}]:
        c = p["ms"]["median"]
        t = gpu["frame_ms"]["median"] if p["name"] == "frame" else g.get(p["name"])
        row = {"pass": p["name"], "cpu_ms": c}
        if t is not None:
            row["timestamp"] = {"ms": t, "over_cpu": t / c if c > 0 else 0.0}
        rows.append(row)
        if t is not None and c > 5 and p["name"] != "frame":
            spread.append(abs(t / c - 1))
    backends.append({"backend": b, "device": cpu["device"], "cpu_timing": cpu["timing"],
                     "gpu_timing": gpu["timing"], "repeat": cpu["repeat"], "rows": rows})
data = {"args": args, "backends": backends, "max_spread": max(spread) if spread else 0.0}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
print("wrote", out)
PY
