#!/usr/bin/env bash
# Fetches Mesa 25.0 from Debian's bookworm-backports and unpacks it beside the system's Mesa,
# never over it, so `strandbench --driver mesa-25.0` can select it (docs/drivers.md).
# Usage: scripts/drivers.sh [DEST]   (DEST defaults to drivers/ in the repository root)
# Leaves DEST/mesa-25.0/root (the unpacked packages) and, beside it, loader files with
# absolute paths: lvp_icd.x86_64.json (Vulkan), 50_mesa.json (EGL) and env.sh (the variables
# that select this driver). Does nothing when DEST/mesa-25.0 is already complete.
# The system's apt configuration is left alone: a private sources list, package lists and
# cache under DEST/.apt only download; nothing is installed.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
dest="${1:-$repo/drivers}"
mkdir -p "$dest"
dest="$(cd "$dest" && pwd)"

name=mesa-25.0
version_prefix="25.0."
suite=bookworm-backports
packages=(
  mesa-vulkan-drivers libegl-mesa0 mesa-libgallium libgbm1 libgl1-mesa-dri libosmesa6
  libdrm2 libdrm-amdgpu1 libdrm-intel1
)
dir="$dest/$name"
root="$dir/root"
lib="$root/usr/lib/x86_64-linux-gnu"

fail() {
  echo "drivers.sh: $*" >&2
  exit 1
}

# Complete when every loader file is there and names libraries that exist; the stamp is
# written last, so an interrupted run is redone.
complete() {
  [ -f "$dir/complete" ] && [ -f "$dir/lvp_icd.x86_64.json" ] && [ -f "$dir/50_mesa.json" ] &&
    [ -f "$dir/env.sh" ] && [ -f "$lib/libvulkan_lvp.so" ] && [ -f "$lib/libEGL_mesa.so.0" ] &&
    [ -f "$lib/libOSMesa.so.8" ]
}
if complete; then
  echo "drivers.sh: $dir is complete ($(cat "$dir/complete")); nothing to do"
  exit 0
fi

for tool in apt-get dpkg-deb; do
  command -v "$tool" >/dev/null || fail "needs $tool (Debian's apt and dpkg)"
done

# A private apt: only the backports suite, its own lists and cache; the system's trusted
# keys (debian-archive-keyring) check the suite's signature.
apt_dir="$dest/.apt"
mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial" "$apt_dir/etc"
echo "deb http://deb.debian.org/debian $suite main" >"$apt_dir/etc/sources.list"
: >"$apt_dir/status"
apt_opts=(
  -o "Dir::Etc::SourceList=$apt_dir/etc/sources.list"
  -o "Dir::Etc::SourceParts=/dev/null"
  -o "Dir::Etc::Preferences=/dev/null"
  -o "Dir::Etc::PreferencesParts=/dev/null"
  -o "Dir::State::Lists=$apt_dir/lists"
  -o "Dir::State::status=$apt_dir/status"
  -o "Dir::Cache=$apt_dir/cache"
  -o "Debug::NoLocking=1"
  -o "APT::Sandbox::User=$(id -un)"
  -o "APT::Architecture=amd64"
  -o "APT::Architectures::=amd64"
)
echo "drivers.sh: reading $suite's package lists"
apt-get -q "${apt_opts[@]}" update >"$apt_dir/update.log" 2>&1 ||
  fail "apt-get update of $suite failed (network?); see $apt_dir/update.log:
$(tail -5 "$apt_dir/update.log")"

debs="$dir/debs"
mkdir -p "$debs"
for p in "${packages[@]}"; do
  v="$(apt-cache "${apt_opts[@]}" show "$p/$suite" 2>/dev/null | sed -n 's/^Version: //p' | head -1)"
  [ -n "$v" ] || fail "$suite has no package $p"
  case "$p" in
    mesa-* | libegl-mesa0 | libgbm1 | libgl1-mesa-dri | libosmesa6)
      [[ "$v" == "$version_prefix"* ]] || fail "$suite has $p $v, not Mesa ${version_prefix}x"
      ;;
  esac
  if ! ls "$debs/${p}_"*.deb >/dev/null 2>&1; then
    echo "drivers.sh: downloading $p $v"
    (cd "$debs" && apt-get -q "${apt_opts[@]}" download "$p=$v" >>"$apt_dir/download.log" 2>&1) ||
      fail "downloading $p=$v failed; see $apt_dir/download.log"
  fi
done

rm -rf "$root"
mkdir -p "$root"
for deb in "$debs"/*.deb; do
  dpkg-deb -x "$deb" "$root" || fail "unpacking $deb failed"
done
mesa_version="$(dpkg-deb -f "$debs"/mesa-vulkan-drivers_*.deb Version)"

for f in libvulkan_lvp.so libEGL_mesa.so.0 libOSMesa.so.8 'libgallium-*.so'; do
  # shellcheck disable=SC2086 # $f may be a pattern (libgallium's name has the version)
  ls "$lib"/$f >/dev/null 2>&1 || fail "the unpacked packages lack $lib/$f"
done

# Every library the drivers link must resolve from the unpacked tree or the system: a
# library missing here would only show up as a driver that silently fails to load.
missing="$(for f in "$lib"/libvulkan_lvp.so "$lib"/libEGL_mesa.so.0 "$lib"/libOSMesa.so.8 \
  "$lib"/libgallium-*.so "$lib"/libgbm.so.1; do
  LD_LIBRARY_PATH="$lib" ldd "$f" | grep 'not found' || true
done | sort -u)"
[ -z "$missing" ] || fail "unresolved libraries of the unpacked Mesa:
$missing"

# The packaged files name libraries by bare file name, which would find the system's Mesa.
packaged_icd="$root/usr/share/vulkan/icd.d/lvp_icd.json"
api_version="$(sed -n 's/.*"api_version": *"\([0-9.]*\)".*/\1/p' "$packaged_icd")"
[ -n "$api_version" ] || fail "no api_version in $packaged_icd"
cat >"$dir/lvp_icd.x86_64.json" <<EOF
{
    "ICD": {
        "api_version": "$api_version",
        "library_arch": "64",
        "library_path": "$lib/libvulkan_lvp.so"
    },
    "file_format_version": "1.0.1"
}
EOF
cat >"$dir/50_mesa.json" <<EOF
{
    "file_format_version" : "1.0.0",
    "ICD" : {
        "library_path" : "$lib/libEGL_mesa.so.0"
    }
}
EOF
# What strandbench sets when --driver selects this folder (it finds the same paths itself;
# this file is for running other programs against this Mesa: `. drivers/mesa-25.0/env.sh`).
cat >"$dir/env.sh" <<EOF
export VK_DRIVER_FILES="$dir/lvp_icd.x86_64.json"
export VK_ICD_FILENAMES="$dir/lvp_icd.x86_64.json"
export __EGL_VENDOR_LIBRARY_FILENAMES="$dir/50_mesa.json"
export LD_LIBRARY_PATH="$lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
export LIBGL_DRIVERS_PATH="$lib/dri"
export GBM_BACKENDS_PATH="$lib/gbm"
EOF
echo "$mesa_version" >"$dir/complete"
rm -rf "$debs"
echo "drivers.sh: Mesa $mesa_version unpacked in $dir"
