// Visual-regression baselines: the manifest (baselines/manifest.json), the
// pass/fail rule, `strandbench check` and `strandbench bless`.
//
// Manifest (JSON, one object; every object may carry a "comment" string):
//   {
//     "format": 2,
//     "tolerances": { "<preset>": {"max_abs": .., "max_failing_fraction": ..,
//                                   "failing_threshold": .., "min_psnr": ..,
//                                   "max_flip_mean": .. (optional)}, ... },
//     "defaults": { <any case key except name and scene> },
//     "cases": [ { "name": "straight-lines",          // [A-Za-z0-9_-]+, unique
//                  "scene": "straight:strands=300",   // --scene spec
//                  <any setting of harness/settings.h by its key: "shadow", "size",
//                   "camera_eye", "light_color", ...>,
//                  "backends": ["gl", "vulkan"],      // or "backend": "gl"
//                  "tolerance": "<preset>" or {fields overriding the default's} }, ... ]
//   }
// A case key that is absent comes from "defaults", then from the settings' own
// defaults, except repeat 1 and warmup 0 (one frame); name, scene, size and a
// complete tolerance must be known. Unknown keys are errors.
// Format 1 (the committed manifest's) is still read: its cases take only scene,
// shadow, oit, size (a "WxH" string), primitive, ribbon_width and backends; a
// further setting is refused with a message asking for "format": 2.
// Images are "<case>.<backend>.png", 16-bit PNG, beside the manifest.
//
// Tolerance (all comparisons are on RGB as a 16-bit PNG stores it, i.e. values
// clamped to [0, 1] and rounded to 1/65535): a comparison passes when
//   max |a - b| <= max_abs, and
//   the fraction of pixels whose largest channel difference exceeds
//     failing_threshold is <= max_failing_fraction, and
//   PSNR >= min_psnr (dB; identical images have PSNR +inf), and
//   mean FLIP (LDR-FLIP at 67 ppd, imaging/flip.h) <= max_flip_mean.
// max_abs, min_psnr and max_flip_mean may be null (no limit); max_flip_mean may
// also be left out (no limit, and FLIP is not computed).
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/render.h"
#include "imaging/image.h"
#include "imaging/metrics.h"

namespace sb {

struct Tolerance {
  double maxAbs = 0.0;                                           // +inf: no limit
  double maxFailingFraction = 0.0;                               // 0..1
  double failingThreshold = 0.0;                                 // >= 0
  double minPsnr = 0.0;                                          // dB; -inf: no limit
  double maxFlipMean = std::numeric_limits<double>::infinity();  // 0..1; +inf: no limit
};

struct BaselineCase {
  std::string name;
  RenderRequest request;  // every setting but the backend
  std::vector<std::string> backends = backendNames();
  Tolerance tolerance;
  // "driver_tolerances": a driver's own tolerance (by driverKey), over `tolerance`.
  std::map<std::string, Tolerance> driverTolerances;
};

struct Manifest {
  std::filesystem::path file;  // the manifest.json it came from
  std::vector<BaselineCase> cases;
};

// Reads and validates a manifest. Throws InputError naming the file: with the
// line and column for invalid JSON; with the case and key for an unknown key, a
// wrong type, a bad value, a duplicate or missing name.
Manifest loadManifest(const std::filesystem::path& file);

// The cases whose name matches `regex` (std::regex_search, ECMAScript); all for
// an empty filter. Throws InputError for a bad regex or when nothing matches.
std::vector<BaselineCase> selectCases(const Manifest& m, const std::string& regex);

// "<case>.<backend>.png"
std::string baselineFileName(const std::string& caseName, const std::string& backend);

// The render request of one case on one backend.
RenderRequest caseRequest(const BaselineCase& c, const std::string& backend);

// What a 16-bit PNG stores: round(clamp(v, 0, 1) * 65535) / 65535 per sample;
// NaN stays NaN so that a comparison still sees it.
Image quantize16(const Image& img);

// The result of comparing an image against a reference under a tolerance.
struct Verdict {
  ImageError error;                   // compareImages(actual, expected, failingThreshold)
  std::optional<FlipResult> flip;     // computeFlip(actual, expected), with a max_flip_mean
  std::vector<std::string> failures;  // one human-readable reason per violated limit
  bool ok() const { return failures.empty(); }
};
// Throws InputError when the sizes differ.
Verdict judge(const Image& actual, const Image& expected, const Tolerance& t);

// `strandbench check`.
struct CheckOptions {
  std::filesystem::path baselines, outDir;
  std::string filter;
  // The expectations file: empty for <baselines>/expectations/<driver>.json where it
  // exists (harness/expectations.h), "none" for none.
  std::string expectations;
  int retries = 2;  // re-runs of a case with a failure nobody expected
};
// Renders the selected cases on each of their backends (on this process's driver),
// compares each with its most specific baseline ("<case>.<backend>.<driver>.png", else
// "<case>.<backend>.png") and the backends with the first one, under the case's
// tolerance for the driver; classifies each comparison with the driver's expectations and
// re-runs: OK, FAILED (every run), FLAKE (failed, then passed on a re-run; or a listed
// flake that failed), EXPECTED FAIL, UNEXPECTED PASS (listed as failing, passed), SKIP,
// MISSING. Prints a line per comparison and the counts; writes actual, expected, diff
// heatmap and JSON numbers of each comparison that did not pass to `outDir`.
// Returns 1 when anything failed, is missing or passed unexpectedly, else 0.
// Throws InputError / DeviceError.
int runCheck(const CheckOptions& options, std::ostream& out);

// `strandbench bless`: copies `baselines` to a staging folder beside it, renders
// the selected cases into it, and swaps it in with renameat2(RENAME_EXCHANGE)
// (two renames where the filesystem refuses); the old copy is removed. Staging
// leftovers of an interrupted bless ("<parent>/.<name>.bless-*") are removed
// first. Env SB_BLESS_ABORT_AFTER=N: std::_Exit(3) after writing N images into
// staging (a test hook that simulates a kill). Returns 0.
int runBless(const std::filesystem::path& baselines, const std::string& filter, std::ostream& out);

// Swaps two existing directory entries atomically (renameat2 RENAME_EXCHANGE);
// where the filesystem does not support it, renames `current` to `aside` and
// `replacement` to `current` (then `replacement` no longer exists and `aside`
// holds the old one). Returns the path that now holds the old contents.
// Throws InputError on failure.
std::filesystem::path swapDirectories(const std::filesystem::path& replacement,
                                      const std::filesystem::path& current,
                                      const std::filesystem::path& aside);

// The repository's baselines folder (SB_SOURCE_DIR/baselines).
std::filesystem::path defaultBaselinesDir();

}  // namespace sb
