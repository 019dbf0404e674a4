// Every binding number of every shader, named once for C++ and GLSL: the C++
// includes this header (through techniques/common/technique.h) and the GLSL
// includes it as "../common/slots.h" (embedded with the shaders). It holds
// preprocessor defines only, so that both languages read it.
//
// All bindings live in Vulkan descriptor set 0, so a number must be unique
// within one pipeline (all its stages, with everything they include, the
// shadow lookup too), not across pipelines: techniques reuse numbers in
// shaders that never meet.
//   0..7    the geometry and shading passes: the view, the shading parameters
//           and the scene's buffers. Full-screen and compute passes that bind
//           none of these reuse 0 and 1 for their own inputs.
//   8..15   the shadow technique: its light passes and its lookup (15 is the
//           opaque mesh's depth map, in every lookup); the occupancy map
//           passes read 9 from the eye as well (occupancy_oit).
//   16..25  the transparency techniques and the outputs (probe), in passes
//           that may also bind 0..15.
#ifndef SB_SLOTS_H
#define SB_SLOTS_H

// --- geometry and shading (common/bindings.glsl, view.glsl, shading.glsl) ---
#define SB_SLOT_VIEW 0            // ViewUniforms: camera or light
#define SB_SLOT_SHADING 1         // lighting parameters of the shading passes
#define SB_SLOT_POINTS 2          // vec4: xyz, thickness
#define SB_SLOT_COLORS 3          // vec4: rgb, alpha
#define SB_SLOT_SEGMENTS 4        // uint: a segment's first point
#define SB_SLOT_MESH_POSITIONS 5  // vec4
#define SB_SLOT_MESH_NORMALS 6    // vec4
#define SB_SLOT_MESH_INDICES 7    // uint, 3 per triangle

// --- the shadow technique: 8..15 ---
#define SB_SLOT_SHADOW_FIRST 8
#define SB_SLOT_SHADOW_LAST 15
#define SB_SLOT_OPAQUE_SHADOW 15  // the opaque mesh's depth from the light (opaque_shadow.glsl)

// shadowmap: the lookup
#define SB_SLOT_SHADOWMAP_DEPTH 8
#define SB_SLOT_SHADOWMAP_PARAMS 9

// dom: parameters (passes and lookup), the depth map z0 (opacity pass and lookup), the maps
// (lookup)
#define SB_SLOT_DOM_PARAMS 8
#define SB_SLOT_DOM_DEPTH 10
#define SB_SLOT_DOM_MAPS 9

// osm: parameters (passes and lookup), a map pass's parameters, the atlases (lookup)
#define SB_SLOT_OSM_PARAMS 8
#define SB_SLOT_OSM_PASS 9
#define SB_SLOT_OSM_ATLASES 9

// occupancy: the lookup; the range also in the occupancy and slab passes
// (OccupancyMaps, from the light and, for occupancy_oit, from the eye)
#define SB_SLOT_OCC_PARAMS 8
#define SB_SLOT_OCC_RANGE 9
#define SB_SLOT_OCC_BITS 10
#define SB_SLOT_OCC_SLABS 11

// dc: the lookup (params, range, counts, sums, squares) and the cluster passes
#define SB_SLOT_DC_PARAMS 8
#define SB_SLOT_DC_RANGE 9
#define SB_SLOT_DC_COUNTS 10
#define SB_SLOT_DC_SUMS 11
#define SB_SLOT_DC_SQUARES 12
#define SB_SLOT_DC_CENTRES 13

// exact: the fragment lists, bound by every pass of the technique and the lookup
#define SB_SLOT_EXACT_PARAMS 8
#define SB_SLOT_EXACT_COUNTS 9
#define SB_SLOT_EXACT_OFFSETS 10
#define SB_SLOT_EXACT_CURSOR 11
#define SB_SLOT_EXACT_NODES 12
#define SB_SLOT_EXACT_STATE 13
#define SB_SLOT_EXACT_STATUS 14

// dsm: the lookup (params, nodes kept per texel, their offsets, the nodes);
// the compression pass (compute) reads exact's sorted lists at the EXACT slots
// and writes the nodes at 0..3 (no geometry bound there)
#define SB_SLOT_DSM_PARAMS 8
#define SB_SLOT_DSM_KEPT 9
#define SB_SLOT_DSM_OFFSETS 10
#define SB_SLOT_DSM_NODES 11
#define SB_SLOT_DSM_OUT_KEPT 0
#define SB_SLOT_DSM_OUT_OFFSETS 1
#define SB_SLOT_DSM_OUT_NODES 2
#define SB_SLOT_DSM_OUT_STATUS 3
#define SB_SLOT_DSM_COMPRESS 4

// adsm: the lookup (params, the hair's front depth)
#define SB_SLOT_ADSM_PARAMS 8
#define SB_SLOT_ADSM_DEPTH 9

// fom: parameters (passes and lookup), the coefficients (lookup)
#define SB_SLOT_FOM_PARAMS 8
#define SB_SLOT_FOM_MAPS 9

// avsm: the lookup (params, nodes per texel, the nodes); the resolve pass
// (compute) reads exact's lists at the EXACT slots and writes at 0..3
#define SB_SLOT_AVSM_PARAMS 8
#define SB_SLOT_AVSM_COUNT 9
#define SB_SLOT_AVSM_NODES 10
#define SB_SLOT_AVSM_OUT_COUNT 0
#define SB_SLOT_AVSM_OUT_NODES 1
#define SB_SLOT_AVSM_OUT_STATUS 2
#define SB_SLOT_AVSM_RESOLVE 3

