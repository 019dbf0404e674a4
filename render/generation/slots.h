// The generation pass's bindings (render/common/slots.h says how slots are
// shared). It writes the scene's points, colours and segments at their shared
// slots (2, 3, 4), so it binds no view: its parameters take 0, its inputs 16..
#ifndef SB_GENERATION_SLOTS_H
#define SB_GENERATION_SLOTS_H

#define SB_SLOT_GEN_PARAMS 0         // GenerationParams (uniforms.h)
#define SB_SLOT_GEN_GUIDE_POINTS 16  // vec4: xyz, thickness; guide-major
#define SB_SLOT_GEN_GUIDE_COLORS 17  // vec4: rgb, transparency
#define SB_SLOT_GEN_NEIGHBOURS 18    // uint: SB_GROOM_NEIGHBOURS per guide
#define SB_SLOT_GEN_PLACEMENTS 19    // vec4 per instance: cosine, sine, x, z
#define SB_SLOT_GEN_SEEDS 20         // uint per instance
#define SB_SLOT_GEN_LODS 21          // uvec4 per instance: GroomInstanceLod (scenes/groom.h)
#define SB_SLOT_GEN_GUIDE_ORDER 22   // uint per guide: the order a cut row keeps them

#endif  // SB_GENERATION_SLOTS_H
