#!/usr/bin/env bash
# vkhr (Jansson 2019, github.com/CaffeineViking/vkhr, MIT) beside strandbench on this machine's
# Vulkan driver: builds the user's vkhr checkout against Debian 12's packages (our CMake file
# and source fixes in scripts/peer-vkhr/, applied to a copy), then scripts/peer-vkhr.py writes
# matching scenes, runs vkhr's --benchmark mode and strandbench's matching render interleaved
# in rounds, and writes the run as data: into the docs' results store when run through
# scripts/docs-record.sh (docs/peer-vkhr-measured.md's blocks are rendered from it), else
# printed. docs/peers.md says more.
#
#   scripts/peer-vkhr.sh VKHR_SRC [peer-vkhr.py options: --rounds N --frames N --repeat N
#     --rows matched:640x360,thin:640x360,raymarch:320x180,... --hair FILE --alpha A
#     --json FILE]   (scripts/peer-vkhr.py --help says each)
#   scripts/docs-record.sh peer-vkhr scripts/peer-vkhr.sh VKHR_SRC ...   (the docs' run)
#
# VKHR_SRC: a vkhr source checkout (git clone https://github.com/CaffeineViking/vkhr; its
# submodules and large files are not needed). strandbench is not in it and it is not changed:
# the build is in build/peer-vkhr/. Needs build/strandbench (scripts/setup.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2; }
if [ $# -lt 1 ] || [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then
  usage
  exit 2
fi
src=$(cd "$1" 2>/dev/null && pwd) || { echo "peer-vkhr: $1: no such folder" >&2; exit 2; }
shift
for f in src/main.cc include/vkhr/benchmark.hh include/vkhr/rasterizer/interface.hh share/shaders; do
  if [ ! -e "$src/$f" ]; then
    echo "peer-vkhr: $src is not a vkhr checkout (no $f)" >&2
    exit 2
  fi
done
if [ ! -x build/strandbench ]; then
  echo "peer-vkhr: build/strandbench is missing: run scripts/setup.sh first" >&2
  exit 2
fi

# What vkhr's build and the run need, only what is missing (as scripts/setup.sh does).
packages=(build-essential cmake pkg-config python3 libvulkan-dev mesa-vulkan-drivers glslc
          libglm-dev libimgui-dev libtinyobjloader-dev libstb-dev nlohmann-json3-dev
          libglfw3-dev libembree-dev xvfb xauth)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "peer-vkhr: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# A fresh copy of the checkout with our fixes, built beside the last good one and swapped in
# only when it built: a failed build leaves nothing half made. Skipped when neither the
# checkout nor our files changed since the last build (the stamp).
work=$root/build/peer-vkhr
mkdir -p "$work"
stamp=$( (tar -C "$src" --exclude=.git --sort=name --mtime=0 -cf - . ; cat "$root"/scripts/peer-vkhr/*) | sha256sum | cut -d' ' -f1)
if [ ! -x "$work/src/_build/vkhr" ] || [ "$(cat "$work/src/.stamp" 2>/dev/null)" != "$stamp" ]; then
  echo "peer-vkhr: building vkhr from $src in $work/src (log: $work/build.log)"
  rm -rf "$work/src.new"
  mkdir "$work/src.new"
  tar -C "$src" --exclude=.git -cf - . | tar -C "$work/src.new" -xf -
  if ! (
    cd "$work/src.new"
    bash "$root/scripts/peer-vkhr/fixes.sh"
    cp "$root/scripts/peer-vkhr/CMakeLists.txt" CMakeLists.txt
    cp "$root/scripts/peer-vkhr/benchmark.hh" include/vkhr/benchmark.hh
    # The checkout's .spv files are large-file pointers: every shader compiled by its Makefile.
    for mk in share/shaders/*/Makefile; do make -s -B -C "$(dirname "$mk")"; done
    launcher=()
    if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
    cmake -S . -B _build -DCMAKE_BUILD_TYPE=Release "${launcher[@]}"
    cmake --build _build -j "$(nproc 2>/dev/null || echo 2)"
  ) > "$work/build.log" 2>&1; then
    tail -20 "$work/build.log" >&2
    echo "peer-vkhr: building vkhr failed (above; $work/build.log); the last good build is kept" >&2
    exit 1
  fi
  echo "$stamp" > "$work/src.new/.stamp"
  rm -rf "$work/src"
  mv "$work/src.new" "$work/src"
fi

commit=$(git -C "$src" rev-parse --short HEAD 2>/dev/null || echo "unknown (not a git checkout)")
exec python3 "$root/scripts/peer-vkhr.py" --vkhr "$work/src/_build/vkhr" --vkhr-root "$work/src" \
  --vkhr-commit "$commit" --work "$work/run" "$@"
