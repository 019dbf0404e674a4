// A frame as a small graph of nodes. A node runs one or more declared passes
// (render/graph/pass.h); what it reads and writes follows from their
// declarations, resource by resource (device handles, not names). Nodes that
// no requested output depends on are left out, and the report lists the
// nodes that ran. A texture read that no earlier node writes is a technique
// bug (textures get contents only from passes), so compile() rejects it,
// naming the node and the texture; a buffer read that no node writes is an
// input filled from the CPU.
#pragma once

#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/graph/pass.h"

namespace sb {

struct PassNode {
  std::string name;
  std::vector<GraphResource> reads;
  std::vector<GraphResource> writes;
  // Written on the side (Inputs::sideOutput): also among the reads, and never
  // a reason to keep the node.
  std::vector<GraphResource> sideWrites;
  std::function<void()> execute;  // records the node's passes on the Device
};

class FrameGraph {
 public:
  // Names resources in messages (e.g. from Device::describe).
  using Namer = std::function<std::string(GraphResource)>;
  explicit FrameGraph(Namer namer = {}) : namer_(std::move(namer)) {}

  void add(PassNode node) { nodes_.push_back(std::move(node)); }
  // A node of one pass, named after it.
  void add(const Pass& pass, std::function<void()> execute) {
    add(pass.name(), {pass}, std::move(execute));
  }
  // A node of several passes, run by `execute` in this order (possibly
  // repeated, e.g. peeling): a read of what an earlier pass of the node
  // writes stays inside the node.
  void add(std::string name, const std::vector<Pass>& passes, std::function<void()> execute);

  // The nodes needed for the outputs, in submission order. Throws
  // std::logic_error for a texture read with no writer earlier in the graph.
  std::vector<const PassNode*> compile(const std::vector<GraphResource>& outputs) const;
  const std::vector<PassNode>& nodes() const { return nodes_; }

 private:
  std::string name(GraphResource r) const;

  Namer namer_;
  std::vector<PassNode> nodes_;
};

}  // namespace sb
