#!/usr/bin/env bash
# Measures ray-traced shadows (--shadow rt) for docs/shadow-techniques.md: the
# error against the exact reference (one sample per pixel and light texel) and
# against the anti-aliased reference (aa:samples=4) as rays per point rise, and
# each tier's cost: the software tier's BVH (build time, memory) and, where the
# device has VK_KHR_ray_query, the ray-query tier's acceleration structure.
# Prints Markdown with the command and date.
# Usage: scripts/rt-shadows.sh [backend] [driver]   (default gl system;
# e.g. vulkan mesa-25.0 for both tiers on Mesa 25.0.7's lavapipe)
set -euo pipefail
cd "$(dirname "$0")/.."
sb=build/strandbench
backend=${1:-gl}
driver=${2:-system}
echo "Written by \`scripts/rt-shadows.sh $backend $driver\` at commit $(git rev-parse --short HEAD)," \
  "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)."
echo
echo "| scene | shadow | tier | visibility RMSE vs exact | image RMSE vs exact | image RMSE vs aa:samples=4 |"
echo "|---|---|---|---:|---:|---:|"
row() {  # scene, shadow, size, extra args
  local scene=$1 shadow=$2 size=$3
  shift 3
  "$sb" render --scene "$scene" --shadow "$shadow" --size "$size" --backend "$backend" \
    --driver "$driver" --warmup 0 --reference --reference aa:samples=4 --json "$@" |
    python3 -c "import json,sys; j=json.load(sys.stdin); e=j['error']
print('| \`%s\` %s | \`%s\` | %s | %.4f | %.4f | %.4f |' % ('$scene', '$*', '$shadow',
      j.get('tier', '-'), e['visibility']['rmse'], e['image']['rmse'], e['aa']['rmse']))"
}
for s in "curly:strands=60,seed=3,head=0" "stray:strands=300"; do
  for shadow in rt:size=64 rt:size=64,rays=4 rt:size=64,rays=16 dom:size=64 exact:size=64; do
    row "$s" "$shadow" 64x64
  done
done
for shadow in rt:size=128,bias=0.05 rt:size=128,bias=0.05,rays=16; do
  row "straight:strands=8,points=4,seed=5,head=0" "$shadow" 128x128 --primitive ribbons \
    --ribbon-width 10
done
echo
echo "| scene | tier | segments | BVH nodes / depth | build ms | BVH or acceleration structure + segments MiB | frame ms (median of 3) |"
echo "|---|---|---:|---:|---:|---:|---:|"
for s in "curly:strands=300" "stray:strands=3000" "straight:strands=20000,points=16,head=0"; do
  for tier in software ray_query; do
    # A device without ray queries refuses tier=ray_query (exit 2): no row.
    json=$("$sb" render --scene "$s" --shadow "rt:tier=$tier" --size 256x256 --backend "$backend" \
      --driver "$driver" --warmup 1 --repeat 3 --json 2>/dev/null) || continue
    python3 -c "import json,sys; j=json.loads(sys.argv[1]); c=j['counters']
b=sum(r['bytes'] for r in j['memory']['resources']
      if r['name'] in ('rt.bvh_nodes','rt.acceleration_structure','rt.boxes','rt.segments'))
print('| \`%s\` | %s | %d | %d / %d | %.1f | %.2f | %.0f |' % ('$s', j['tier'], c['rt.segments'],
      c['rt.bvh_nodes'], c['rt.bvh_depth'], c['rt.bvh_build_ms'], b / 2**20, j['frame_ms']['median']))" "$json"
  done
done
