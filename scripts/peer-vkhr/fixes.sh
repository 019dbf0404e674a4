#!/usr/bin/env bash
# strandbench's source fixes to vkhr (commit 6d26f5b, 2019) for Debian 12's libraries, applied
# by scripts/peer-vkhr.sh to a copy of the user's checkout (the current directory). Each line
# says why; none changes what vkhr renders or times.
set -euo pipefail
# imgui 1.86 (Debian) wants a zeroed init struct with the swapchain's image counts, and renamed
# InvalidateFontUploadObjects.
sed -i 's/ImGui_ImplVulkan_InitInfo init_info;/ImGui_ImplVulkan_InitInfo init_info {}; init_info.MinImageCount = 2; init_info.ImageCount = std::max<uint32_t>(2, vulkan_renderer.swap_chain.size());/' \
  src/vkhr/rasterizer/interface.cc
sed -i 's/ImGui_ImplVulkan_InvalidateFontUploadObjects/ImGui_ImplVulkan_DestroyFontUploadObjects/' \
  src/vkhr/rasterizer/interface.cc
grep -q '#include <algorithm>' src/vkhr/rasterizer/interface.cc || sed -i '1i #include <algorithm>' src/vkhr/rasterizer/interface.cc
# tinyobjloader 2.0 takes a warning string before the error string.
sed -i 's/^\( *\)&error_msg, file_path.c_str()/\1\&error_msg, \&error_msg, file_path.c_str()/' \
  src/vkhr/scene_graph/model.cc
# The benchmark averages its last N frames after N warm-up frames, N = 60 in vkhr: minutes per
# case on a CPU driver. VKHR_SB_FRAMES sets N (default 60, vkhr's own).
sed -i 's|int profile_limit { 60 };|int profile_limit { std::getenv("VKHR_SB_FRAMES") ? std::atoi(std::getenv("VKHR_SB_FRAMES")) : 60 };|' \
  include/vkhr/rasterizer/interface.hh
grep -q '#include <cstdlib>' include/vkhr/rasterizer/interface.hh || sed -i '1a #include <cstdlib>' include/vkhr/rasterizer/interface.hh
# The window icon is a large-file pointer in a checkout without git-lfs: stb cannot read it and
# the resize that follows crashes. A 16x16 grey PNG of our own stands in for it.
if ! head -c 8 share/images/vulkan_icon.png 2>/dev/null | grep -q PNG; then
  python3 - <<'PY'
import struct, zlib
def chunk(t, d): return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
rows = b"".join(b"\0" + b"\x80\x80\x80\xff" * 16 for _ in range(16))
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 16, 16, 8, 6, 0, 0, 0)) \
    + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b"")
open("share/images/vulkan_icon.png", "wb").write(png)
PY
fi
# vkhr scores only discrete and integrated GPUs, so a CPU device (lavapipe) scores 0 and none is
# chosen; every device type scores at least 1, GPUs still first.
sed -i 's/physical_device.is_integrated_gpu();$/physical_device.is_integrated_gpu() + 1;/' src/vkhr/rasterizer.cc
# The frame's clear colour: white in vkhr, black in strandbench; black so the two images (and
# vkhr's against strandbench's reference) differ only in the hair. Only the colour pass's clear.
sed -i '/begin_render_pass(color_pass, framebuffers\[frame\],/{n;s/{ 1.00f, 1.00f, 1.00f, 1.00f }/{ 0.00f, 0.00f, 0.00f, 1.00f }/}' \
  src/vkhr/rasterizer.cc
