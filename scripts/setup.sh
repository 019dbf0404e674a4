#!/usr/bin/env bash
# Installs what strandbench needs on Debian 12, only what is missing, then configures and
# builds into build/ (the CLI lands at build/strandbench).
# Usage: scripts/setup.sh [--tests] [extra cmake args...]
#   (default)  the packages of the strandbench target; builds only that target
#   --tests    also what the tests need (Xvfb, Vulkan's validation layers, clang for the
#              fuzzers, Chromium for the report pages, Slurm) and builds every target
# Both configure build/ the same way (tests included, warnings as errors), so the test
# command rebuilds nothing the main command built. A compiler that warns where Debian 12's
# GCC 12 does not: add -DSB_WERROR=OFF.
set -euo pipefail
cd "$(dirname "$0")/.."

tests=0
if [ "${1:-}" = "--tests" ]; then
  tests=1
  shift
fi

# The strandbench target: compilers, GL (EGL, OSMesa) and Vulkan drivers and headers, the
# shader compiler and the libraries it links (GoogleTest: the build folder is configured
# with the tests, though the main command does not build them). glslang-tools and
# openimageio-tools only because glslang's and OpenImageIO's CMake configs import their
# programs: configure fails without them. libstb-dev: stb_easy_font.h, the viewer's overlay text.
# libembree-dev: Embree 3, the ray tracing of the CPU strand references (pbr/).
packages=(
  build-essential cmake pkg-config git
  libegl-dev libegl-mesa0 libgl-dev libgl1-mesa-dri libosmesa6
  libvulkan-dev mesa-vulkan-drivers
  glslang-dev glslang-tools libglfw3-dev libglm-dev
  libopenimageio-dev openimageio-tools libcli11-dev nlohmann-json3-dev libtinyobjloader-dev
  libgtest-dev fonts-dejavu-core libstb-dev libembree-dev
)
if ((tests)); then
  packages+=(
    vulkan-validationlayers xvfb xauth googletest
    clang libclang-rt-14-dev llvm
    chromium
    slurm-wlm munge
  )
fi
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

if ((tests)); then scripts/drivers.sh; fi  # Mesa 25.0 beside the system's, for tests/test_drivers.cpp
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSB_WERROR=ON "$@" >/dev/null
if ((tests)); then
  cmake --build build -j "$jobs"
else
  cmake --build build -j "$jobs" --target strandbench
fi
