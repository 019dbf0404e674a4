#!/usr/bin/env bash
# Image RMSE against the exact transparency reference for every --oit technique
# the binary lists (`strandbench list --json`, so techniques added later appear
# without editing this script), on both backends, on a scene of eye depth
# complexity >= 100 (the one tests/test_oit_layers.cpp and
# tests/test_occupancy_oit.cpp use), then the option variants the papers'
# claims are about. Shadows off (--shadow none), and the error is the
# transparency technique's own (error.own.image.rmse: the reference with the
# same shadows), so only the transparency differs.
#
#   scripts/oit-errors.sh                 # build/strandbench, 48x48
#   BIN=path SIZE=64x64 SCENE=... BACKENDS="gl" scripts/oit-errors.sh
#
# Prints one line per technique and backend:
#   backend  technique  rmse  eye-depth-complexity(max/mean)  oit-bytes  passes  [emulated]
# With SB_DOCS_RESULTS set, also writes them there as JSON (one row per technique, each
# backend's error) for the results store: scripts/docs-record.sh oit-errors scripts/oit-errors.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BIN=${BIN:-build/strandbench}
SCENE=${SCENE:-clustered:strands=1500,points=6,head=0,alpha=0.2}
SIZE=${SIZE:-48x48}
BACKENDS=${BACKENDS:-gl vulkan}
EXTRA=${EXTRA:-"mboit:moments=4 mboit:moments=8 mboit:precision=16 kbuffer:k=1 kbuffer:k=2 kbuffer:k=4 kbuffer:k=16 mlab:layers=1 mlab:layers=8 shortcut:k=8"}

# One line from a render --json object (stdin).
SUMMARY='
import json, sys
backend, technique = sys.argv[1], sys.argv[2]
j = json.load(sys.stdin)
err = j.get("error", {})
rmse = err.get("own", {}).get("image", {}).get("rmse", err.get("image", {}).get("rmse"))
eye = (j.get("depth_complexity") or {}).get("eye") or {}
complexity = "%s/%.0f" % (eye.get("max", "-"), eye.get("mean", 0)) if eye else "-"
oit = j.get("memory", {}).get("oit_bytes", "-")
passes = len(j.get("passes", []))
note = "timing emulated" if j.get("timing_emulated") else ""
counters = j.get("counters")
if counters:
    note = (note + " " + " ".join("%s=%s" % kv for kv in counters.items())).strip()
print("%-8s %-30s %-10.6f %-12s %-10s %-6s %s" % (backend, technique, rmse, complexity, oit, passes, note))
if len(sys.argv) > 3:
    with open(sys.argv[3], "a") as f:
        f.write(json.dumps({"backend": backend, "technique": technique, "rmse": rmse,
                            "eye_max": eye.get("max"), "eye_mean": eye.get("mean"), "bytes": oit,
                            "passes": passes, "emulated": bool(j.get("timing_emulated"))}) + "\n")
'
[ -x "$BIN" ] || { echo "oit-errors: $BIN not found (build it first, or set BIN)" >&2; exit 2; }
mapfile -t TECHNIQUES < <("$BIN" list --json |
  python3 -c 'import json, sys; print("\n".join(t["name"] for t in json.load(sys.stdin)["oit"]))')
# shellcheck disable=SC2206
TECHNIQUES+=($EXTRA)

rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
echo "scene $SCENE at $SIZE; rmse = error.own.image.rmse against the exact reference (shadows off)"
printf '%-8s %-30s %-10s %-12s %-10s %-6s %s\n' backend technique rmse complexity oit_bytes passes note
for backend in $BACKENDS; do
  for t in "${TECHNIQUES[@]}"; do
    if ! out=$("$BIN" render --backend "$backend" --scene "$SCENE" --size "$SIZE" --shadow none \
      --oit "$t" --reference --repeat 1 --warmup 0 --json 2>/dev/null); then
      printf "%-8s %-30s %s\n" "$backend" "$t" "FAILED"
      continue
    fi
    python3 -c "$SUMMARY" "$backend" "$t" ${SB_DOCS_RESULTS:+"$rows"} <<<"$out"
  done
done
[ -n "${SB_DOCS_RESULTS:-}" ] || exit 0
python3 - "$rows" "$SB_DOCS_RESULTS" "$SCENE" "$SIZE" <<'PY'
import json, sys
rows_file, out, scene, size = sys.argv[1:]
rows = [json.loads(l) for l in open(rows_file)]
w, h = (int(v) for v in size.split("x"))
techniques = list(dict.fromkeys(r["technique"] for r in rows))
def pick(t, backend):
    m = [r for r in rows if r["technique"] == t and r["backend"] == backend]
    return m[0] if m else {}
table = []
for t in techniques:
    gl, vk = pick(t, "gl"), pick(t, "vulkan")
    any_ = gl or vk
    table.append({"technique": t, "rmse_gl": gl.get("rmse"), "rmse_vulkan": vk.get("rmse"),
                  "bytes": any_.get("bytes"), "bytes_per_pixel": any_.get("bytes") / (w * h)
                  if isinstance(any_.get("bytes"), (int, float)) else None,
                  "passes": any_.get("passes"), "emulated": any_.get("emulated", False)})
eye = next((r for r in rows if r.get("eye_max") is not None), {})
data = {"scene": scene, "size": size, "eye_max": eye.get("eye_max"), "eye_mean": eye.get("eye_mean"),
        "rows": table}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
PY
