// The frame graph's planning (render/graph/frame_planner.h) on a real device,
// both backends: a frame's memory known before anything is made, the memory
// guard's refusals (of a plan and of each making), the storage range checked
// with the plan, and the labels and pass observer the Device's one hook serves.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "backends/device.h"
#include "base/errors.h"
#include "harness/render.h"
#include "render/graph/frame_planner.h"
#include "render/graph/pass.h"
#include "render_request.h"

namespace sb {
namespace {

class FramePlannerTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    DeviceOptions opts;
    opts.backend = GetParam();
    opts.platform = GetParam() == "vulkan" ? "headless" : "egl";
    try {
      dev_ = createDevice(opts);
    } catch (const DeviceError& e) {
      GTEST_SKIP() << GetParam() << " backend unavailable: " << e.what();
    }
  }
  std::size_t total(const std::vector<ResourceBytes>& rs) const {
    std::size_t bytes = 0;
    for (const auto& r : rs) bytes += r.bytes;
    return bytes;
  }
  // Refuses whatever would make the device hold more than `most` bytes.
  void limitTo(std::size_t most) {
    FramePlanner::of(*dev_).setMemoryGuard(
        [this, most](const std::vector<ResourceBytes>& planned, const std::string& what) {
          if (total(planned) > most)
            throw OutOfMemoryError(what + ": over " + std::to_string(most));
        });
  }
  std::unique_ptr<Device> dev_;
};

TEST_P(FramePlannerTest, AFramesMemoryIsKnownBeforeAnythingIsMade) {
  FramePlanner& planner = FramePlanner::of(*dev_);
  const uint32_t first = dev_->nextHandleId();
  const Buffer a = dev_->createBuffer({"a", Owner::Oit, BufferUsage::Storage, 4096});
  dev_->createTexture({"t", Owner::Frame, Format::RGBA32F, 8, 4, false});
  const std::set<uint32_t> ids = dev_->resourceIdsFrom(first);
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_TRUE(dev_->allocations().empty());
  const auto planned = planner.allocationsAfterUsing(ids);
  ASSERT_EQ(planned.size(), 2u);
  EXPECT_EQ(planned[0].name, "a");
  EXPECT_EQ(planned[1].owner, Owner::Frame);
  EXPECT_EQ(total(planned), 4096u + 8 * 4 * 16);
  // Control: a plan of nothing holds only what is made; using one makes it.
  EXPECT_TRUE(planner.allocationsAfterUsing({}).empty());
  dev_->fillBuffer(a, 0);
  EXPECT_EQ(planner.allocationsAfterUsing({}).size(), 1u);
  EXPECT_EQ(total(planner.allocationsAfterUsing(ids)), total(planned));
}

