// The frame graph's planning (as Filament's frame graph owns resource
// planning): what a frame will hold before it runs, the memory guard that
// refuses a run before its memory is taken, an observer of the passes as they
// are recorded, and the labels that set an extra light's passes and resources
// apart. The Device only makes, frees and counts; it calls its one hook
// (Device::Hook), which this planner is.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "backends/device.h"

namespace sb {

class FramePlanner final : public Device::Hook {
 public:
  // The device's planner, installed on it (Device::setHook) when first asked for.
  static FramePlanner& of(Device& dev);

  // What dev.allocations() will be once the resources with these ids (buffer
  // and texture handle ids) have been used: known before any of them is made.
  std::vector<ResourceBytes> allocationsAfterUsing(const std::set<uint32_t>& ids) const;

  // A refusal before memory is taken: set (by the harness) for a run, the
  // guard is called with what the device will hold before any resource is
  // made, and by guardMemory; it throws to refuse. Null: none.
  using MemoryGuard =
      std::function<void(const std::vector<ResourceBytes>& planned, const std::string& what)>;
  void setMemoryGuard(MemoryGuard guard) { memoryGuard_ = std::move(guard); }
  // The guard's verdict on making the resources with these ids (the renderer
  // asks it before a technique's preparation, which makes what it declared),
  // then the device's refusal of any storage buffer among them over its range.
  void guardMemory(const std::set<uint32_t>& ids, const std::string& what) const;

  // Called with a pass's name before it is recorded: the harness counts passes
  // for its progress line and stops a run there. Null: none.
  void setPassObserver(std::function<void(const std::string& pass)> observer) {
    passObserver_ = std::move(observer);
  }

  // Passes begun or dispatched on the device so far (a node's are the
  // difference across its execution).
  std::size_t passesBegun() const { return passesBegun_; }

  // Puts `prefix` before the name of every buffer and texture created and every
  // pass begun or dispatched from now on ("" stops): the renderer's extra lights
  // run the same techniques again, and their memory and times stand apart by
  // name ("light2.osm.atlases", "light2.osm.map"). LabelScope sets it for a block.
  void setLabelPrefix(std::string prefix) { labelPrefix_ = std::move(prefix); }
  const std::string& labelPrefix() const { return labelPrefix_; }

  // Device::Hook
  std::string label(const std::string& name) const override { return labelPrefix_ + name; }
  void beforeMaking(const ResourceBytes& resource) override;
  void beforePass(const std::string& pass) override;

 private:
  explicit FramePlanner(Device& dev) : dev_(dev) {}

  Device& dev_;
  MemoryGuard memoryGuard_;
  std::function<void(const std::string&)> passObserver_;
  std::string labelPrefix_;
  std::size_t passesBegun_ = 0;
};

// FramePlanner::setLabelPrefix for the lifetime of the scope, then the previous prefix again.
class LabelScope {
 public:
  LabelScope(Device& dev, std::string prefix)
      : planner_(FramePlanner::of(dev)), previous_(planner_.labelPrefix()) {
    planner_.setLabelPrefix(std::move(prefix));
  }
  ~LabelScope() { planner_.setLabelPrefix(previous_); }
  LabelScope(const LabelScope&) = delete;
  LabelScope& operator=(const LabelScope&) = delete;

 private:
  FramePlanner& planner_;
  std::string previous_;
};

}  // namespace sb
