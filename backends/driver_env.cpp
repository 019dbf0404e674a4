#include "backends/driver_env.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <system_error>

#include "base/errors.h"

namespace sb {

namespace fs = std::filesystem;

const char* const kDriverHelp =
    "the driver: system, a folder under drivers/ by name (scripts/drivers.sh fetches "
    "mesa-25.0) or a path to one; the process re-executes itself with that driver's loader "
    "environment (docs/drivers.md)";

namespace {

constexpr const char* kMarker = "SB_DRIVER";  // the driver this process was started with
// LD_LIBRARY_PATH before a driver prepended its folder ("-": it was unset), so that a
// child started with the system driver gets the user's own back.
constexpr const char* kSavedLibraryPath = "SB_DRIVER_SAVED_LD_LIBRARY_PATH";
// What a driver folder sets; cleared again for the system driver.
constexpr const char* kLoaderVariables[] = {
    "VK_DRIVER_FILES",    "VK_ICD_FILENAMES",  "__EGL_VENDOR_LIBRARY_FILENAMES",
    "LIBGL_DRIVERS_PATH", "GBM_BACKENDS_PATH", "NODEVICE_SELECT"};

constexpr const char* kLibDir = "root/usr/lib/x86_64-linux-gnu";

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

// What a folder lacks to be a driver ("" when complete): scripts/drivers.sh writes
// `complete` last, so a folder it was interrupted in is not taken.
std::string missingPart(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return "no folder " + dir.string();
  for (const char* f : {"complete", "lvp_icd.x86_64.json", "50_mesa.json"})
    if (!fs::is_regular_file(dir / f, ec)) return dir.string() + " lacks " + f;
  if (!fs::is_directory(dir / kLibDir, ec)) return dir.string() + " lacks " + kLibDir;
  return "";
}

bool isPath(const std::string& name) { return name.find('/') != std::string::npos; }

fs::path folderOf(const std::string& name) {
  return isPath(name) ? fs::path(name) : driversFolder() / name;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The folder of a driver other than system, checked.
fs::path driverFolder(const std::string& name) {
  if (name.empty())
    throw InputError("--driver needs a value: " + joinNames(driverNames()) + " or a path");
  const fs::path dir = folderOf(name);
  const std::string missing = missingPart(dir);
  if (missing.empty()) return fs::absolute(dir).lexically_normal();
  if (isPath(name))
    throw InputError("driver '" + name + "': " + missing +
                     " (a driver folder is what scripts/drivers.sh DEST writes into "
                     "DEST/mesa-25.0)");
  throw InputError("unknown driver '" + name + "' (" + missing +
                   "; found: " + joinNames(driverNames()) +
                   "): scripts/drivers.sh fetches mesa-25.0 into drivers/");
}

void setOrThrow(const char* name, const std::string& value) {
  if (setenv(name, value.c_str(), 1) != 0)
    throw std::system_error(errno, std::generic_category(), std::string("setenv ") + name);
}

}  // namespace

fs::path driversFolder() {
  const std::string dir = env("SB_DRIVERS_DIR");
  return dir.empty() ? fs::path(SB_SOURCE_DIR) / "drivers" : fs::path(dir);
}

std::vector<std::string> driverNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(driversFolder(), ec))
    if (missingPart(e.path()).empty()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  names.insert(names.begin(), "system");
  return names;
}

std::string currentDriver() {
  const std::string d = env(kMarker);
  return d.empty() ? "system" : d;
}

void checkDriver(const std::string& name) {
  if (name != "system") driverFolder(name);
}

bool isCurrentDriver(const std::string& name) {
  const std::string current = currentDriver();
  if (name == "system" || current == "system") {
    checkDriver(name);
    return name == current;
  }
  return driverFolder(name) == driverFolder(current);
}

void setDriverEnvironment(const std::string& name) {
  // Back to the state before any driver was set: the user's LD_LIBRARY_PATH, none of
  // the loader variables a driver set.
  if (env(kMarker) != "") {
    const std::string saved = env(kSavedLibraryPath);
    if (saved == "-")
      unsetenv("LD_LIBRARY_PATH");
    else
      setOrThrow("LD_LIBRARY_PATH", saved);
    for (const char* v : kLoaderVariables) unsetenv(v);
    unsetenv(kSavedLibraryPath);
    unsetenv(kMarker);
  }
  if (name == "system") return;
  const fs::path dir = driverFolder(name);
  const std::string lib = (dir / kLibDir).string();
  const char* userPath = std::getenv("LD_LIBRARY_PATH");
  setOrThrow(kSavedLibraryPath, userPath ? userPath : "-");
  // The unpacked folder first: Mesa's EGL finds its libgallium and libgbm there, and
  // dlopen("libOSMesa.so.8") the unpacked OSMesa.
  std::string path = lib;
  if (userPath && *userPath) path.append(":").append(userPath);
  setOrThrow("LD_LIBRARY_PATH", path);
  const std::string icd = (dir / "lvp_icd.x86_64.json").string();
  setOrThrow("VK_DRIVER_FILES", icd);   // Vulkan loader >= 1.3.207
  setOrThrow("VK_ICD_FILENAMES", icd);  // older loaders
  setOrThrow("__EGL_VENDOR_LIBRARY_FILENAMES", (dir / "50_mesa.json").string());
  setOrThrow("LIBGL_DRIVERS_PATH", lib + "/dri");
  setOrThrow("GBM_BACKENDS_PATH", lib + "/gbm");
  // The system's Mesa device-select layer is implicit: it would load the system's Mesa
  // code into this process beside the selected driver.
  setOrThrow("NODEVICE_SELECT", "1");
  setOrThrow(kMarker, name);
}

void selectDriverFromArgs(int argc, char** argv) {
  std::string name;
  bool given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") break;
    if (a == "--driver" && i + 1 < argc) {
      name = argv[i + 1];
      given = true;
    } else if (a.rfind("--driver=", 0) == 0) {
      name = a.substr(9);
      given = true;
    }
  }
  if (!given) return;
  try {
    if (isCurrentDriver(name)) return;
    setDriverEnvironment(name);
  } catch (const std::exception& e) {
    std::cerr << "strandbench: --driver " << name << ": " << e.what() << "\n";
    std::exit(2);
  }
  execv("/proc/self/exe", argv);
  std::cerr << "strandbench: --driver " << name
            << ": re-executing /proc/self/exe failed: " << std::strerror(errno) << "\n";
  std::exit(2);
}

int runSelfOnDriver(const std::string& driver, const std::vector<std::string>& args) {
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) throw InputError("cannot start a process for driver " + driver + " (fork failed)");
  if (pid == 0) {
    try {
      setDriverEnvironment(driver);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      _exit(2);
    }
    std::vector<std::string> argv = {"strandbench"};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> p;
    for (std::string& a : argv) p.push_back(a.data());
    p.push_back(nullptr);
    execv("/proc/self/exe", p.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace sb
