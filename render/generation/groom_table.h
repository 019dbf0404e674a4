// The groom as the mesh path reads it (render --geometry mesh; strands.mesh):
// beside the guides' points and colours, one table of uint words, declared once
// for the C++ (mesh_groom.cpp fills it) and the GLSL. Floats are stored as
// their bits (floatBitsToUint), so the mesh shader reads the very values the
// compute pass and the CPU use.
#ifndef SB_GROOM_TABLE_H
#define SB_GROOM_TABLE_H

// The header's words.
#define SB_GROOM_TABLE_GUIDES 0u       // guides
#define SB_GROOM_TABLE_POINTS 1u       // points per strand
#define SB_GROOM_TABLE_STRANDS 2u      // rendered strands per instance
#define SB_GROOM_TABLE_SEGMENTS 3u     // segments in all (of the strands every instance keeps)
#define SB_GROOM_TABLE_RULE 4u         // 4 floats: spread, offset, noise, clump
#define SB_GROOM_TABLE_ALONG 8u        // float: 1 / (points - 1)
#define SB_GROOM_TABLE_ALPHA 9u        // float: the scene's opacity
#define SB_GROOM_TABLE_INSTANCES 10u   // instances
#define SB_GROOM_TABLE_SEEDS 11u       // where the instances' seeds start (uint each)
#define SB_GROOM_TABLE_PLACEMENTS 12u  // where their placements start (4 floats each)
#define SB_GROOM_TABLE_LODS 13u        // where their levels of detail start (GroomInstanceLod:
                                       // first, kept, widen's bits, 0)
#define SB_GROOM_TABLE_ORDER 14u       // where the guide order starts (uint per guide)
#define SB_GROOM_TABLE_HEADER 16u      // the neighbours (SB_GROOM_NEIGHBOURS per guide) follow

// Segments one mesh-shader workgroup draws, one invocation each.
#define SB_MESH_SEGMENTS 32u

#endif  // SB_GROOM_TABLE_H