// voxel: parameters (splat and lookup), the density grid
#define SB_SLOT_VOXEL_PARAMS 8
#define SB_SLOT_VOXEL_GRID 9

// msm: parameters (light pass and lookup), b0 and the moment targets (lookup)
#define SB_SLOT_MSM_PARAMS 8
#define SB_SLOT_MSM_B0 9
#define SB_SLOT_MSM_LOW 10
#define SB_SLOT_MSM_HIGH 11

// --- transparency techniques and outputs: 16.. ---
// The exact ones (abuffer, peel): the accumulation they composite
// (common/composite.frag) and the per-pixel fragment counts (common/count.frag)
#define SB_SLOT_OIT_ACCUM 16
#define SB_SLOT_OIT_COUNTS 17

// abuffer: the lists (fill and resolve) and the resolve's size
#define SB_SLOT_ABUFFER_OFFSETS 18
#define SB_SLOT_ABUFFER_CURSOR 19
#define SB_SLOT_ABUFFER_FRAGMENTS 20
#define SB_SLOT_ABUFFER_STATUS 21
#define SB_SLOT_ABUFFER_SIZE 0  // resolve.comp only

// peel: the peeling state (also common/peel_advance.comp)
#define SB_SLOT_PEEL_STATE 18
#define SB_SLOT_PEEL_PEELED 19
// common/peel_advance.comp (peel and exact): its size
#define SB_SLOT_PEEL_ADVANCE_SIZE 0

// weighted and wboit: the resolve samples target i at SB_SLOT_BLENDED_TARGETS + i
#define SB_SLOT_BLENDED_TARGETS 16
#define SB_SLOT_WEIGHTED_ACCUM 16   // target 0
#define SB_SLOT_WEIGHTED_COUNT 17   // target 1
#define SB_SLOT_WBOIT_ACCUM 16      // target 0
#define SB_SLOT_WBOIT_REVEALAGE 17  // target 1

// occupancy_oit: the maps in the accumulation (beside the shadow lookup), and
// the resolve's inputs (a full-screen pass)
#define SB_SLOT_OOIT_RANGE 20
#define SB_SLOT_OOIT_BITS 21
#define SB_SLOT_OOIT_SLABS 25
#define SB_SLOT_OOIT_ACCUM 0
#define SB_SLOT_OOIT_LOG2T 1

// fake: the three subset images in the blend (a full-screen pass)
#define SB_SLOT_FAKE_IMAGE0 16
#define SB_SLOT_FAKE_IMAGE1 17
#define SB_SLOT_FAKE_IMAGE2 18

// stochastic: the params and the sample depths in the hair passes (beside the
// shadow lookup), the resolve's inputs (a full-screen pass)
#define SB_SLOT_STOCH_PARAMS 16
#define SB_SLOT_STOCH_DEPTHS 18
#define SB_SLOT_STOCH_ACCUM 16
#define SB_SLOT_STOCH_ALPHA 17

// peel_classic: the layer pass (beside the shadow lookup), then the blend and
// composite (full-screen passes)
#define SB_SLOT_PEELC_PREV_DEPTH 16
#define SB_SLOT_PEELC_OPAQUE_DEPTH 17
#define SB_SLOT_PEELC_LAYER_COLOR 16
#define SB_SLOT_PEELC_LAYER_DEPTH 17
#define SB_SLOT_PEELC_UNDER 16

// dual_peel: the peel pass (beside the shadow lookup), then the back blend and
// the final (full-screen passes)
#define SB_SLOT_DUAL_DEPTH 16
#define SB_SLOT_DUAL_FRONT 17
#define SB_SLOT_DUAL_OPAQUE_DEPTH 18
#define SB_SLOT_DUAL_BACK_TEMP 16
#define SB_SLOT_DUAL_FRONT_FINAL 16
#define SB_SLOT_DUAL_BACK_FINAL 17

// probe: the points and their shadow values (beside the shadow lookup)
#define SB_SLOT_PROBE_POINTS 16
#define SB_SLOT_PROBE_VALUES 17

// mboit: the parameters (both hair passes), the moment targets sampled by the
// second hair pass and the accumulation sampled by the resolve
#define SB_SLOT_MBOIT_PARAMS 16
#define SB_SLOT_MBOIT_B0 17
#define SB_SLOT_MBOIT_LOW 18
#define SB_SLOT_MBOIT_HIGH 19
#define SB_SLOT_MBOIT_ACCUM 20

// kbuffer, mlab: the abuffer lists (SB_SLOT_ABUFFER_*), plus the counters of
// the node pool (dropped fragments) in the same status buffer

// shortcut: the k nearest depths, their colours and claims, the tail targets
#define SB_SLOT_SHORTCUT_PARAMS 16
#define SB_SLOT_SHORTCUT_DEPTHS 18
#define SB_SLOT_SHORTCUT_COLORS 19
#define SB_SLOT_SHORTCUT_CLAIMS 20
#define SB_SLOT_SHORTCUT_TAIL 21
#define SB_SLOT_SHORTCUT_REVEALAGE 22

// the renderer's sum of the lights (a full-screen pass): an extra light's colour
#define SB_SLOT_LIGHTS_SUM_COLOR 0

#endif  // SB_SLOTS_H
