#!/usr/bin/env bash
# Measures ray-traced transparency's two tiers (--oit rt:tier=software and
# tier=ray_query) for docs/transparency-techniques.md: per tier, the error
# against the exact reference (equal in both: the same hits), the frame time,
# the walk's data (the software tier's BVH, or the ray-query tier's boxes and
# acceleration structure; the segments) and its build on the CPU, and the
# hits. A device without VK_KHR_ray_query refuses tier=ray_query (exit 2): no
# row. (scripts/rt-oit.sh measures rt beside the other techniques; its
# anti-aliased reference of the stray scene outgrows lavapipe's largest
# storage buffer, so it stays on GL.) Prints the rows; with SB_DOCS_RESULTS set,
# writes them there as JSON for the results store (docs/measured-pages.md):
#   scripts/docs-record.sh rt-oit-tiers scripts/rt-oit-tiers.sh vulkan mesa-25.0
# Usage: scripts/rt-oit-tiers.sh [backend] [driver]   (default gl system;
# e.g. vulkan mesa-25.0 for both tiers on Mesa 25.0.7's lavapipe)
set -euo pipefail
cd "$(dirname "$0")/.."
sb=build/strandbench
[ -x "$sb" ] || { echo "rt-oit-tiers.sh: $sb missing: run scripts/setup.sh" >&2; exit 2; }
backend=${1:-gl}
driver=${2:-system}
rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
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
print(json.dumps({'scene': sys.argv[2], 'oit': sys.argv[3], 'tier': j['tier'],
      'rmse': j['error']['image']['rmse'], 'frame_ms': j['frame_ms']['median'],
      'segments': c['rt.oit_segments'], 'bvh_nodes': c['rt.oit_bvh_nodes'],
      'bvh_depth': c['rt.oit_bvh_depth'], 'build_ms': c['rt.oit_bvh_build_ms'], 'bytes': b,
      'hits': c['rt.oit_hits']}))" "$json" "$s" "$oit" >> "$rows"
    done
  done
done
python3 - "$rows" "$backend" "$driver" "${SB_DOCS_RESULTS:-}" <<'PY'
import json, sys
rows, backend, driver, out = sys.argv[1:]
data = {"backend": backend, "driver": driver,
        "rows": [json.loads(l) for l in open(rows) if l.strip()]}
for r in data["rows"]:
    print(f"{r['scene']} {r['oit']} {r['tier']}: rmse {r['rmse']:.4f}, frame {r['frame_ms']:.0f} ms, "
          f"hits {r['hits']}")
if out:
    json.dump(data, open(out, "w"), indent=1)
PY
