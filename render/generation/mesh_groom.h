// The mesh path's scene on the device (render --geometry mesh; strands.mesh,
// docs/geometry.md): only the groom, bound where the strands' buffers go, so
// that every geometry pass binds it unchanged and its strand draw (the mesh
// shader in Geometry::strandVertexShader) makes the strands as it draws them.
#pragma once

#include "render/common/technique.h"

namespace sb {

// Makes the groom's buffers (owner "scene"): gpu.points holds the guides'
// points, gpu.colors their colours, gpu.segments the groom's table
// (groom_table.h); gpu.segmentCount is the segments of every instance, as the
// CPU path has them. The scene must have a groom (geometryRefusal says so).
void uploadMeshGroom(Device& dev, const Scene& scene, GpuScene& gpu);

}  // namespace sb
