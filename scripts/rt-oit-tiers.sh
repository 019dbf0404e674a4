#!/usr/bin/env bash
# Measures ray-traced transparency's two tiers (--oit rt:tier=software and
# tier=ray_query) for docs/transparency-techniques.md: per tier, the error
# against the exact reference (equal in both: the same hits), the frame time,
# the walk's data (the software tier's BVH, or the ray-query tier's boxes and
# acceleration structure; the segments) and its build on the CPU, and the
# hits. A device without VK_KHR_ray_query refuses tier=ray_query (exit 2): no
# row. (scripts/rt-oit.sh measures rt beside the other techniques; its
# anti-aliased reference of the stray scene outgrows lavapipe's largest
# storage buffer, so it stays on GL.) Prints Markdown with the command and date.
# Usage: scripts/rt-oit-tiers.sh [backend] [driver]   (default gl system;
# e.g. vulkan mesa-25.0 for both tiers on Mesa 25.0.7's lavapipe)
set -euo pipefail
cd "$(dirname "$0")/.."
sb=build/strandbench
[ -x "$sb" ] || { echo "rt-oit-tiers.sh: $sb missing: run scripts/setup.sh" >&2; exit 2; }
backend=${1:-gl}
driver=${2:-system}
echo "Written by \`scripts/rt-oit-tiers.sh $backend $driver\` at commit $(git rev-parse --short HEAD)," \
  "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)."
echo
echo "| scene | transparency | tier | image RMSE vs exact | frame ms (median of 3) | segments | BVH nodes / depth | build ms | BVH or acceleration structure + segments MiB | hits |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"
for s in "curly:strands=300,seed=3,alpha=0.4" "stray:alpha=0.4"; do
  for oit in rt rt:k=8; do
    for tier in software ray_query; do
      spec="$oit$([ "$oit" = rt ] && echo : || echo ,)tier=$tier"
      json=$("$sb" render --scene "$s" --shadow exact --oit "$spec" --size 128x128 \
        --backend "$backend" --driver "$driver" --warmup 1 --repeat 3 --reference --json \
        2>/dev/null) || continue
      python3 -c "import json,sys; j=json.loads(sys.argv[1]); c=j['counters']
b=sum(r['bytes'] for r in j['memory']['resources'] if r['name'] in
      ('rt.oit_bvh_nodes','rt.oit_acceleration_structure','rt.oit_boxes','rt.oit_segments'))
print('| \`%s\` | \`%s\` | %s | %.4f | %.0f | %d | %d / %d | %.1f | %.2f | %d |' % ('$s', '$oit',
      j['tier'], j['error']['image']['rmse'], j['frame_ms']['median'], c['rt.oit_segments'],
      c['rt.oit_bvh_nodes'], c['rt.oit_bvh_depth'], c['rt.oit_bvh_build_ms'], b / 2**20,
      c['rt.oit_hits']))" "$json"
    done
  done
done
