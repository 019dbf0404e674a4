#!/usr/bin/env bash
# Driver A/B on the quick suite: the system's Mesa against Mesa 25.0.7 (scripts/drivers.sh),
# each in its own process, with the triage page (OUT/ab.html). Writes
# docs/driver-ab-measured.md (or the file given): what changed, headed by the command,
# commit, date and load that made it.
# Usage: scripts/driver-ab.sh [OUT.md] [FOLDER]   Needs build/strandbench and drivers/mesa-25.0.
set -euo pipefail
cd "$(dirname "$0")/.."
md=${1:-docs/driver-ab-measured.md}
dir=${2:-out/driver-ab-quick}
cli=build/strandbench
[ -x "$cli" ] || { echo "driver-ab.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
rm -rf "$dir"
mkdir -p "$(dirname "$dir")"
"$cli" driver-ab suites/quick.json --b mesa-25.0 --out "$dir" > "$dir.log"
python3 - "$dir" "$md" "$load_before" "$(cut -d' ' -f1-3 /proc/loadavg)" <<'PY'
import json, subprocess, sys, datetime, platform
d, md, load0, load1 = sys.argv[1:]
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
ab = json.load(open(f"{d}/ab.json"))
pairs = ab["pairs"]
changed = [p for p in pairs if p.get("change", {}).get("max_abs", 0) > 0]
timed = [p for p in pairs if "time_ratio_b_over_a" in p]
verdicts = {}
for p in timed:
    v = p["time_ratio_b_over_a"]["verdict"]
    verdicts[v] = verdicts.get(v, 0) + 1
work_same = sum(1 for p in pairs if p["a"].get("work") == p["b"].get("work"))
samples_same = sum(1 for p in pairs if p["a"].get("work", {}).get("samples_passed") == p["b"].get("work", {}).get("samples_passed"))
def f(x, n=3):
    return "-" if x is None else f"{x:.{n}g}"
L = [f"<!-- written by scripts/driver-ab.sh on {commit}, {datetime.date.today()}, "
     f"{platform.node()}, load {load0} before, {load1} after; do not edit by hand -->",
     "# Driver A/B on the quick suite: Mesa 22.3.6 (system) against Mesa 25.0.7", "",
     f"`scripts/driver-ab.sh` ran `strandbench driver-ab suites/quick.json --b mesa-25.0 --out {d}` "
     f"on commit {commit} ({datetime.date.today()}, load {load0} before, {load1} after). "
     f"A: {ab['a'].get('version','?')}; B: {ab['b'].get('version','?')}.", "",
     f"- {len(pairs)} cases paired; **{len(changed)} with a changed image** (8-bit PNGs), "
     f"{len(pairs) - len(changed)} identical.",
     f"- Work counters identical in {work_same} of {len(pairs)} cases; samples passed identical in "
     f"{samples_same}. Fragment invocations differ by design: Mesa 25 counts them after the "
     "depth test (docs/work-counters.md).",
     f"- Frame time, B over A (unpaired 95% intervals: the two sweeps ran one after the other): "
     + ", ".join(f"{n} {v}" for v, n in sorted(verdicts.items())) + f" of {len(timed)} timed cases.", ""]
L += ["## Cases whose image changed, largest first", "",
      "| case | FLIP B vs A | max abs | pixels over 1/255 | RMSE vs reference, A | B | samples passed A | B |",
      "|---|---:|---:|---:|---:|---:|---:|---:|"]
for p in changed:
    c = p["change"]
    L.append(f"| {p['id']} | {f(c['flip_mean'])} | {f(c['max_abs'])} | {c['pixels_over']} | "
             f"{f(p['a'].get('rmse_vs_reference'), 5)} | {f(p['b'].get('rmse_vs_reference'), 5)} | "
             f"{p['a'].get('work', {}).get('samples_passed', '-')} | {p['b'].get('work', {}).get('samples_passed', '-')} |")
if not changed:
    L.append("| (none) | | | | | | | |")
L += ["", "## Frame time, B over A", "",
      "| case | A ms | B ms | B/A [95%] | verdict |", "|---|---:|---:|---|---|"]
for p in sorted(timed, key=lambda p: p["time_ratio_b_over_a"]["estimate"]):
    t = p["time_ratio_b_over_a"]
    L.append(f"| {p['id']} | {f(p['a'].get('frame_ms'))} | {f(p['b'].get('frame_ms'))} | "
             f"{f(t['estimate'])} [{f(t['ci95'][0])}, {f(t['ci95'][1])}] | {t['verdict']} |")
open(md, "w").write("\n".join(L) + "\n")
print(f"wrote {md}: {len(pairs)} pairs, {len(changed)} changed")
PY
