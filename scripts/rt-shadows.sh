#!/usr/bin/env bash
# Measures ray-traced shadows (--shadow rt) for docs/shadow-techniques.md: the
# error against the exact reference (one sample per pixel and light texel) and
# against the anti-aliased reference (aa:samples=4) as rays per point rise, and
# each tier's cost: the software tier's BVH (build time, memory) and, where the
# device has VK_KHR_ray_query, the ray-query tier's acceleration structure.
# Prints the rows; with SB_DOCS_RESULTS set, writes them there as JSON for the
# results store (docs/measured-pages.md):
#   scripts/docs-record.sh rt-shadows scripts/rt-shadows.sh vulkan mesa-25.0
# Usage: scripts/rt-shadows.sh [backend] [driver]   (default gl system;
# e.g. vulkan mesa-25.0 for both tiers on Mesa 25.0.7's lavapipe)
set -euo pipefail
cd "$(dirname "$0")/.."
sb=build/strandbench
[ -x "$sb" ] || { echo "rt-shadows.sh: $sb missing: run scripts/setup.sh" >&2; exit 2; }
backend=${1:-gl}
driver=${2:-system}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
row() {  # scene, shadow, size, extra args
  local scene=$1 shadow=$2 size=$3
  shift 3
  "$sb" render --scene "$scene" --shadow "$shadow" --size "$size" --backend "$backend" \
    --driver "$driver" --warmup 0 --reference --reference aa:samples=4 --json "$@" |
    python3 -c "import json,sys; j=json.load(sys.stdin); e=j['error']
print(json.dumps({'scene': sys.argv[1], 'args': ' '.join(sys.argv[3:]), 'shadow': sys.argv[2],
      'tier': j.get('tier', '-'), 'visibility': e['visibility']['rmse'],
      'image': e['image']['rmse'], 'aa': e['aa']['rmse']}))" "$scene" "$shadow" "$@" \
    >> "$tmp/errors.jsonl"
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
touch "$tmp/tiers.jsonl"
for s in "curly:strands=300" "stray:strands=3000" "straight:strands=20000,points=16,head=0"; do
  for tier in software ray_query; do
    # A device without ray queries refuses tier=ray_query (exit 2): no row.
    json=$("$sb" render --scene "$s" --shadow "rt:tier=$tier" --size 256x256 --backend "$backend" \
      --driver "$driver" --warmup 1 --repeat 3 --json 2>/dev/null) || continue
    python3 -c "import json,sys; j=json.loads(sys.argv[1]); c=j['counters']
b=sum(r['bytes'] for r in j['memory']['resources']
      if r['name'] in ('rt.bvh_nodes','rt.acceleration_structure','rt.boxes','rt.segments'))
print(json.dumps({'scene': sys.argv[2], 'tier': j['tier'], 'segments': c['rt.segments'],
      'bvh_nodes': c['rt.bvh_nodes'], 'bvh_depth': c['rt.bvh_depth'],
      'build_ms': c['rt.bvh_build_ms'], 'bytes': b, 'frame_ms': j['frame_ms']['median']}))" \
      "$json" "$s" >> "$tmp/tiers.jsonl"
  done
done
python3 - "$tmp" "$backend" "$driver" "${SB_DOCS_RESULTS:-}" <<'PY'
import json, os, sys
tmp, backend, driver, out = sys.argv[1:]
read = lambda f: [json.loads(l) for l in open(os.path.join(tmp, f)) if l.strip()]
data = {"backend": backend, "driver": driver, "errors": read("errors.jsonl"),
        "tiers": read("tiers.jsonl")}
for r in data["errors"]:
    print(f"{r['scene']} {r['args']} {r['shadow']} {r['tier']}: visibility {r['visibility']:.4f}, "
          f"image {r['image']:.4f}, vs aa {r['aa']:.4f}")
for r in data["tiers"]:
    print(f"{r['scene']} {r['tier']}: {r['segments']} segments, build {r['build_ms']:.1f} ms, "
          f"{r['bytes'] / 2**20:.2f} MiB, frame {r['frame_ms']:.0f} ms")
if out:
    json.dump(data, open(out, "w"), indent=1)
PY
