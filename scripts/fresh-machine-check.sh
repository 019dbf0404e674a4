#!/usr/bin/env bash
# The honest test of the install: builds a clean Debian 12 root with mmdebstrap, copies the
# committed tree into it (git archive HEAD: what a clone gets, nothing from the working tree)
# and runs the README's two commands in it exactly as written, as a new user would:
#   scripts/main-job.sh   then   scripts/test.sh
# A green CI on a developer's machine cannot show a missing install step; this can.
#
# Usage: scripts/fresh-machine-check.sh [--quick] [--tests REGEX] [--keep] [--root DIR]
#   --quick        the main job, then only the tests matching --tests (default: a named
#                  subset, below) instead of the full test command; for when time is short
#   --keep         keep the root afterwards (printed), e.g. to look inside
#   --root DIR     where to build the root (default: a new folder under /var/tmp)
# Needs root (mmdebstrap in root mode, chroot, mounts); installs mmdebstrap when missing.
# Prints each step with its time and ends with one line:
#   fresh machine: OK      or      fresh machine: FAILED at STEP
# The test command's whole log is kept in /var/tmp/sb-fresh-test.log.
# Exit 0 or 1 (2 for bad arguments). Not part of CI: run it before submitting a change to
# dependencies, CMake, setup or test scripts (README, "A fresh machine").
set -uo pipefail
cd "$(dirname "$0")/.."

quick=0
keep=0
root=""
# The quick subset: the CLI end to end, loaders, the device on both APIs, reports in Chromium.
tests='^(Cli|Loader|Device|Report|ReportBrowser|Check)'
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --keep) keep=1 ;;
    --tests) tests=${2:?--tests needs a regular expression}; shift ;;
    --root) root=${2:?--root needs a folder}; shift ;;
    -h | --help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fresh-machine-check: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if [ "$(id -u)" -ne 0 ]; then
  echo "fresh-machine-check: needs root (mmdebstrap, chroot and mounts)" >&2
  exit 2
fi

start=$(date +%s)
current="start"
declare -A took  # seconds per step, for the stored run (docs/results/fresh-machine)
step() {  # step NAME COMMAND...: runs it, prints its time; stops the script at the first failure
  current=$1
  shift
  local t0=$(date +%s)
  echo "== $current"
  if "$@"; then
    took[$current]=$(($(date +%s) - t0))
    echo "== $current: done in ${took[$current]} s"
  else
    echo "== $current: FAILED after $(($(date +%s) - t0)) s"
    echo "fresh machine: FAILED at $current"
    exit 1
  fi
}

mounted=()
cleanup() {
  local status=$?
  if [ -n "$root" ] && [ -d "$root" ]; then
    # The test log outlives the root, so a failure can be read after it is removed.
    [ -s "$root/root/test.log" ] && cp "$root/root/test.log" /var/tmp/sb-fresh-test.log &&
      echo "fresh-machine-check: the test command's log is in /var/tmp/sb-fresh-test.log"
    # Processes left inside the root (a server a test started) would keep its mounts busy.
    for p in /proc/[0-9]*; do
      [ "$(readlink "$p/root" 2>/dev/null)" = "$root" ] && kill -9 "${p#/proc/}" 2>/dev/null
    done
    for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
      umount -R "${mounted[$i]}" 2>/dev/null || umount -l "${mounted[$i]}" 2>/dev/null
    done
    if ((keep)); then
      echo "fresh-machine-check: the root is kept in $root"
    elif ! findmnt -R "$root" >/dev/null 2>&1; then
      rm -rf --one-file-system "$root"
    else
      echo "fresh-machine-check: $root still has mounts; not removed" >&2
    fi
  fi
  exit "$status"
}
trap cleanup EXIT
trap 'echo; echo "fresh machine: FAILED at $current (interrupted)"; exit 1' INT TERM

install_mmdebstrap() {
  command -v mmdebstrap >/dev/null && return 0
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq mmdebstrap
}

# A minimal Debian 12 (minbase: apt, dpkg, bash, coreutils; no compiler, no git, no sudo).
build_root() {
  mmdebstrap --quiet --variant=minbase bookworm "$root" \
    "deb http://deb.debian.org/debian bookworm main" \
    "deb http://deb.debian.org/debian bookworm-updates main" \
    "deb http://deb.debian.org/debian-security bookworm-security main"
}

copy_tree() {
  mkdir -p "$root/root/strandbench"
  git archive --format=tar "$commit" | tar -x -C "$root/root/strandbench"
  cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
}

mount_system() {
  mount -t proc proc "$root/proc" && mounted+=("$root/proc") &&
    mount --rbind /dev "$root/dev" && mount --make-rslave "$root/dev" && mounted+=("$root/dev") &&
    mount --rbind /sys "$root/sys" && mount --make-rslave "$root/sys" && mounted+=("$root/sys") &&
    mount -t tmpfs tmpfs "$root/tmp" && mounted+=("$root/tmp")
}

# Inside the root, as a new user would type it: a login shell in the tree.
inside() {
  chroot "$root" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    bash -c "cd /root/strandbench && $1"
}

