#include "reports/files.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "base/errors.h"

namespace sb {

void writeFileAtomic(const std::filesystem::path& path, const std::string& contents) {
  // mkstemp gives a unique name, so two writers never share a temporary file.
  std::string pattern = path.string() + ".tmp-XXXXXX";
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw InputError(path.string() + ": cannot write (folder missing or not writable)");
  const std::string tmp(name.data());
  std::size_t done = 0;
  bool ok = true;
  while (ok && done < contents.size()) {
    const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
    ok = n > 0;
    if (ok) done += static_cast<std::size_t>(n);
  }
  ok = ::fsync(fd) == 0 && ok;
  ok = ::close(fd) == 0 && ok;
  std::error_code ec;
  if (ok) std::filesystem::rename(tmp, path, ec);
  if (!ok || ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path.string() + ": write failed");
  }
}

std::string readTextFile(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path.string() + ": cannot read (missing or not readable)");
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace sb
