#include "harness/version.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <sstream>

#include "backends/device.h"
#include "backends/driver_env.h"
#include "harness/backend_names.h"
#include "sb_version.h"

namespace sb {

namespace {

const char* yesNo(bool b) { return b ? "yes" : "no"; }

// Runs `/proc/self/exe --version-probe` with `driver`'s environment: a process of its
// own per driver, since one process never loads two Mesas. Its stdout, or why not.
std::string probeDriver(const std::string& driver) {
  int fds[2];
  if (pipe(fds) != 0) return "  unavailable (pipe failed)\n";
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return "  unavailable (fork failed)\n";
  }
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    try {
      setDriverEnvironment(driver);
    } catch (const std::exception& e) {
      std::printf("  unavailable (%s)\n", e.what());
      std::fflush(stdout);
      _exit(2);
    }
    char arg0[] = "strandbench";
    char arg1[] = "--version-probe";
    char* args[] = {arg0, arg1, nullptr};
    execv("/proc/self/exe", args);
    _exit(127);
  }
  close(fds[1]);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) != 0;) {
    if (n < 0) break;
    out.append(buf, static_cast<size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    out += "  probe failed (" +
           (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                : "exit status " + std::to_string(WEXITSTATUS(status))) +
           ")\n";
  return out;
}

}  // namespace

std::string versionProbeText() {
  std::ostringstream out;
  // Every platform of every backend; the platform is named where a backend has several.
  for (const auto& b : backendCatalog())
    for (const auto& platform : b.platforms) {
      out << "  " << b.name << (b.platforms.size() > 1 ? " (" + platform + ")" : "") << ": ";
      if (isWindowPlatform(platform)) {  // not opened here: a window would flash up
        out << "a GLFW window (needs a display; not opened by --version)\n";
        continue;
      }
      try {
        const DeviceInfo info = createDevice({b.name, platform, false})->info();
        out << info.device << "; " << info.driver << "\n    "
            << (b.name == "gl" ? "OpenGL " : "Vulkan ") << info.apiVersion
            << "; ray query: " << yesNo(info.rayQuery)
            << ", mesh shaders: " << yesNo(info.meshShaders)
            << ", fragment shader interlock: " << yesNo(info.fragmentShaderInterlock)
            << ", pipeline statistics: " << yesNo(!info.counters.empty())
            << ", timestamps: " << yesNo(info.timestamps) << "\n";
      } catch (const std::exception& e) {
        out << "unavailable (" << e.what() << ")\n";
      }
    }
  return out.str();
}

std::string versionText() {
  std::ostringstream out;
  out << "strandbench " << SB_VERSION << "\n";
  out << "commit: " << SB_GIT_COMMIT << (SB_GIT_DIRTY ? " (with uncommitted changes)" : "") << "\n";
  out << "build type: " << SB_BUILD_TYPE << "\n";
  out << "drivers (--driver NAME; " << driversFolder().string()
      << "/ holds the named ones, scripts/drivers.sh fetches them):\n";
  for (const std::string& name : driverNames()) {
    out << name << (name == currentDriver() ? " (this process)" : "") << ":\n";
    out << probeDriver(name);
  }
  std::string text = out.str();
  text.pop_back();  // CLI11 ends the message with its own newline
  return text;
}

}  // namespace sb
