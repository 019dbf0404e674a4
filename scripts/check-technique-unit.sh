#!/usr/bin/env bash
# The copy-a-folder acceptance check (a technique is its folder): a copy of techniques/wboit as
# techniques/wboit_copy, with its file, class and descriptor names changed by
# sed and nothing else edited, builds in a scratch copy of the tree, appears in
# `strandbench list`, renders on GL and Vulkan and is accepted by a suite.
#   scripts/check-technique-unit.sh [BUILD_DIR]   (default build/; it must be built)
# Only the new folder, the embedded shaders and main.cpp are compiled: the rest
# is linked from BUILD_DIR's libraries (cmake/PrebuiltUnits.cmake).
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
[ -f "$build/libsb_techniques.a" ] || { echo "check-technique-unit: build $build first" >&2; exit 2; }
scratch=$(mktemp -d /tmp/strandbench-unit-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$scratch"' EXIT
# The sources only (no builds, baselines or history).
tar --exclude=./build --exclude='./build-*' --exclude=./.git --exclude=./baselines -cf - . |
  tar -xf - -C "$scratch"

# The copy: files renamed, then the folder's names changed; nothing else edited.
src=$scratch/techniques/wboit
dst=$scratch/techniques/wboit_copy
cp -r "$src" "$dst"
for f in "$dst"/wboit*; do mv "$f" "$dst/wboit_copy${f##*/wboit}"; done
sed -i -e 's/wboit/wboit_copy/g' -e 's/WBOIT/WBOIT_COPY/g' \
  -e 's/WeightedBlendedOit/WeightedBlendedCopyOit/g' "$dst"/*

cmake -S "$scratch" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release -DSB_PREBUILT_DIR="$build" \
  -DSB_UNIT_FOLDERS=wboit_copy ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} \
  >"$scratch/configure.log" || { cat "$scratch/configure.log"; exit 1; }
cmake --build "$scratch/build" -j"$(nproc)" >"$scratch/build.log" || { cat "$scratch/build.log"; exit 1; }
bin=$scratch/build/strandbench

"$bin" list >"$scratch/list.txt"
grep -q '^  wboit_copy ' "$scratch/list.txt" || { echo "wboit_copy is not in strandbench list" >&2; exit 1; }
"$bin" list wboit_copy
for backend in gl vulkan; do
  "$bin" render --backend "$backend" --scene curly:strands=50 --size 32x32 --shadow none \
    --oit wboit_copy --out "$scratch/copy.$backend.png"
done
cat >"$scratch/unit.json" <<'JSON'
{
  "name": "unit",
  "description": "one case of the copied technique",
  "defaults": {"scene": "curly:strands=50", "size": "32x32", "repeat": 1, "warmup": 0},
  "groups": [{"name": "copy", "axes": {"oit": ["wboit_copy"], "backend": ["gl", "vulkan"]}}]
}
JSON
"$bin" sweep "$scratch/unit.json" --out "$scratch/sweep"
echo "check-technique-unit: wboit_copy builds, lists, renders on gl and vulkan and runs in a suite"
