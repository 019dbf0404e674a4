#!/usr/bin/env bash
# Records one run into the results store the docs are rendered from (docs/measured-pages.md):
# runs COMMAND with SB_DOCS_RESULTS naming the JSON file it must write, then keeps that file
# as docs/results/NAME/results.json beside meta.json (the command, the commit, the date, the
# machine, the driver and the load average before and after). Refused on a tree with
# uncommitted changes outside docs/ and README.md (the commit must be the code that ran). docs/results/NAME/blocks.json
# (the templates, written by hand) is left as it is; `build/strandbench docs refresh` then
# renders the pages' blocks.
# Usage: scripts/docs-record.sh NAME COMMAND [ARGS...]
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -ge 2 ] || { echo "usage: scripts/docs-record.sh NAME COMMAND [ARGS...]" >&2; exit 2; }
name=$1
shift
case $name in
  */* | .* | "") echo "docs-record.sh: '$name': a run's name is one folder name" >&2; exit 2 ;;
esac
# docs/ and README.md aside: they are what the runs write (so runs can be recorded one after
# another, as scripts/docs-refresh-stale.sh does), not code that runs.
code=(-- . ':!docs' ':!README.md')
if [ -n "$(git status --porcelain --untracked-files=no "${code[@]}")" ]; then
  echo "docs-record.sh: the tree has uncommitted changes; commit them first (the docs cite only" \
       "runs of a clean commit):" >&2
  git status --short --untracked-files=no "${code[@]}" >&2
  exit 2
fi
dir=docs/results/$name
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
commit=$(git rev-parse HEAD)
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
SB_DOCS_RESULTS="$tmp/results.json" "$@"
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
[ -s "$tmp/results.json" ] || { echo "docs-record.sh: '$*' wrote no \$SB_DOCS_RESULTS" >&2; exit 2; }
# The code must not have moved under the run (a commit or an edit while it ran).
if [ "$(git rev-parse HEAD)" != "$commit" ] || [ -n "$(git status --porcelain --untracked-files=no "${code[@]}")" ]; then
  echo "docs-record.sh: the tree changed while the run ran; nothing recorded" >&2
  exit 2
fi
driver=""
if [ -x build/strandbench ]; then
  # The default driver's headless devices, as `strandbench --version` lists them:
  # "gl (egl): DEVICE; VERSION; ..." -> "gl: DEVICE, VERSION".
  driver=$(build/strandbench --version 2>/dev/null |
    awk '/\(this process\):$/ {on = 1; next} on && /^[^ ]/ {on = 0}
         on && /^ *(gl \(egl\)|vulkan \(headless\)):/ {
           sub(/^ +/, ""); sub(/ \([a-z]+\):/, ":"); n = split($0, f, "; ");
           printf "%s%s, %s", sep, f[1], f[2]; sep = "; "}')
fi
python3 - "$tmp" "$dir" "$commit" "$load_before" "$load_after" "$driver" "$@" <<'PY'
import json, os, sys, datetime, shlex
tmp, out, commit, load0, load1, driver, *cmd = sys.argv[1:]
results = json.load(open(os.path.join(tmp, "results.json")))  # must be JSON
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")),
           None)
mem = next((int(l.split()[1]) for l in open("/proc/meminfo") if l.startswith("MemTotal")), 0)
meta = {
    "command": " ".join(shlex.quote(c) for c in cmd),
    "commit": commit,
    "dirty": False,
    "date": f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC",
    "machine": {"cpu": cpu, "cores": os.cpu_count(), "memory_gib": round(mem / 2**20, 1)},
    "driver": driver or None,
    "load_before": load0,
    "load_after": load1,
}
os.makedirs(out, exist_ok=True)
for name, doc in (("results.json", results), ("meta.json", meta)):
    with open(os.path.join(out, name + ".tmp"), "w") as f:
        json.dump(doc, f, indent=1, sort_keys=False)
        f.write("\n")
    os.replace(os.path.join(out, name + ".tmp"), os.path.join(out, name))
print(f"docs-record.sh: recorded {out} (commit {commit[:7]})")
PY
