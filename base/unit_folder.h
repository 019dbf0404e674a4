// The folder a unit registers from: the one after the last `root` in its unit.cpp's
// __FILE__ (absolute or relative), as "pbr" in ".../harness/references/pbr/unit.cpp".
#pragma once

#include <stdexcept>
#include <string>

namespace sb {

inline std::string unitFolder(const std::string& file, const std::string& root,
                              const std::string& what) {
  const std::size_t at = file.rfind(root);
  if (at == std::string::npos)
    throw std::logic_error(file + ": a " + what + " registers from " + root + "<folder>/unit.cpp");
  const std::size_t begin = at + root.size();
  return file.substr(begin, file.find('/', begin) - begin);
}

}  // namespace sb