TEST_P(FramePlannerTest, TheMemoryGuardRefusesAPlanAndAMakingOverIt) {
  FramePlanner& planner = FramePlanner::of(*dev_);
  limitTo(8192);
  const uint32_t first = dev_->nextHandleId();
  const Buffer big = dev_->createBuffer({"big", Owner::Oit, BufferUsage::Storage, 8192 + 4});
  EXPECT_THROW(planner.guardMemory(dev_->resourceIdsFrom(first), "preparing oit"),
               OutOfMemoryError);
  try {
    dev_->fillBuffer(big, 0);
    ADD_FAILURE() << "a buffer over the guard's limit was made";
  } catch (const OutOfMemoryError& e) {
    EXPECT_NE(std::string(e.what()).find("making 'big' (oit)"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(dev_->allocations().empty());
  // Control: under the limit it is made; without a guard anything is.
  const Buffer small = dev_->createBuffer({"small", Owner::Oit, BufferUsage::Storage, 4096});
  EXPECT_NO_THROW(dev_->fillBuffer(small, 0));
  planner.setMemoryGuard(nullptr);
  EXPECT_NO_THROW(dev_->fillBuffer(big, 0));
  EXPECT_EQ(dev_->allocations().size(), 2u);
}

// A shader sees at most maxStorageBufferRange bytes of a storage buffer
// (Vulkan; 128 MiB on lavapipe) or GL_MAX_SHADER_STORAGE_BLOCK_SIZE (GL; 128
// MiB on llvmpipe): a larger one is refused when it would be made or planned
// (guardMemory), before any work, rather than bound in part (the exact
// reference's fragment pool at 512x512 once lost the strands drawn last that
// way; fragment pools now split into pages below it). The refusal comes after
// the memory guard's, which lists every resource.
TEST_P(FramePlannerTest, StorageBufferOverTheDevicesRangeIsRefusedBeforeItIsMade) {
  FramePlanner& planner = FramePlanner::of(*dev_);
  const std::size_t most = dev_->info().maxStorageBufferBytes;
  ASSERT_GT(most, 0u);
  auto expectRefused = [&](const std::function<void()>& use, const char* how) {
    try {
      use();
      ADD_FAILURE() << how << ": a storage buffer of " << most + 4 << " bytes was accepted";
    } catch (const DeviceError& e) {
      EXPECT_NE(std::string(e.what()).find("more than this device binds as one storage buffer"),
                std::string::npos)
          << how << ": " << e.what();
    }
  };
  const uint32_t first = dev_->nextHandleId();
  const Buffer big = dev_->createBuffer({"fragments", Owner::Oit, BufferUsage::Storage, most + 4});
  expectRefused([&] { planner.guardMemory(dev_->resourceIdsFrom(first), "preparing oit"); },
                "planned");
  expectRefused([&] { dev_->readBuffer(big); }, "first used");
  EXPECT_TRUE(dev_->allocations().empty());
  // A memory guard that refuses speaks first.
  planner.setMemoryGuard([](const std::vector<ResourceBytes>&, const std::string&) {
    throw OutOfMemoryError("over the budget");
  });
  EXPECT_THROW(planner.guardMemory(dev_->resourceIdsFrom(first), "preparing oit"),
               OutOfMemoryError);
  planner.setMemoryGuard(nullptr);
  // At the limit it is taken (planned only: making 128 MiB would spend time).
  const uint32_t atLimit = dev_->nextHandleId();
  dev_->createBuffer({"fragments", Owner::Oit, BufferUsage::Storage, most});
  EXPECT_NO_THROW(planner.guardMemory(dev_->resourceIdsFrom(atLimit), "preparing oit"));
}

// An extra light's resources and passes carry its prefix while its LabelScope
// lasts (scopes nest); the pass observer sees each pass, labelled, before it
// is recorded, and what it throws stops the pass.
TEST_P(FramePlannerTest, LabelsAndThePassObserver) {
  FramePlanner& planner = FramePlanner::of(*dev_);
  std::vector<std::string> seen;
  planner.setPassObserver([&seen](const std::string& pass) { seen.push_back(pass); });
  Texture plain, lit;
  {
    LabelScope light(*dev_, "light2.");
    lit = dev_->createTexture({"t", Owner::Frame, Format::RGBA8, 4, 4, false});
    {
      LabelScope key(*dev_, "");
      plain = dev_->createTexture({"t", Owner::Frame, Format::RGBA8, 4, 4, false});
    }
    EXPECT_EQ(planner.labelPrefix(), "light2.");
    dev_->beginFrame();
    Pass("clear").color(lit, LoadOp::Clear).draw(*dev_, Pipeline{}, 0);
    dev_->endFrame();
  }
  EXPECT_EQ(planner.labelPrefix(), "");
  EXPECT_EQ(dev_->describe(lit).name, "light2.t");
  EXPECT_EQ(dev_->describe(plain).name, "t");
  dev_->beginFrame();
  Pass("clear").color(plain, LoadOp::Clear).draw(*dev_, Pipeline{}, 0);
  dev_->endFrame();
  EXPECT_EQ(seen, (std::vector<std::string>{"light2.clear", "clear"}));
  ASSERT_EQ(dev_->lastFrameTimings().size(), 1u);
  EXPECT_EQ(dev_->lastFrameTimings()[0].name, "clear");
  // Control: an observer that throws stops the pass before the device looks
  // at it (outside a frame, the device's own refusal would come next).
  struct Stopped {};
  planner.setPassObserver([](const std::string&) { throw Stopped{}; });
  EXPECT_THROW(Pass("clear").color(plain, LoadOp::Clear).draw(*dev_, Pipeline{}, 0), Stopped);
}

// Each timed pass carries the owner of the graph node that began it: the
// bench sums a shadow technique's time by owner, not by name, so the passes a
// technique borrows (dsm runs the exact shadow's, named "exact.") count too.
TEST_P(FramePlannerTest, EachTimedPassCarriesItsOwner) {
  dev_.reset();  // runRender makes its own
  for (const char* shadow : {"osm:maps=2", "dsm"}) {
    SCOPED_TRACE(shadow);
    const RenderResult r = runRender(sbtest::smallRender(
        GetParam(), "straight:strands=20,points=4,head=1,alpha=0.5", shadow, "wavg", 16));
    std::size_t shadowPasses = 0, borrowed = 0;
    for (const PassTimes& p : r.passes) {
      SCOPED_TRACE(p.name);
      const auto startsWith = [&p](const char* prefix) { return p.name.rfind(prefix, 0) == 0; };
      EXPECT_NE(p.owner, Owner::None);
      if (startsWith("wavg.")) {
        EXPECT_EQ(p.owner, Owner::Oit);
      }
      if (startsWith("osm.") || startsWith("dsm.") || startsWith("exact.")) {
        EXPECT_EQ(p.owner, Owner::Shadow);
        ++shadowPasses;
        borrowed += startsWith("exact.") ? 1 : 0;
      } else {
        EXPECT_NE(p.owner, Owner::Shadow);
      }
    }
    EXPECT_GT(shadowPasses, 0u);
    if (std::string(shadow) == "dsm") {
      EXPECT_GT(borrowed, 0u);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, FramePlannerTest, ::testing::Values("gl", "vulkan"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           return param.param;
                         });

}  // namespace
}  // namespace sb
