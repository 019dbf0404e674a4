// The steps of runRender (harness/render.h) shared between its files: render.cpp
// (validation, device, plan, frames), render_measures.cpp (reference, errors,
// invariants) and render_json.cpp. Internal to harness/render*.cpp.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness/invariants.h"
#include "harness/render.h"

namespace sb {

class Renderer;

// The reference's transparency: exact, from sorted fragment lists.
extern const char* kReferenceOit;
// The reference for a technique: exact shadows at its light-map size, its lookup jittered as
// the technique's is (jitter, jitter_samples).
Spec referenceShadowSpec(const Spec& shadow);
// Everything the reference's pixels depend on (the cache's key).
std::string referenceKey(const RenderRequest& req, const RenderSettings& s, const Spec& refShadow);

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
// The anti-aliased exact reference: `settings` at samples x samples per pixel
// and per light texel, strands with their true width, box-filtered.
RenderResult::MoreReference renderAaReference(const RenderRequest& req, const Scene& scene,
                                              const RenderSettings& settings, const Spec& refShadow,
                                              int samples);
// The mean of each samples x samples block (the image's size divided by samples).
Image boxFilter(const Image& image, int samples);
VisibilityError visibilityError(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);
// Buckets 0, 1, 2-3, 4-7, ... of eye layers; errors averaged per bucket.
std::vector<LayerBucket> errorByLayers(const RenderResult& out, const DepthComplexity& eye,
                                       const std::vector<uint8_t>& referenceVisibility);
// The case's own error (OwnError), its reference rendered once per sweep.
OwnError ownError(const RenderRequest& req, Device& dev, const Scene& scene,
                  const RenderSettings& settings, const Spec& shadowSpec, const Spec& oitSpec,
                  const Spec& refShadow, const RenderResult& out, RenderCache* cache);
// Frames 1 .. N-1 of an animation, each by the technique and by the reference.
AnimationResult runAnimation(const RenderRequest& req, const Scene& scene,
                             const RenderSettings& settings, const Spec& shadowSpec,
                             const Spec& oitSpec, const Spec& refShadow, const RenderResult& out,
                             const RenderCache::Reference& ref);
std::vector<RenderResult::LightShare> lightShares(const RenderSettings& s, const RenderResult& r);
// The invariants of a finished run (harness/invariants.h), the reported errors included.
std::vector<InvariantFailure> checkInvariants(const RenderRequest& req, const RenderResult& out,
                                              const RenderSettings& settings, Renderer& renderer,
                                              Device& dev, const std::vector<float>& exactProbe);
// `error` of the report: {image (with an image), visibility, total, own}.
nlohmann::json errorJson(const RenderResult& r);

}  // namespace sb
