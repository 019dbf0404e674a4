#!/usr/bin/env bash
# Visibility RMSE against the exact visibility and shadow time for every
# shadow technique on the straight, curly and stray scenes, on both backends:
# docs/shadow-techniques.md's "Error against time" table.
#   scripts/shadow-errors.sh [SIZE] [REPEAT]    (defaults 256 and 5; STRANDBENCH=path
#   runs another binary; SHADOWS="spec spec ..." measures only those rows; BACKENDS="gl"
#   only those backends, default "gl vulkan")
# With SB_DOCS_RESULTS set, also writes the rows there as JSON, for the results store:
#   scripts/docs-record.sh shadow-errors scripts/shadow-errors.sh 128 3
# Shadow time: the median over the timed frames of the technique's own passes
# (names starting "<technique>.", and "exact." for dsm and avsm, which build
# their curves from the exact technique's light-space lists), in ms; avsm's
# is marked "timing emulated" (its resolve stands in for fragment-shader
# interlock: render JSON "timing_emulated"). Image SIZExSIZE, light maps at
# the techniques' default size.
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-256}
repeat=${2:-5}
scenes=("straight:strands=4000,points=16,head=0" "curly:strands=1500,points=48,head=0"
        "stray:strands=3000,points=16")
bin=${STRANDBENCH:-build/strandbench}
# Every registered shadow technique (`strandbench list --json`) but none, at its
# defaults, or as the variants named here.
declare -A variants=(
  [osm]="osm:maps=16 osm:maps=16,filter=pcf6x4" [dc]="dc:clusters=4"
  [dom]="dom:layers=3 dom:layers=3,spacing=power,filter=pcf6x4"
  [dsm]="dsm:epsilon=0,max_nodes=65536 dsm:epsilon=0.02 dsm:epsilon=0.1"
  [fom]="fom:coefficients=4 fom:coefficients=16"
  [msm]="msm:moments=4 msm:moments=8 msm:moments=8,kind=trig"
  [avsm]="avsm:nodes=4 avsm:nodes=8 avsm:nodes=16" [voxel]="voxel:grid=64,steps=64 voxel")
shadows=()
while read -r name; do
  [ "$name" = none ] && continue
  # shellcheck disable=SC2206
  shadows+=(${variants[$name]:-$name})
done < <("$bin" list --json |
  python3 -c 'import json, sys; print("\n".join(t["name"] for t in json.load(sys.stdin)["shadow"]))')
if [ -n "${SHADOWS:-}" ]; then read -ra shadows <<< "$SHADOWS"; fi
out=${SB_DOCS_RESULTS:-}
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
row() {  # scene backend shadow: one table row on stdout, one JSON line in $tmp
  "$bin" render --scene "$1" --backend "$2" --shadow "$3" --size "${size}x${size}" \
    --repeat "$repeat" --warmup 1 --reference --no-image --json |
    python3 -c '
import json, sys
r = json.load(sys.stdin)
tech = r["shadow"].split(":")[0]
prefixes = (tech + ".",) + (("exact.",) if tech in ("dsm", "avsm") else ())
ms = sum(p["ms"]["median"] for p in r["passes"] if p["name"].startswith(prefixes))
rmse = r["error"]["visibility"]["rmse"]
emulated = bool(r.get("timing_emulated"))
note = " (timing emulated)" if emulated else ""
print("| %s | %s | %s | %.4f | %.2f%s |" % (sys.argv[1].split(":")[0], sys.argv[2], r["shadow"], rmse, ms, note))
with open(sys.argv[3], "a") as f:
    f.write(json.dumps({"scene": sys.argv[1], "backend": sys.argv[2], "shadow": r["shadow"],
                        "rmse": rmse, "ms": ms, "emulated": emulated}) + "\n")
' "$1" "$2" "$tmp"
}
echo "| scene | backend | shadow | visibility RMSE | shadow ms |"
echo "|---|---|---|---:|---:|"
for scene in "${scenes[@]}"; do
  for backend in ${BACKENDS:-gl vulkan}; do
    for shadow in "${shadows[@]}"; do row "$scene" "$backend" "$shadow"; done
  done
done
# For the results store (docs/results/shadow-errors): one row per shadow technique, the
# scenes as columns with each backend's time.
[ -n "$out" ] || exit 0
python3 - "$tmp" "$out" "$size" "$repeat" "${scenes[@]}" <<'PY'
import json, sys
tmp, out, size, repeat, *scenes = sys.argv[1:]
rows = [json.loads(l) for l in open(tmp)]
shadows = list(dict.fromkeys(r["shadow"] for r in rows))
def cell(scene, shadow, backend, key):
    m = [r for r in rows if r["scene"] == scene and r["shadow"] == shadow and r["backend"] == backend]
    return m[0][key] if m else None
data = {"size": int(size), "repeat": int(repeat),
        "scenes": [{"scene": s, "short": s.split(":")[0]} for s in scenes],
        "rows": [{"shadow": sh, "emulated": any(r["emulated"] for r in rows if r["shadow"] == sh),
                  "cells": [{"rmse_gl": cell(s, sh, "gl", "rmse"), "rmse_vulkan": cell(s, sh, "vulkan", "rmse"),
                             "ms_gl": cell(s, sh, "gl", "ms"), "ms_vulkan": cell(s, sh, "vulkan", "ms")}
                            for s in scenes]} for sh in shadows]}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
PY
