#include "pbr/strand_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "base/errors.h"

namespace sb::pbr {

namespace {

constexpr unsigned kStrandGeometry = 0, kMeshGeometry = 1;

// The context a ray carries into the strands' filter: every strand hit is recorded and
// rejected, so Embree goes on to the next one; the mesh's hits are accepted (the nearest
// one ends the ray).
struct CollectContext {
  RTCIntersectContext context;                    // first: Embree hands the filter a pointer to it
  std::vector<std::pair<float, uint32_t>>* hits;  // t, primitive
  std::vector<float>* u;
};

void collectStrandHits(const RTCFilterFunctionNArguments* args) {
  auto* c = reinterpret_cast<CollectContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    c->hits->push_back(
        {RTCRayN_tfar(args->ray, args->N, i), RTCHitN_primID(args->hit, args->N, i)});
    c->u->push_back(RTCHitN_u(args->hit, args->N, i));
    args->valid[i] = 0;
  }
}

[[noreturn]] void embreeFailed(RTCDevice device, const std::string& what) {
  throw std::runtime_error("Embree: " + what + " failed (error " +
                           std::to_string(static_cast<int>(rtcGetDeviceError(device))) + ")");
}

}  // namespace

struct StrandTracer::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

StrandTracer::StrandTracer(const TraceGeometry& g) : g_(g), e_(std::make_unique<Embree>()) {
  for (float r : g_.radius)
    if (!(r >= 0.0f) || !std::isfinite(r))
      throw InputError("pbr reference: a strand radius is negative or not finite");
  if (g_.radius.size() != g_.points.size())
    throw InputError("pbr reference: one radius per strand point is needed");
  for (float r : g_.radius) backOff_ = std::max(backOff_, 4.0f * r);
  for (std::size_t s = 0; s < g_.pointCount.size(); ++s)
    for (uint32_t k = 0; k + 1 < g_.pointCount[s]; ++k) {
      segmentStart_.push_back(g_.firstPoint[s] + k);
      segmentStrand_.push_back(static_cast<uint32_t>(s));
    }

  e_->device = rtcNewDevice("verbose=0");
  if (!e_->device) throw std::runtime_error("Embree: no device");
  e_->scene = rtcNewScene(e_->device);
  rtcSetSceneBuildQuality(e_->scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(e_->scene, RTC_SCENE_FLAG_ROBUST);

  // Geometry ids fixed (kStrandGeometry, kMeshGeometry); an empty one is left out.
  if (!segmentStart_.empty()) addStrands();
  if (g_.meshIndices.size() >= 3) addMesh();
  rtcCommitScene(e_->scene);
  if (rtcGetDeviceError(e_->device) != RTC_ERROR_NONE) embreeFailed(e_->device, "the scene build");
}

void StrandTracer::addStrands() {
  RTCGeometry curves = rtcNewGeometry(e_->device, RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE);
  auto* vertices = static_cast<glm::vec4*>(rtcSetNewGeometryBuffer(
      curves, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, sizeof(glm::vec4), g_.points.size()));
  auto* index = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      curves, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(uint32_t), segmentStart_.size()));
  if (!vertices || !index) embreeFailed(e_->device, "curve buffers");
  for (std::size_t i = 0; i < g_.points.size(); ++i)
    vertices[i] = glm::vec4(g_.points[i], g_.radius[i]);
  std::copy(segmentStart_.begin(), segmentStart_.end(), index);
  rtcSetGeometryIntersectFilterFunction(curves, collectStrandHits);
  rtcCommitGeometry(curves);
  rtcAttachGeometryByID(e_->scene, curves, kStrandGeometry);
  rtcReleaseGeometry(curves);
}

void StrandTracer::addMesh() {
  RTCGeometry mesh = rtcNewGeometry(e_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const std::size_t triangles = g_.meshIndices.size() / 3;
  auto* mp = static_cast<glm::vec3*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0,
                                                             RTC_FORMAT_FLOAT3, sizeof(float) * 3,
                                                             g_.meshPositions.size()));
  auto* mi = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(uint32_t) * 3, triangles));
  if (!mp || !mi) embreeFailed(e_->device, "mesh buffers");
  std::copy(g_.meshPositions.begin(), g_.meshPositions.end(), mp);
  std::copy(g_.meshIndices.begin(), g_.meshIndices.begin() + std::ptrdiff_t(triangles * 3), mi);
  rtcCommitGeometry(mesh);
  rtcAttachGeometryByID(e_->scene, mesh, kMeshGeometry);
  rtcReleaseGeometry(mesh);
}

