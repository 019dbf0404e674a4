#!/usr/bin/env bash
# Thesis Table 2 (fur on the bunny: 2,088,900 and 22,977,900 vertices at 800x800) is too large
# for this machine in an hour; this measures how the figure's wall time grows with its fur,
# so that the size it runs is the largest that fits 60 minutes by the measured scaling (not
# guessed, not extrapolated from another machine). It runs the figure's --small variant with
# every group's strands multiplied by each scale K (the two levels keep the paper's ratio),
# at the paper's image size, one timed round, on the backends given, timing each whole run;
# fits seconds = a + b * K by least squares; and writes to $SB_DOCS_RESULTS (or prints):
# the runs, the fit, the predicted time of the paper's size, and the largest K (and its
# vertices) predicted to fit the budget.
# Usage: scripts/thesis-table2-scaling.sh [--backend gl|vulkan|both] [--size WxH]
#                                         [--budget-s S] K1 K2 [K3...]
#   defaults: --backend both --size 800x800 --budget-s 3600; at least two scales.
# Record it: scripts/docs-record.sh thesis-table2-scaling scripts/thesis-table2-scaling.sh 1 2 4
set -euo pipefail
cd "$(dirname "$0")/.."
backend=both size=800x800 budget=3600 scales=()
usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
  case $1 in
    --backend) backend=${2:?}; shift 2 ;;
    --size) size=${2:?}; shift 2 ;;
    --budget-s) budget=${2:?}; shift 2 ;;
    [0-9]*) scales+=("$1"); shift ;;
    *) usage ;;
  esac
done
[ ${#scales[@]} -ge 2 ] || { echo "thesis-table2-scaling.sh: give at least two scales K" >&2; usage; }
cli=build/strandbench
[ -x "$cli" ] || { echo "thesis-table2-scaling.sh: $cli missing: build first" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
runs=()
for k in "${scales[@]}"; do
  # The figure file with its small groups' strands times K and the image at SIZE.
  python3 - "$k" "$size" suites/figures/thesis-table2.json "$work/t2-$k.json" <<'PY'
import json, re, sys
k, size, src, dst = float(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4]
d = json.load(open(src))
d["small"]["defaults"]["size"] = size
for g in d["small"]["groups"].values():
    g["scene"] = re.sub(r"strands=(\d+)", lambda m: "strands=%d" % round(int(m.group(1)) * k), g["scene"])
json.dump(d, open(dst, "w"), indent=1)
PY
  start=$(date +%s.%N)
  status=0
  "$cli" figure "$work/t2-$k.json" --small --min-reps 1 --backend "$backend" \
    --out "$work/out-$k" >"$work/log-$k" 2>&1 || status=$?
  seconds=$(python3 -c "import sys; print(round(float(sys.argv[2]) - float(sys.argv[1]), 1))" "$start" "$(date +%s.%N)")
  vertices=$(python3 - "$work/out-$k/results.json" <<'PY'
import json, sys
try:
    rs = json.load(open(sys.argv[1]))["results"]
    print(max(int(r.get("scene", {}).get("points", 0) or 0) for r in rs))
except Exception:
    print(0)
PY
)
  echo "scale $k: $seconds s, exit $status, largest scene $vertices vertices" >&2
  runs+=("$k $seconds $status $vertices")
done
python3 - "$backend" "$size" "$budget" "${runs[@]}" <<'PY'
import json, os, sys
backend, size, budget = sys.argv[1], sys.argv[2], float(sys.argv[3])
runs = []
for r in sys.argv[4:]:
    k, s, status, v = r.split()
    runs.append({"scale": float(k), "seconds": float(s), "exit": int(status), "vertices": int(v)})
xs = [r["scale"] for r in runs]; ys = [r["seconds"] for r in runs]
n = len(xs); sx = sum(xs); sy = sum(ys)
sxx = sum(x * x for x in xs); sxy = sum(x * y for x, y in zip(xs, ys))
b = (n * sxy - sx * sy) / (n * sxx - sx * sx)
a = (sy - b * sx) / n
# The paper's size: level 2's 2,088,900 vertices over the small variant's (300 strands of
# 10 points): the scale of the full figure.
small_strands, points, paper_vertices = 300, 10, [2088900, 22977900]
full_scale = paper_vertices[0] / (small_strands * points)
fit_scale = (budget - a) / b if b > 0 else None
out = {
    "backend": backend, "size": size, "budget_s": budget, "runs": runs,
    "fit": {"a_s": a, "b_s_per_scale": b},
    "paper": {"scale": full_scale, "vertices_lvl2": paper_vertices[0],
              "vertices_lvl4": paper_vertices[1], "predicted_s": a + b * full_scale,
              "predicted_h": (a + b * full_scale) / 3600},
    "fits_budget": None if fit_scale is None else {
        "scale": fit_scale,
        "strands_lvl2": round(300 * fit_scale), "strands_lvl4": round(3300 * fit_scale),
        "vertices_lvl2": round(300 * fit_scale) * points,
        "vertices_lvl4": round(3300 * fit_scale) * points},
}
text = json.dumps(out, indent=1)
if os.environ.get("SB_DOCS_RESULTS"):
    open(os.environ["SB_DOCS_RESULTS"], "w").write(text + "\n")
print(text)
PY
