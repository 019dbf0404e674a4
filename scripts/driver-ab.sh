#!/usr/bin/env bash
# Driver A/B on the quick suite: the system's Mesa against Mesa 25.0.7 (scripts/drivers.sh),
# each in its own process, with the triage page (FOLDER/ab.html). Writes its numbers as JSON
# to $SB_DOCS_RESULTS (or out/driver-ab.json): `scripts/docs-record.sh driver-ab
# scripts/driver-ab.sh`, then `build/strandbench docs refresh` renders docs/driver-ab-measured.md.
# Usage: scripts/driver-ab.sh [FOLDER]   Needs build/strandbench and drivers/mesa-25.0.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${SB_DOCS_RESULTS:-out/driver-ab.json}
dir=${1:-out/driver-ab-quick}
cli=build/strandbench
[ -x "$cli" ] || { echo "driver-ab.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
rm -rf "$dir"
mkdir -p "$(dirname "$dir")" "$(dirname "$out")"
"$cli" driver-ab suites/quick.json --b mesa-25.0 --out "$dir" > "$dir.log"
python3 - "$dir" "$out" <<'PY'
import json, sys
d, out = sys.argv[1:]
ab = json.load(open(f"{d}/ab.json"))
pairs = ab["pairs"]
changed = [p for p in pairs if p.get("change", {}).get("max_abs", 0) > 0]
timed = [p for p in pairs if "time_ratio_b_over_a" in p]
verdicts = {}
for p in timed:
    v = p["time_ratio_b_over_a"]["verdict"]
    verdicts[v] = verdicts.get(v, 0) + 1
def g(x, n=3):  # significant digits, as text: "-" where the run has none
    return "-" if x is None else f"{x:.{n}g}"
data = {
    "folder": d,
    "a": ab["a"].get("version", "?"), "b": ab["b"].get("version", "?"),
    "pairs": len(pairs), "changed": len(changed), "identical": len(pairs) - len(changed),
    "work_same": sum(1 for p in pairs if p["a"].get("work") == p["b"].get("work")),
    "samples_same": sum(1 for p in pairs if p["a"].get("work", {}).get("samples_passed")
                        == p["b"].get("work", {}).get("samples_passed")),
    "timed": len(timed),
    "verdicts": [{"verdict": v, "count": n} for v, n in sorted(verdicts.items())],
    "changed_rows": [{
        "id": p["id"], "flip": g(p["change"]["flip_mean"]), "max_abs": g(p["change"]["max_abs"]),
        "pixels_over": p["change"]["pixels_over"],
        "rmse_a": g(p["a"].get("rmse_vs_reference"), 5), "rmse_b": g(p["b"].get("rmse_vs_reference"), 5),
        "samples_a": str(p["a"].get("work", {}).get("samples_passed", "-")),
        "samples_b": str(p["b"].get("work", {}).get("samples_passed", "-"))} for p in changed],
    "time_rows": [{
        "id": p["id"], "a_ms": g(p["a"].get("frame_ms")), "b_ms": g(p["b"].get("frame_ms")),
        "ratio": p["time_ratio_b_over_a"]["estimate"], "lo": p["time_ratio_b_over_a"]["ci95"][0],
        "hi": p["time_ratio_b_over_a"]["ci95"][1], "verdict": p["time_ratio_b_over_a"]["verdict"]}
        for p in sorted(timed, key=lambda p: p["time_ratio_b_over_a"]["estimate"])],
}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
print(f"wrote {out}: {len(pairs)} pairs, {len(changed)} changed")
PY