StrandTracer::~StrandTracer() = default;

RayHits StrandTracer::trace(glm::vec3 origin, glm::vec3 dir, float tnear, float tfar) const {
  std::vector<std::pair<float, uint32_t>> raw;
  std::vector<float> us;
  CollectContext c{};
  rtcInitIntersectContext(&c.context);
  c.hits = &raw;
  c.u = &us;
  // Embree's curve intersectors miss a curve that passes within about its radius of the ray's
  // origin (against a brute-force test, shadow rays started inside a dense groom lost some of
  // their crossings, always the nearest ones). The ray starts backOff_ earlier instead, and its
  // distances are taken back.
  const float back = backOff_;
  const glm::vec3 start = origin - back * dir;
  RTCRayHit rh{};
  rh.ray.org_x = start.x;
  rh.ray.org_y = start.y;
  rh.ray.org_z = start.z;
  rh.ray.dir_x = dir.x;
  rh.ray.dir_y = dir.y;
  rh.ray.dir_z = dir.z;
  rh.ray.tnear = tnear + back;
  rh.ray.tfar = tfar + back;
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(e_->scene, &c.context, &rh);

  RayHits out;
  float end = tfar;
  if (rh.hit.geomID == kMeshGeometry) {
    out.mesh = true;
    out.meshT = end = rh.ray.tfar - back;
    out.triangle = rh.hit.primID;
  }
  // Sorted by t; a segment kept once (a primitive may be reported from more than one leaf).
  std::vector<std::size_t> order(raw.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&raw](std::size_t a, std::size_t b) {
    return raw[a].first < raw[b].first ||
           (raw[a].first == raw[b].first && raw[a].second < raw[b].second);
  });
  std::vector<uint32_t> seen;
  for (std::size_t i : order) {
    const float t = raw[i].first - back;
    const uint32_t prim = raw[i].second;
    if (t >= end || std::find(seen.begin(), seen.end(), prim) != seen.end()) continue;
    const uint32_t first = segmentStart_[prim];
    const glm::vec3 p0 = g_.points[first], p1 = g_.points[first + 1];
    const glm::vec3 d = p1 - p0;
    // Embree caps a linear segment past each end (u then reads 0 or 1); a cap hit lies over
    // the next segment and would take its tangent. Strands are ribbons without caps, as the
    // raster draws them: a hit whose point lies beyond the segment's ends is not one.
    const float along =
        glm::dot(d, d) > 1e-30f ? glm::dot(origin + t * dir - p0, d) / glm::dot(d, d) : 0.5f;
    if (along < -1e-4f || along > 1.0f + 1e-4f) continue;
    seen.push_back(prim);
    StrandHit h;
    h.t = t;
    h.segment = prim;
    h.u = std::clamp(us[i], 0.0f, 1.0f);
    h.tangent = glm::dot(d, d) > 1e-30f ? glm::normalize(d) : glm::vec3(0, 1, 0);
    // The offset across the ribbon: from the axis, along the ribbon's width (perpendicular
    // to the ray and the tangent), in units of the radius there. Its sign is the hair BSDF's:
    // positive along its frame's y = z x x, with x the tangent and z toward the ray's origin
    // (-dir), i.e. along tangent x dir (the R lobe then leaves at phi = -2 asin(h)).
    const glm::vec3 axis = p0 + h.u * d;
    const float r = glm::mix(g_.radius[first], g_.radius[first + 1], h.u);
    const glm::vec3 across = glm::cross(h.tangent, dir);
    const float len = glm::length(across);
    if (r > 0 && len > 1e-12f)
      h.h = std::clamp(glm::dot(origin + t * dir - axis, across / len) / r, -1.0f, 1.0f);
    out.strands.push_back(h);
  }
  return out;
}

}  // namespace sb::pbr
