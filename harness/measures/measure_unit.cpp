// The registry the measure folders fill (harness/measures/measure_unit.h).
#include "harness/measures/measure_unit.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>

#include "base/unit_folder.h"

namespace sb {

namespace {
// Filled during static initialisation, hence a function-local static.
std::map<std::string, MeasureDescriptor>& registry() {
  static std::map<std::string, MeasureDescriptor> measures;
  return measures;
}
}  // namespace

MeasureRegistrar::MeasureRegistrar(const char* file, MeasureDescriptor d) {
  d.folder = unitFolder(file, "harness/measures/", "measure");
  if (d.name.empty() || d.help.empty() || !d.measure)
    throw std::logic_error(std::string(file) + ": a measure needs a name, help and measure");
  const std::string name = d.name;
  if (!registry().emplace(name, std::move(d)).second)
    throw std::logic_error("two measures named " + name);
}

std::vector<const MeasureDescriptor*> measureCatalog() {
  std::vector<const MeasureDescriptor*> out;
  for (const auto& [name, d] : registry()) out.push_back(&d);  // by name
  std::stable_sort(
      out.begin(), out.end(),
      [](const MeasureDescriptor* a, const MeasureDescriptor* b) { return a->order < b->order; });
  return out;
}

std::vector<float> visibilityFloats(const std::vector<uint8_t>& bytes) {
  std::vector<float> v(bytes.size() / sizeof(float));
  std::memcpy(v.data(), bytes.data(), v.size() * sizeof(float));
  return v;
}

}  // namespace sb
