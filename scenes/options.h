// Reading "key=value" options of a Spec with validation: unknown names get the
// closest valid name in the message, values are range-checked. Shared by
// scenes and techniques.
#pragma once

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sb {

// The valid name closest to `name` by edit distance ("" when none is close).
std::string closestName(const std::string& name, const std::vector<std::string>& valid);

// "unknown <kind> '<name>' (did you mean '<closest>'?); valid <kind>s: a, b, c"
std::string unknownNameMessage(const std::string& kind, const std::string& name,
                               const std::vector<std::string>& valid);

class OptionReader {
 public:
  // what: e.g. "scene 'curly'" or "shadow technique 'shadowmap'", used in messages.
  // Throws InputError for an option not in `known`, and for a typed option
  // (given or default) that its declaration refuses.
  OptionReader(const Spec& spec, const std::vector<OptionInfo>& known, std::string what);
  double number(const std::string& name, double min, double max) const;
  long long integer(const std::string& name, long long min, long long max) const;
  std::string choice(const std::string& name, const std::vector<std::string>& valid) const;
  // A typed option, read with its declared range or choices.
  double number(const std::string& name) const;
  long long integer(const std::string& name) const;
  std::string choice(const std::string& name) const;
  bool flag(const std::string& name) const;  // "on" | "off"
  std::string text(const std::string& name) const;
  bool has(const std::string& name) const;  // given explicitly

 private:
  std::string raw(const std::string& name) const;  // given value or the default
  const OptionInfo& declared(const std::string& name) const;
  void validate(const OptionInfo& o) const;
  const Spec& spec_;
  const std::vector<OptionInfo>& known_;
  std::string what_;
};

}  // namespace sb
