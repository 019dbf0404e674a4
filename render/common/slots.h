// The binding numbers shared by several folders, named once for C++ and GLSL:
// the C++ includes this header (through render/common/technique.h) and the
// GLSL includes it as "render/common/slots.h" (embedded with the shaders). A name
// that only one folder uses lives in that folder's own slots.h
// (techniques/<folder>/slots.h: its C++ includes "techniques/<folder>/slots.h",
// its GLSL "slots.h"), within the ranges below. Every such header holds
// preprocessor defines only, so that both languages read it; tests/test_slots.cpp
// reads them all and checks that no two names bound in one shader collide.
//
// All bindings live in Vulkan descriptor set 0, so a number must be unique
// within one pipeline (all its stages, with everything they include, the
// shadow lookup too), not across pipelines: techniques reuse numbers in
// shaders that never meet.
//   0..7    the geometry and shading passes: the view, the shading parameters
//           and the scene's buffers. Full-screen and compute passes that bind
//           none of these reuse 0 and up (0..4 at most) for their own inputs.
//   8..15   the shadow technique: its light passes and its lookup (15 is the
//           opaque mesh's depth map, in every lookup); the occupancy map
//           passes read 9 from the eye as well (occupancy_oit). exact's light
//           passes, which meet no transparency technique, also use 16..18.
//   16..25  the transparency techniques and the outputs (probe), in passes
//           that may also bind 0..15.
//   26..    the shading model in the hair shading passes: its uniform block and
//           its folder's tables, beside all of the above.
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

// exact: the fragment lists, bound by every pass of the technique and the
// lookup; dsm's compression and avsm's resolve (compute) read them too. The
// node pool is paged (techniques/exact/nodes.glsl): page 0 is
// SB_SLOT_EXACT_NODES, pages 1..2 take free slots of the lookup, which reads
// no counts (the offsets' next entry ends a list): GL allows 16 storage blocks
// a stage, and compute_raster's resolve binds 12 beside the lookup's 4.
#define SB_SLOT_EXACT_PARAMS 8
#define SB_SLOT_EXACT_COUNTS 9
#define SB_SLOT_EXACT_OFFSETS 10
#define SB_SLOT_EXACT_PAGE1 11
#define SB_SLOT_EXACT_NODES 12
#define SB_SLOT_EXACT_PAGE2 13
// what the lookup does not read: in the light passes and the compute passes on
// the lists only, which bind no transparency technique, so 16.. is free there
#define SB_SLOT_EXACT_CURSOR 16
#define SB_SLOT_EXACT_STATE 17
#define SB_SLOT_EXACT_STATUS 18

// --- transparency techniques and outputs: 16.. ---
// The exact ones (abuffer, peel): the accumulation they composite
// (common/composite.frag) and the per-pixel fragment counts (common/count.frag)
#define SB_SLOT_OIT_ACCUM 16
#define SB_SLOT_OIT_COUNTS 17

// abuffer, and kbuffer and mlab (which include abuffer.glsl): the lists (fill
// and resolve) and the resolve's size; kbuffer and mlab keep the counters of
// the node pool (dropped fragments) in the same status buffer
#define SB_SLOT_ABUFFER_OFFSETS 18
#define SB_SLOT_ABUFFER_CURSOR 19
#define SB_SLOT_ABUFFER_FRAGMENTS 20
#define SB_SLOT_ABUFFER_STATUS 21
// the fragment pool's further pages, where it is larger than one storage
// binding (abuffer.glsl): page 0 is SB_SLOT_ABUFFER_FRAGMENTS
#define SB_SLOT_ABUFFER_PAGE1 22
#define SB_SLOT_ABUFFER_PAGE2 23
#define SB_SLOT_ABUFFER_PAGE3 24
#define SB_SLOT_ABUFFER_PAGE4 25
#define SB_SLOT_ABUFFER_SIZE 0  // resolve.comp only

// peel: the peeling state (also common/peel_advance.comp)
#define SB_SLOT_PEEL_STATE 18
#define SB_SLOT_PEEL_PEELED 19
// common/peel_advance.comp (peel and exact): its size
#define SB_SLOT_PEEL_ADVANCE_SIZE 0

// weighted and wboit: the resolve samples target i at SB_SLOT_BLENDED_TARGETS + i
#define SB_SLOT_BLENDED_TARGETS 16

// --- the shading model: 26.. ---
#define SB_SLOT_SHADING_MODEL 26  // its uniform block (its folder's uniforms.h)

// the renderer's sum of the lights (a full-screen pass): an extra light's colour
#define SB_SLOT_LIGHTS_SUM_COLOR 0

// the viewer's overlay (a full-screen pass, cli/view_overlay.cpp): the image shown and the text
#define SB_SLOT_OVERLAY_IMAGE 0
#define SB_SLOT_OVERLAY_TEXT 1

#endif  // SB_SLOTS_H
