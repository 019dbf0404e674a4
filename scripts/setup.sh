#!/usr/bin/env bash
# Installs what strandbench needs on Debian 12, only what is missing, then
# configures and builds into build/ (the CLI lands at build/strandbench).
# Usage: scripts/setup.sh [extra cmake args...]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git
  libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri libosmesa6
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  glslang-dev glslang-tools libglfw3-dev libglm-dev
  xvfb xauth
  libopenimageio-dev openimageio-tools libcli11-dev nlohmann-json3-dev libtinyobjloader-dev
  libgtest-dev googletest
  clang libclang-rt-14-dev llvm
  chromium
  slurm-wlm munge
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j "$jobs"
