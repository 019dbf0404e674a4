// The cost model (reports/cost_model.h): non-negative least squares, the fit of frame
// time against work counters, the cases it marks, and too few cases to fit.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reports/cost_model.h"

using nlohmann::json;
using sb::report::CostModel;

namespace {

constexpr double kMiB = 1024.0 * 1024.0;

// A result with frame work of `mfrags` million fragments, `mib` MiB of bytes (split
// over written, read and storage), `verts` vertices and `passes` pass executions.
json makeCase(int i, double ms, double mfrags, double mib, double verts, int passes) {
  json passList = json::array();
  for (int p = 0; p < passes; ++p)
    passList.push_back({{"name", "pass" + std::to_string(p)}, {"executions", 1}});
  return {{"backend", "gl"},
          {"device", "testpipe"},
          {"shadow", "osm:maps=" + std::to_string(i)},
          {"oit", "none"},
          {"case", {{"id", "case" + std::to_string(i)}, {"group", "g"}}},
          {"frame_ms", {{"median", ms}}},
          {"passes", passList},
          {"frame_work",
           {{"fragment_invocations", mfrags * 1e6},
            {"vertex_invocations", verts},
            {"compute_invocations", 0},
            {"samples_passed", nullptr},
            {"bytes_written", mib * kMiB / 2},
            {"bytes_read", mib * kMiB / 4},
            {"bytes_storage", mib * kMiB / 4}}}};
}

// Work that varies independently per case (no two counters proportional).
struct Work {
  double mfrags, mib, verts;
  int passes;
};
std::vector<Work> works(int n) {
  std::vector<Work> w;
  for (int i = 0; i < n; ++i)
    w.push_back({0.5 + 0.37 * ((i * 7) % 11), 1.0 + 2.3 * ((i * 5) % 7), 1000.0 * (1 + (i * 3) % 5),
                 1 + (i % 4)});
  return w;
}

std::vector<const json*> pointers(const std::vector<json>& docs) {
  std::vector<const json*> out;
  for (const json& d : docs) out.push_back(&d);
  return out;
}

double coefficient(const CostModel& m, const std::string& name) {
  for (const auto& t : m.terms)
    if (t.name == name) return t.coefficient;
  ADD_FAILURE() << "no term " << name;
  return NAN;
}

}  // namespace

TEST(CostModel, NnlsSolvesExactAndClampsNegative) {
  // b = 2 a0 + 3 a1: recovered exactly.
  const std::vector<std::vector<double>> a = {{1, 0}, {0, 1}, {1, 1}, {2, 1}};
  std::vector<double> x = sb::report::nnls(a, {2, 3, 5, 7});
  ASSERT_EQ(x.size(), 2u);
  EXPECT_NEAR(x[0], 2, 1e-9);
  EXPECT_NEAR(x[1], 3, 1e-9);
  // b = -1 a0 + 2 a1: unconstrained would give a0 < 0; NNLS keeps it at 0.
  x = sb::report::nnls(a, {-1, 2, 1, 0});
  EXPECT_EQ(x[0], 0);
  EXPECT_GE(x[1], 0);
}

