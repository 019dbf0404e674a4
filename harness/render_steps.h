// The steps of runRender (harness/render.h) shared between its files: render.cpp
// (validation, device, plan, frames, measures), render_measures.cpp (the reference),
// render_references.cpp and render_json.cpp. Internal to harness/render*.cpp and the
// measure units (harness/measures/).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/references/exact/exact_reference.h"
#include "harness/render.h"

namespace sb {

class Renderer;

// Everything the reference's pixels depend on (the cache's key).
std::string referenceKey(const RenderRequest& req, const RenderSettings& s, const Spec& refShadow);

// The world size of one pixel (one texel of a square map of `side`) at p for this
// view-projection: 2 w / (P[1][1] side), w the clip w (1 for an orthographic light).
float worldPixelAt(const glm::mat4& proj, const glm::mat4& viewProj, glm::vec3 p, float side);
// One pixel at the scene's centre: the width of world strands that have none of their own.
double pixelAtSceneCentre(const Scene& scene, const RenderSettings& s);

// The host memory the final image takes after the frames: the RGBA32F rows
// read back and the image made of them, both held at once.
std::size_t imageHostBytes(const RenderSettings& s);
// The renderer's colour target read back as an RGBA float image (alpha 1).
Image colorImage(Renderer& r, const RenderSettings& s);
// Refuses a run whose resources would not fit, before they are made: over
// --memory-limit (`limit`, all of the timed frames' resources) or over the
// device's budget. `host`: host memory the run takes besides its resources.
void checkMemory(const std::vector<ResourceBytes>& planned, const std::vector<ResourceBytes>& made,
                 long long limit, const MemoryBudget& budget, const std::string& what,
                 std::size_t host = 0);

RenderCache::Reference renderReference(Device& dev, const Scene& scene,
                                       const RenderSettings& settings, const Spec& refShadow,
                                       const RenderRequest& req);
// The further references of a request (RenderRequest::references), each on a
// device of its own, compared with out.image; cached per sweep.
std::vector<RenderResult::MoreReference> moreReferences(
    const RenderRequest& req, const Scene& scene, const RenderSettings& settings,
    const Spec& refShadow, const RenderResult& out, RenderCache* cache);
// Refuses (InputError) a further reference that cannot be made at any memory:
// a side over 16384. Before any work.
void checkMoreReferences(const RenderRequest& req, const RenderSettings& settings,
                         const Spec& refShadow);
VisibilityError visibilityError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);
// `error` of the report: image (with an image), visibility, each further reference's, and
// each measure's (own, by_eye_layers, full_model).
nlohmann::json errorJson(const RenderResult& r);

}  // namespace sb
