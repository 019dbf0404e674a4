// The own-error measure (own.h), its reference rendered once per sweep.
#include "harness/measures/measure_unit.h"
#include "harness/measures/own/own.h"
#include "harness/render_steps.h"
#include "render/frame/renderer.h"

namespace sb {
namespace {

// Which technique a case's own error judges, and its reference: exact in the
// other family only.
struct OwnReference {
  std::string technique;
  Spec shadow, oit;
};
OwnReference ownReference(const Spec& shadowSpec, const Spec& oitSpec, const Spec& refShadow) {
  if (oitSpec.name != "none") return {"transparency", shadowSpec, Spec::parse(kReferenceOit)};
  return {"shadow", refShadow, oitSpec};
}

std::shared_ptr<const MeasureSlice> measure(const MeasureInputs& in) {
  if (!in.req.reference || !in.reference) return nullptr;
  const RenderResult& out = in.out;
  const OwnReference o = ownReference(in.shadow, in.oit, in.refShadow);
  auto e = std::make_shared<OwnError>();
  e->technique = o.technique;
  e->referenceShadow = o.shadow.str();
  e->referenceOit = o.oit.str();
  if (o.technique == "shadow") e->visibility = out.visibilityError;
  if (!in.req.image) return e;
  // Exact transparency is exact at pixel centres: one sample, as the full reference.
  RenderSettings own = in.settings;
  if (o.technique == "transparency") own.msaa = 1;
  const std::string key = referenceKey(in.req, in.settings, o.shadow) + "|own " + o.shadow.str() +
                          " " + o.oit.str() + "|msaa " + std::to_string(own.msaa);
  Image fresh;
  const Image* image = nullptr;
  if (o.shadow.str() == in.refShadow.str() && o.oit.str() == kReferenceOit) {
    image = &out.referenceImage;  // exact in both families: the full reference
  } else if (in.cache && in.cache->ownReferences.count(key)) {
    image = &in.cache->ownReferences.at(key);
  } else {
    Renderer r(in.dev, in.scene, own, o.shadow, o.oit, {Output::Color});
    r.renderFrame();
    fresh = colorImage(r, own);
    image = in.cache ? &(in.cache->ownReferences[key] = std::move(fresh)) : &fresh;
  }
  e->image = compareImages(out.image, *image);
  e->flipMean = computeFlip(out.image, *image).mean;
  return e;
}

}  // namespace

void OwnError::errorJson(nlohmann::json& error) const {
  nlohmann::json own = {{"technique", technique},
                        {"reference", {{"shadow", referenceShadow}, {"oit", referenceOit}}}};
  if (image) own["image"] = toJson(*image);
  if (flipMean) own["image"]["flip"] = {{"mean", *flipMean}};
  if (visibility) own["visibility"] = visibilityJson(*visibility);
  error["own"] = own;
}

}  // namespace sb

SB_MEASURE({.name = "own",
            .help = "with a reference: the case's own technique against exact in its other "
                    "family only (error.own)",
            .measure = sb::measure});
