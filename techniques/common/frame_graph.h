// A frame as a small graph of passes. Each pass declares the named resources
// it reads and writes; passes that no requested output depends on are left
// out, and the report lists the passes that ran. A read that no pass writes is
// a technique bug (a misspelled name would silently cull its writer), so
// compile() rejects it, naming the pass and the resource.
#pragma once

#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace sb {

struct PassNode {
  std::string name;
  std::vector<std::string> reads;
  std::vector<std::string> writes;
  std::function<void()> execute;  // records the pass on the Device
};

class FrameGraph {
 public:
  void add(PassNode pass) { passes_.push_back(std::move(pass)); }
  // The passes needed for the outputs, in submission order. Throws
  // std::logic_error for a read with no writer earlier in the graph.
  std::vector<const PassNode*> compile(const std::set<std::string>& outputs) const {
    std::set<std::string> written;
    for (const auto& p : passes_) {
      for (const auto& r : p.reads)
        if (!written.count(r))
          throw std::logic_error("frame graph: pass '" + p.name + "' reads '" + r +
                                 "', which no earlier pass writes");
      written.insert(p.writes.begin(), p.writes.end());
    }
    std::set<std::string> needed = outputs;
    std::vector<const PassNode*> kept;
    for (auto it = passes_.rbegin(); it != passes_.rend(); ++it) {
      bool useful = false;
      for (const auto& w : it->writes) useful = useful || needed.count(w) > 0;
      if (!useful) continue;
      kept.insert(kept.begin(), &*it);
      needed.insert(it->reads.begin(), it->reads.end());
    }
    return kept;
  }
  const std::vector<PassNode>& passes() const { return passes_; }

 private:
  std::vector<PassNode> passes_;
};

}  // namespace sb