if [ -z "$root" ]; then
  root=$(mktemp -d /var/tmp/sb-fresh.XXXXXX)
  rmdir "$root"  # mmdebstrap wants to create it (or find it empty)
elif [ -e "$root" ] && [ -n "$(ls -A "$root" 2>/dev/null)" ]; then
  echo "fresh-machine-check: --root $root is not empty" >&2
  root=""
  exit 2
fi
root=$(realpath -m "$root")
# The commit tested, fixed now: HEAD may move while the check runs (about 25 minutes).
commit=$(git rev-parse HEAD)
echo "fresh-machine-check: commit ${commit:0:7} in $root"
[ -z "$(git status --porcelain --untracked-files=no)" ] ||
  echo "fresh-machine-check: note: uncommitted changes are not part of the check (git archive HEAD)"

step "install mmdebstrap" install_mmdebstrap
step "build a Debian 12 root" build_root
step "copy the committed tree" copy_tree
step "mount /proc /dev /sys" mount_system
# The run kept in the results store (docs/results/fresh-machine: results.json and meta.json),
# by a full run that passed; `strandbench docs refresh` renders it into the README's and
# docs/testing.md's fresh-machine blocks: its numbers come from the run, never from a hand.
# The tree that ran is `git archive HEAD`, so the commit is a clean one by construction.
write_store_entry() {
  local log=$root/root/test.log
  local ctest_line skips
  # The first summary is the test suite's; the last one is the fuzzers'.
  ctest_line=$(grep -E "tests passed|tests failed" "$log" | head -n 1)
  skips=$(sed -n '/^== skipped tests:/,/^== slowest/p' "$log" | sed '1s/^== //;$d' | sed 's/^ *//' |
    paste -sd ';' | sed 's/;/; /g')
  python3 - "$commit" "$load0" "$(cut -d' ' -f1-3 /proc/loadavg)" "$ctest_line" "$skips" \
    "${took["README main command (scripts/main-job.sh)"]}" \
    "${took["README test command (scripts/test.sh)"]}" "$log" <<'PY'
import json, os, re, sys, datetime
commit, load0, load1, ctest, skips, main_s, test_s, log = sys.argv[1:]
# test-report.sh's slowest tests ("== slowest tests (seconds)", then "  SECONDS  NAME" lines)
# and its skips by reason ("  COUNT REASON" lines after "== skipped tests: N").
slowest, skipped, section = [], [], None
for line in open(log, errors="replace"):
    if line.startswith("=="):
        section = ("slowest" if line.startswith("== slowest tests") else
                   "skips" if line.startswith("== skipped tests") else None)
        continue
    m = re.match(r"^\s*([0-9.]+)\s+(\S+)\s*$", line)
    if section == "slowest" and m:
        slowest.append({"seconds": float(m.group(1)), "test": m.group(2)})
    m = re.match(r"^\s*([0-9]+) (.+?)\s*$", line)
    if section == "skips" and m:
        skipped.append({"count": int(m.group(1)), "reason": m.group(2)})
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), None)
mem = next((int(l.split()[1]) for l in open("/proc/meminfo") if l.startswith("MemTotal")), 0)
out = "docs/results/fresh-machine"
os.makedirs(out, exist_ok=True)
docs = {
    "results.json": {"main_s": int(main_s), "test_s": int(test_s), "ctest": ctest, "skips": skips,
                     "slowest": slowest, "skipped": skipped},
    "meta.json": {"command": "sudo scripts/fresh-machine-check.sh", "commit": commit, "dirty": False,
                  "date": f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC",
                  "machine": {"cpu": cpu, "cores": os.cpu_count(), "memory_gib": round(mem / 2**20, 1)},
                  "driver": None, "load_before": load0, "load_after": load1},
}
for name, doc in docs.items():
    with open(os.path.join(out, name + ".tmp"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    os.replace(os.path.join(out, name + ".tmp"), os.path.join(out, name))
PY
  if [ -x build/strandbench ]; then
    build/strandbench docs refresh
    echo "fresh-machine-check: docs/results/fresh-machine and the pages' blocks rewritten (commit them)"
  else
    echo "fresh-machine-check: docs/results/fresh-machine rewritten: run build/strandbench docs refresh and commit"
  fi
}

load0=$(cut -d' ' -f1-3 /proc/loadavg)
step "README main command (scripts/main-job.sh)" inside "scripts/main-job.sh"
step "main command wrote its report" test -s "$root/root/strandbench/out/quick/report.html"
if ((quick)); then
  step "tests matching $tests (--quick)" \
    inside "scripts/setup.sh --tests && cd build && ctest --output-on-failure -j \"\$(nproc)\" -R '$tests' 2>&1 | tail -n 40; exit \${PIPESTATUS[0]}"
else
  step "README test command (scripts/test.sh)" \
    inside "scripts/test.sh >/root/test.log 2>&1; s=\$?; tail -n 60 /root/test.log
      # The tail may hold only the skips and the fuzzers: name the failed tests too.
      sed -n '/The following tests FAILED/,/^Errors while running/p' /root/test.log; exit \$s"
  write_store_entry
fi
echo "== total: $(($(date +%s) - start)) s"
echo "fresh machine: OK"
