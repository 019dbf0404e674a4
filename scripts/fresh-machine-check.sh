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
declare -A took  # seconds per step, for the README's block
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
# The README's block between the fresh-machine markers, rewritten by a full run that passed:
# its numbers come from the run that measured them, never from a hand.
write_readme_block() {
  local log=$root/root/test.log
  local ctest_line skips
  # The first summary is the test suite's; the last one is the fuzzers'.
  ctest_line=$(grep -E "tests passed|tests failed" "$log" | head -n 1)
  skips=$(sed -n '/^== skipped tests:/,/^== slowest/p' "$log" | sed '1s/^== //;$d' | sed 's/^ *//' |
    paste -sd ';' | sed 's/;/; /g')
  local block
  block=$(
    cat <<TXT
Measured by \`sudo scripts/fresh-machine-check.sh\` on commit ${commit:0:7}, $(date -u '+%Y-%m-%d %H:%M') UTC,
$(nproc) cores, load average $load0 before it started: the main command took
${took["README main command (scripts/main-job.sh)"]} s (report written), the test command
${took["README test command (scripts/test.sh)"]} s (ctest: "$ctest_line"; $skips; the fuzzers
included).
TXT
  )
  awk -v block="$block" '
    /^<!-- fresh-machine:begin/ {print; print block; skip=1; next}
    /^<!-- fresh-machine:end/ {skip=0}
    !skip {print}' README.md >README.md.new && mv README.md.new README.md
  echo "fresh-machine-check: README.md's measured block rewritten (commit it)"
}

load0=$(cut -d' ' -f1 /proc/loadavg)
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
  write_readme_block
fi
echo "== total: $(($(date +%s) - start)) s"
echo "fresh machine: OK"
