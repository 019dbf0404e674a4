#include "render/graph/frame_planner.h"

#include <memory>
#include <stdexcept>

namespace sb {

FramePlanner& FramePlanner::of(Device& dev) {
  if (!dev.hook()) dev.setHook(std::unique_ptr<Device::Hook>(new FramePlanner(dev)));
  auto* planner = dynamic_cast<FramePlanner*>(dev.hook());
  if (!planner) throw std::logic_error("FramePlanner::of: the device has another hook");
  return *planner;
}

std::vector<ResourceBytes> FramePlanner::allocationsAfterUsing(
    const std::set<uint32_t>& ids) const {
  std::vector<ResourceBytes> planned;
  for (Device::Held& h : dev_.inventory())
    if (h.made || ids.count(h.id)) planned.push_back(std::move(h.bytes));
  return planned;
}

void FramePlanner::guardMemory(const std::set<uint32_t>& ids, const std::string& what) const {
  if (memoryGuard_) memoryGuard_(allocationsAfterUsing(ids), what);
  dev_.checkStorageRanges(ids);
}

void FramePlanner::beforeMaking(const ResourceBytes& resource) {
  if (!memoryGuard_) return;
  std::vector<ResourceBytes> planned = dev_.allocations();
  planned.push_back(resource);
  memoryGuard_(planned, "making '" + resource.name + "' (" + ownerName(resource.owner) + ")");
}

void FramePlanner::beforePass(const std::string& pass) {
  ++passesBegun_;
  if (passObserver_) passObserver_(pass);
}

}  // namespace sb
