#!/usr/bin/env bash
# The copy-a-folder acceptance check (a unit is its folder): copies of a shadow technique
# (techniques/voxel as voxel_copy), a transparency technique (wboit as wboit_copy), a shading
# model (marschner as marschner_copy) and a scene generator (scenes/generators/stray as
# streak), each with its file, class and descriptor names changed by sed and nothing else
# edited, build in a scratch copy of the tree, appear in `strandbench list`, render on GL and
# Vulkan (the model's and the scene's copies the same image as their originals), are accepted
# by a suite, and run the tests they carry (<folder>/test_*.cpp).
#   scripts/check-technique-unit.sh [BUILD_DIR]   (default build/; it must be built)
# Only the new folders, their tests, the embedded shaders and main.cpp are compiled: the rest
# is linked from BUILD_DIR's libraries (cmake/PrebuiltUnits.cmake).
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
[ -f "$build/libsb_techniques.a" ] || { echo "check-technique-unit: build $build first" >&2; exit 2; }
scratch=$(mktemp -d /tmp/strandbench-unit-XXXXXX)
trap '[ -n "${KEEP:-}" ] || rm -rf "$scratch"' EXIT
# The sources only (no builds, baselines or history).
tar --exclude=./build --exclude='./build-*' --exclude=./.git --exclude=./baselines \
  --exclude=./drivers -cf - . | tar -xf - -C "$scratch"

# copy ROOT FOLDER NEW SED...: ROOT/FOLDER copied as ROOT/NEW, its files renamed (FOLDER ->
# NEW in the name), then its names changed by the sed expressions; nothing else edited.
copy_unit() {
  local root=$scratch/$1 from=$2 to=$3
  shift 3
  cp -r "$root/$from" "$root/$to"
  for f in "$root/$to"/*"$from"*; do
    [ -e "$f" ] || continue
    local name=${f##*/}
    mv "$f" "$root/$to/${name//$from/$to}"
  done
  sed -i "$@" "$root/$to"/*
}
copy() { copy_unit techniques "$@"; }
copy voxel voxel_copy -e 's/voxel/voxel_copy/g' -e 's/Voxel/VoxelCopy/g' -e 's/VOXEL/VOXEL_COPY/g'
copy wboit wboit_copy -e 's/wboit/wboit_copy/g' -e 's/WBOIT/WBOIT_COPY/g' \
  -e 's/WeightedBlendedOit/WeightedBlendedCopyOit/g'
copy marschner marschner_copy -e 's/marschner/marschner_copy/g' -e 's/Marschner/MarschnerCopy/g' \
  -e 's/MARSCHNER/MARSCHNER_COPY/g'
copy_unit scenes/generators stray streak -e 's/stray/streak/g' -e 's/Stray/Streak/g'

cmake -S "$scratch" -B "$scratch/build" -DCMAKE_BUILD_TYPE=Release -DSB_PREBUILT_DIR="$build" \
  "-DSB_UNIT_FOLDERS=voxel_copy;wboit_copy;marschner_copy" -DSB_SCENE_UNIT_FOLDERS=streak \
  ${CMAKE_CXX_COMPILER_LAUNCHER:+-DCMAKE_CXX_COMPILER_LAUNCHER=$CMAKE_CXX_COMPILER_LAUNCHER} \
  >"$scratch/configure.log" || { cat "$scratch/configure.log"; exit 1; }
cmake --build "$scratch/build" -j"$(nproc)" >"$scratch/build.log" || { cat "$scratch/build.log"; exit 1; }
bin=$scratch/build/strandbench

"$bin" list >"$scratch/list.txt"
for name in voxel_copy wboit_copy marschner_copy streak; do
  grep -q "^  $name " "$scratch/list.txt" || { echo "$name is not in strandbench list" >&2; exit 1; }
done
for name in voxel_copy wboit_copy marschner_copy; do "$bin" list "$name"; done
for backend in gl vulkan; do
  render() {
    "$bin" render --backend "$backend" --scene curly:strands=50 --size 32x32 "$@"
  }
  render --shadow voxel_copy --oit wboit_copy --out "$scratch/copy.$backend.png"
  # The model's copy is the model: the same pixels.
  render --shading marschner --out "$scratch/model.$backend.png"
  render --shading marschner_copy --out "$scratch/model_copy.$backend.png"
  cmp "$scratch/model.$backend.png" "$scratch/model_copy.$backend.png" ||
    { echo "marschner_copy renders otherwise than marschner on $backend" >&2; exit 1; }
  # The scene's copy is the scene.
  for scene in stray streak; do
    "$bin" render --backend "$backend" --scene "$scene:strands=50" --size 32x32 \
      --out "$scratch/scene.$scene.$backend.png"
  done
  cmp "$scratch/scene.stray.$backend.png" "$scratch/scene.streak.$backend.png" ||
    { echo "streak renders otherwise than stray on $backend" >&2; exit 1; }
done
cat >"$scratch/unit.json" <<'JSON'
{
  "name": "unit",
  "description": "one case of the copied units",
  "defaults": {"scene": "curly:strands=50", "size": "32x32", "repeat": 1, "warmup": 0},
  "groups": [{"name": "copy", "axes": {"shadow": ["voxel_copy"], "oit": ["wboit_copy"],
                                       "shading": ["marschner_copy"], "backend": ["gl", "vulkan"]}}]
}
JSON
"$bin" sweep "$scratch/unit.json" --out "$scratch/sweep"

# The copies' own tests, and nothing but theirs.
tests=$scratch/build/sb_unit_tests
"$tests" --gtest_list_tests >"$scratch/tests.txt"
for suite in VoxelCopyMath MarschnerCopyShading SceneStreak; do
  grep -q "^$suite\." "$scratch/tests.txt" || { echo "the copy's $suite tests were not built" >&2; exit 1; }
done
if grep -q "^\(VoxelMath\|MarschnerShading\|SceneStray\)\." "$scratch/tests.txt"; then
  echo "the originals' tests were built into the copies' test program" >&2
  exit 1
fi
(cd "$scratch" && "$tests")
echo "check-technique-unit: voxel_copy, wboit_copy, marschner_copy and the scene streak build," \
  "list, render on gl and vulkan, run in a suite and pass their copied tests"
