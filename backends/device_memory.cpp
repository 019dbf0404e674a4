// The Device's memory: a resource is made on the device when first used (never
// when only culled passes use it), every making asks the memory guard first, and
// what is made or declared is counted here (allocations, declared, inventory:
// the frame graph plans from it, render/graph/frame_planner.h).
#include <algorithm>

#include "backends/device.h"
#include "backends/device_records.h"

namespace sb {

using device_detail::namingAllocation;
using device_detail::quoted;
using device_detail::textureBytes;

// Resources are declared by create*() and made on the device when a pass, a
// binding, an update or a read first uses them: what only culled passes use is
// never allocated, and allocations() counts exactly what was made.
DriverObject* Device::created(BufferRec& r) {
  if (!r.object) {
    const std::string what =
        "making buffer '" + r.desc.name + "' (" + ownerName(r.desc.owner) + ")";
    if (r.desc.usage == BufferUsage::AccelerationStructure) {
      // Its boxes first (their own accounting), then the structure built from them.
      DriverObject* boxes =
          created(buffer(r.aabbs, quoted("createAccelerationStructure", r.desc.name)));
      guardMaking(r.desc.name, r.desc.owner, r.desc.bytes);
      r.object = namingAllocation(what, r.desc.bytes, [&] {
        return driver_->createAccelerationStructure(r.desc, *boxes, r.boxes);
      });
      return r.object.get();
    }
    guardMaking(r.desc.name, r.desc.owner, r.desc.bytes);
    checkStorageRange(r.desc);
    r.object = namingAllocation(what, r.desc.bytes, [&] {
      return driver_->createBuffer(r.desc, r.pending.empty() ? nullptr : r.pending.data());
    });
    std::vector<uint8_t>().swap(r.pending);
  }
  return r.object.get();
}

DriverObject* Device::created(TextureRec& t) {
  if (!t.object) guardMaking(t.desc.name, t.desc.owner, textureBytes(t.desc));
  if (!t.object)
    t.object = namingAllocation(
        "making texture '" + t.desc.name + "' (" + ownerName(t.desc.owner) + ", " +
            formatName(t.desc.format) + " " + std::to_string(t.desc.width) + "x" +
            std::to_string(t.desc.height) + "x" + std::to_string(t.desc.layers) + ")",
        textureBytes(t.desc), [&] { return driver_->createTexture(t.desc); });
  return t.object.get();
}

void Device::setBufferSize(Buffer b, std::size_t bytes) {
  BufferRec& r = buffer(b, "setBufferSize");
  requireContents(r, "setBufferSize");
  const std::string where = quoted("setBufferSize", r.desc.name);
  if (bytes == 0) throw DeviceError(where + ": zero size");
  if (r.object) throw DeviceError(where + ": already made (sizes change only before first use)");
  if (!r.pending.empty()) throw DeviceError(where + ": created with contents of its own size");
  r.desc.bytes = bytes;
}

std::vector<Device::Held> Device::inventory() const {
  std::vector<Held> all;
  for (const auto& [id, r] : buffers_)
    all.push_back({id, {r->desc.name, r->desc.owner, r->desc.bytes}, r->object != nullptr});
  for (const auto& [id, t] : textures_)
    all.push_back({id, {t->desc.name, t->desc.owner, textureBytes(t->desc)}, t->object != nullptr});
  std::sort(all.begin(), all.end(), [](const Held& a, const Held& b) { return a.id < b.id; });
  return all;
}

std::vector<ResourceBytes> Device::resources(bool createdOnly) const {
  std::vector<ResourceBytes> out;
  for (Held& h : inventory())
    if (h.made || !createdOnly) out.push_back(std::move(h.bytes));
  return out;
}

void Device::makeDeferredBuffers() {
  for (auto& [id, r] : buffers_)
    if (!r->object && !r->pending.empty()) created(*r);
}

std::vector<ResourceBytes> Device::allocations() const { return resources(true); }

std::vector<ResourceBytes> Device::declared() const { return resources(false); }

void Device::checkStorageRanges(const std::set<uint32_t>& ids) const {
  for (const uint32_t id : ids)
    if (auto it = buffers_.find(id); it != buffers_.end()) checkStorageRange(it->second->desc);
}

// Refused before any work rather than bound in part (a shader would lose what
// lies beyond). Checked after the memory guard: a run over the budget hears
// that first, with every resource listed, since fitting it fixes both.
void Device::checkStorageRange(const BufferDesc& desc) const {
  const std::size_t most = driver_->info().maxStorageBufferBytes;
  if (desc.usage != BufferUsage::Storage || most == 0 || desc.bytes <= most) return;
  throw DeviceError(quoted("createBuffer", desc.name) + ": " + std::to_string(desc.bytes) +
                    " bytes, more than this device binds as one storage buffer (" +
                    std::to_string(most) + " bytes" +
                    (desc.owner == Owner::None ? "" : ", owner " + ownerName(desc.owner)) +
                    "); a smaller --size, map size=, scene or samples= would fit");
}

void Device::guardMaking(const std::string& name, Owner owner, std::size_t bytes) const {
  if (hook_) hook_->beforeMaking({name, owner, bytes});
}

std::set<uint32_t> Device::resourceIdsFrom(uint32_t first) const {
  std::set<uint32_t> ids;
  for (auto it = buffers_.lower_bound(first); it != buffers_.end(); ++it) ids.insert(it->first);
  for (auto it = textures_.lower_bound(first); it != textures_.end(); ++it) ids.insert(it->first);
  return ids;
}

MemoryBudget Device::memoryBudget() const { return driver_->memoryBudget(); }

}  // namespace sb
