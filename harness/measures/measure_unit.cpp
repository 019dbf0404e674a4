// The registry the measure folders fill (harness/measures/measure_unit.h).
#include "harness/measures/measure_unit.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "base/unit_registry.h"

namespace sb {

namespace {
UnitRegistry<MeasureDescriptor>& registry() {
  static UnitRegistry<MeasureDescriptor> measures("measure", "harness/measures/");
  return measures;
}
}  // namespace

MeasureRegistrar::MeasureRegistrar(const char* file, MeasureDescriptor d) {
  if (d.help.empty() || !d.measure)
    throw std::logic_error(std::string(file) + ": a measure needs a name, help and measure");
  registry().add(file, std::move(d));
}

std::vector<const MeasureDescriptor*> measureCatalog() {
  std::vector<const MeasureDescriptor*> out = registry().all();  // by name
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
