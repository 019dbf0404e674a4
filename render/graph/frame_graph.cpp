#include "render/graph/frame_graph.h"

#include <algorithm>

namespace sb {

namespace {
void addUnique(std::vector<GraphResource>& to, GraphResource r) {
  if (r.id != 0 && std::find(to.begin(), to.end(), r) == to.end()) to.push_back(r);
}
bool contains(const std::vector<GraphResource>& v, GraphResource r) {
  return std::find(v.begin(), v.end(), r) != v.end();
}
}  // namespace

void FrameGraph::add(std::string name, const std::vector<Pass>& passes,
                     std::function<void()> execute) {
  PassNode node{std::move(name), {}, {}, {}, std::move(execute)};
  for (const Pass& p : passes) {
    for (GraphResource r : p.reads())
      if (!contains(node.writes, r)) addUnique(node.reads, r);
    for (GraphResource r : p.writes()) addUnique(node.writes, r);
    for (GraphResource r : p.sideWrites()) addUnique(node.sideWrites, r);
  }
  nodes_.push_back(std::move(node));
}

std::string FrameGraph::name(GraphResource r) const {
  if (namer_) return namer_(r);
  return (r.texture ? "texture #" : "buffer #") + std::to_string(r.id);
}

std::vector<const PassNode*> FrameGraph::compile(const std::vector<GraphResource>& outputs) const {
  std::set<GraphResource> written;
  for (const auto& n : nodes_) {
    for (const auto& r : n.reads)
      if (r.texture && !written.count(r))
        throw std::logic_error("frame graph: pass '" + n.name + "' reads '" + name(r) +
                               "', which no earlier pass writes");
    written.insert(n.writes.begin(), n.writes.end());
  }
  std::set<GraphResource> needed(outputs.begin(), outputs.end());
  std::vector<const PassNode*> kept;
  for (auto it = nodes_.rbegin(); it != nodes_.rend(); ++it) {
    bool useful = false;
    for (const auto& w : it->writes) useful = useful || needed.count(w) > 0;
    if (!useful) continue;
    kept.insert(kept.begin(), &*it);
    needed.insert(it->reads.begin(), it->reads.end());
  }
  return kept;
}

}  // namespace sb
