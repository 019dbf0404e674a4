#include "cli/render_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "harness/measures/animation/animation.h"
#include "harness/settings.h"
#include "reports/stats.h"

namespace sb {
namespace {

// Three significant digits ("22.1", "0.0208", "1.69e+03" never: times stay plain).
std::string sig3(double v) {
  char text[32];
  std::snprintf(text, sizeof text, std::fabs(v) >= 1000.0 ? "%.0f" : "%#.3g", v);
  return text;
}

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * fraction);
  return text;
}

std::string imageErrorText(const ImageError& e, const std::optional<FlipResult>& flip) {
  if (e.identical()) return "identical (PSNR infinite)";
  std::string s = "PSNR " + sig3(e.psnr) + " dB, RMSE " + sig3(e.rmse) + ", SSIM " + sig3(e.ssim);
  if (flip) s += ", FLIP mean " + sig3(flip->mean);
  return s + ", max |difference| " + sig3(e.maxAbs) + " (" + percent(e.fractionOver) +
         " of pixels over the threshold)";
}

std::string complexityText(const DepthComplexity& c) {
  return "max " + std::to_string(c.max) + " layers, mean " + sig3(c.mean) + " (" +
         std::to_string(c.total) + " fragments)";
}

}  // namespace

void printRenderSummary(std::ostream& out, const RenderRequest& req, const RenderResult& r) {
  out << req.scene << " | shadow " << req.shadow << " | oit " << req.oit << " | "
      << r.device.backend << "/" << r.device.platform << " (" << r.device.device << ") | "
      << r.scene.segments << " segments | " << req.primitive << " | " << req.width << "x"
      << req.height << "\n";
  if (!r.tier.empty()) out << "  tier " << r.tier << " (" << r.tierReason << ")\n";
  if (!r.scene.up.empty())
    out << "  file's up axis " << r.scene.up << ", turned to +y (" << r.scene.upReason
        << "); thickness: " << r.scene.thicknessSource << "\n";
  std::size_t width = 5;  // "frame"
  for (const PassTimes& p : r.passes) width = std::max(width, p.name.size());
  auto row = [&](const std::string& name, const std::string& median, const std::string& range) {
    out << "  " << name << std::string(width + 2 - name.size(), ' ') << median
        << std::string(median.size() < 12 ? 12 - median.size() : 1, ' ') << range << "\n";
  };
  row("pass", "median ms", "min-max over " + std::to_string(req.repeat) + " frames");
  for (const PassTimes& p : r.passes) {
    const Stats s = summarize(p.ms);
    row(p.name, sig3(s.median), sig3(s.min) + "-" + sig3(s.max));
  }
  const Stats frame = summarize(r.frameMs);
  row("frame", sig3(frame.median), sig3(frame.min) + "-" + sig3(frame.max));
  if (r.reference && (r.imageError || r.visibilityError)) {
    out << "  error against " << r.reference->first << " + " << r.reference->second << ":\n";
    if (r.imageError) out << "    image: " << imageErrorText(*r.imageError, r.flip) << "\n";
    if (r.visibilityError)
      out << "    visibility: RMSE " << sig3(r.visibilityError->rmse) << ", max "
          << sig3(r.visibilityError->max) << " (" << r.visibilityError->pixels << " pixels)\n";
  }
  for (const RenderResult::MoreReference& m : r.moreReferences)
    out << "  error against reference " << m.spec << " (" << m.width << "x" << m.height
        << " samples, " << sig3(m.wallMs / 1000.0) << " s, " << sig3(double(m.bytes) / (1 << 20))
        << " MiB" << (m.cached ? ", cached" : "")
        << "):\n    image: " << imageErrorText(m.image, m.flip) << "\n";
  if (const AnimationResult* a = r.measure<AnimationResult>()) {
    out << "  animation " << settingText(req, *findSetting("animate")) << ": flicker visibility "
        << sig3(a->visibilityFlicker);
    if (a->imageFlicker) out << ", image " << sig3(*a->imageFlicker);
    out << "\n";
  }
  if (r.eyeComplexity)
    out << "  depth complexity, eye: " << complexityText(*r.eyeComplexity) << "\n";
  if (r.lightComplexity)
    out << "  depth complexity, light: " << complexityText(*r.lightComplexity) << "\n";
  for (const auto& warning : r.warnings) out << "  warning: " << warning << "\n";
}

}  // namespace sb