TEST(CostModel, RecoversExactCoefficients) {
  std::vector<json> docs;
  int i = 0;
  for (const Work& w : works(12))
    docs.push_back(makeCase(i++, 2 * w.mfrags + 3 * w.mib + 1, w.mfrags, w.mib, w.verts, w.passes));
  const auto models = sb::report::fitCostModels(pointers(docs));
  ASSERT_EQ(models.size(), 1u);
  const CostModel& m = models[0];
  ASSERT_TRUE(m.fitted) << m.note;
  EXPECT_EQ(m.backend, "gl");
  EXPECT_EQ(m.device, "testpipe");
  ASSERT_TRUE(m.r2);
  EXPECT_NEAR(*m.r2, 1.0, 1e-9);
  EXPECT_NEAR(coefficient(m, "fragments"), 2.0, 1e-6);  // ms per million fragments
  EXPECT_NEAR(coefficient(m, "bytes"), 3.0, 1e-6);      // ms per MiB
  EXPECT_NEAR(coefficient(m, "constant"), 1.0, 1e-6);
  EXPECT_NEAR(coefficient(m, "vertices"), 0.0, 1e-6);
  EXPECT_NEAR(coefficient(m, "passes"), 0.0, 1e-6);
  for (const auto& t : m.terms) EXPECT_NE(t.name, "compute");  // zero throughout: left out
  for (const auto& c : m.cases) {
    ASSERT_TRUE(c.ratio);
    EXPECT_NEAR(*c.ratio, 1.0, 1e-6) << c.caseId;
    EXPECT_FALSE(c.inefficient) << c.caseId;
  }
  const json j = sb::report::costModelsJson(models);
  EXPECT_NEAR(j["models"][0]["r2"].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(j["models"][0]["cases"].size(), 12u);
}

TEST(CostModel, FlagsACaseFarSlowerThanItsWork) {
  std::vector<json> docs;
  int i = 0;
  for (const Work& w : works(14)) {
    const double ms = 2 * w.mfrags + 3 * w.mib + 1;
    docs.push_back(makeCase(i, i == 5 ? 5 * ms : ms, w.mfrags, w.mib, w.verts, w.passes));
    ++i;
  }
  // A failed case and one without counters take no part.
  docs.push_back({{"backend", "gl"},
                  {"device", "testpipe"},
                  {"case", {{"id", "failed"}}},
                  {"failed", {{"reason", "out of memory"}}}});
  docs.push_back({{"backend", "gl"},
                  {"device", "testpipe"},
                  {"case", {{"id", "old"}}},
                  {"frame_ms", {{"median", 3.0}}}});
  const auto models = sb::report::fitCostModels(pointers(docs));
  ASSERT_EQ(models.size(), 1u);
  const CostModel& m = models[0];
  ASSERT_TRUE(m.fitted) << m.note;
  ASSERT_EQ(m.cases.size(), 14u);
  EXPECT_NE(m.note.find("1 case without work counters"), std::string::npos) << m.note;
  // Sorted by measured / predicted: the slow case first, and only it marked.
  EXPECT_EQ(m.cases[0].caseId, "case5");
  EXPECT_TRUE(m.cases[0].inefficient);
  ASSERT_TRUE(m.cases[0].ratio);
  EXPECT_GT(*m.cases[0].ratio, 2.0);
  for (std::size_t k = 1; k < m.cases.size(); ++k) EXPECT_FALSE(m.cases[k].inefficient);
  // Refitted without it: the others' costs as they are, and R² = 1 over the fit.
  EXPECT_FALSE(m.cases[0].inFit);
  EXPECT_EQ(m.fitCases, 13);
  EXPECT_NEAR(coefficient(m, "fragments"), 2.0, 1e-6);
  EXPECT_NEAR(coefficient(m, "bytes"), 3.0, 1e-6);
  EXPECT_NEAR(coefficient(m, "constant"), 1.0, 1e-6);
  ASSERT_TRUE(m.r2 && m.r2All);
  EXPECT_NEAR(*m.r2, 1.0, 1e-9);
  EXPECT_LT(*m.r2All, 0.9);
}

TEST(CostModel, CoefficientsStayNonNegative) {
  // Time falls as fragments grow: least squares would give fragments a negative cost.
  std::vector<json> docs;
  int i = 0;
  for (const Work& w : works(12))
    docs.push_back(
        makeCase(i++, 20 - 2 * w.mfrags + 0.5 * w.mib, w.mfrags, w.mib, w.verts, w.passes));
  const auto models = sb::report::fitCostModels(pointers(docs));
  ASSERT_EQ(models.size(), 1u);
  ASSERT_TRUE(models[0].fitted);
  for (const auto& t : models[0].terms) EXPECT_GE(t.coefficient, 0.0) << t.name;
  EXPECT_EQ(coefficient(models[0], "fragments"), 0.0);
  ASSERT_TRUE(models[0].r2);
  EXPECT_LT(*models[0].r2, 1.0);
}

TEST(CostModel, TooFewCasesGiveNoFit) {
  // Five terms (fragments, vertices, bytes, passes, constant) need seven cases.
  std::vector<json> docs;
  int i = 0;
  for (const Work& w : works(6))
    docs.push_back(makeCase(i++, 2 * w.mfrags + 1, w.mfrags, w.mib, w.verts, w.passes));
  const auto models = sb::report::fitCostModels(pointers(docs));
  ASSERT_EQ(models.size(), 1u);
  EXPECT_FALSE(models[0].fitted);
  EXPECT_FALSE(models[0].r2);
  EXPECT_NE(models[0].note.find("too few cases to fit"), std::string::npos) << models[0].note;
  EXPECT_EQ(models[0].cases.size(), 6u);
  const json j = sb::report::costModelsJson(models);
  EXPECT_TRUE(j["models"][0]["r2"].is_null());
}

TEST(CostModel, OneModelPerBackendAndDevice) {
  std::vector<json> docs;
  int i = 0;
  for (const Work& w : works(8)) {
    json c = makeCase(i++, 2 * w.mfrags + 1, w.mfrags, w.mib, w.verts, w.passes);
    docs.push_back(c);
    c["backend"] = "vulkan";
    docs.push_back(c);
  }
  const auto models = sb::report::fitCostModels(pointers(docs));
  ASSERT_EQ(models.size(), 2u);
  EXPECT_EQ(models[0].backend, "gl");
  EXPECT_EQ(models[1].backend, "vulkan");
  EXPECT_EQ(models[1].cases.size(), 8u);
}
