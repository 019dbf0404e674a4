// The strands and the opaque mesh as Embree geometry (docs/physics-reference.md "The
// geometry"), and every hit along a ray. Strands are Embree's flat linear curves
// (RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE): ribbons that face each ray, one segment per pair of
// points, a radius per point. That is the shape the rasterized techniques draw (a
// camera-facing ribbon, or a one-pixel line), and pbrt's flat curves, whose offset across
// the ribbon is the hair BSDF's h. Plain data in, no scene or GPU code: the harness converts
// its Scene (harness/references/pbr/pbr_reference.cpp).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace sb::pbr {

struct TraceGeometry {
  // Strand s owns points [firstPoint[s], firstPoint[s] + pointCount[s]).
  std::vector<uint32_t> firstPoint, pointCount;
  std::vector<glm::vec3> points;
  std::vector<float> radius;  // per point, world units (half the ribbon's width)
  // The opaque mesh: triangles.
  std::vector<glm::vec3> meshPositions;
  std::vector<uint32_t> meshIndices;
};

// One strand segment crossed by a ray.
struct StrandHit {
  float t = 0;              // distance along the (unit) direction
  uint32_t segment = 0;     // index into StrandTracer::segmentStart()
  float u = 0;              // along the segment, 0 at its first point
  float h = 0;              // across the ribbon, -1..1, along tangent x dir (the BSDF's h)
  glm::vec3 tangent{0.0f};  // the segment's direction, root to tip
};

struct RayHits {
  std::vector<StrandHit> strands;  // every strand hit before the mesh, nearest first
  bool mesh = false;               // the ray ends on the mesh at meshT
  float meshT = 0;
  uint32_t triangle = 0;
};

class StrandTracer {
 public:
  // Builds the Embree scene (throws sb::InputError when a radius is negative or not finite,
  // std::runtime_error when Embree fails).
  explicit StrandTracer(const TraceGeometry& g);
  ~StrandTracer();
  StrandTracer(const StrandTracer&) = delete;
  StrandTracer& operator=(const StrandTracer&) = delete;

  // Every strand hit in (tnear, tfar) up to the first mesh hit, sorted by t. dir: unit length.
  // Safe to call from several threads at once.
  RayHits trace(glm::vec3 origin, glm::vec3 dir, float tnear, float tfar) const;

  // The first point of each segment (into TraceGeometry::points).
  const std::vector<uint32_t>& segmentStart() const { return segmentStart_; }
  // The strand of each segment.
  const std::vector<uint32_t>& segmentStrand() const { return segmentStrand_; }
  const TraceGeometry& geometry() const { return g_; }

 private:
  struct Embree;
  void addStrands();
  void addMesh();
  TraceGeometry g_;
  std::vector<uint32_t> segmentStart_, segmentStrand_;
  float backOff_ = 0;  // how far before its origin a ray starts (trace)
  std::unique_ptr<Embree> e_;
};

}  // namespace sb::pbr
