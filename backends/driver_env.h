// Drivers as named things: "system" (the Mesa the system's loaders find) or a
// folder that scripts/drivers.sh fills (drivers/mesa-25.0: a Mesa unpacked beside
// the system's, with loader files naming its libraries by absolute path), by name
// or by path. The loaders (libvulkan, libEGL, the dynamic linker for libOSMesa)
// read their environment once, when they first load, so a driver is selected by
// re-executing the process with that environment: one process, one driver.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace sb {

// The folder of named drivers: $SB_DRIVERS_DIR, else drivers/ in the source tree.
std::filesystem::path driversFolder();

// "system", then each folder under driversFolder() that holds a driver.
std::vector<std::string> driverNames();

// The driver this process runs ("system" unless started with --driver).
std::string currentDriver();

// Whether `name` is this process's driver (a name and the path of its folder are
// the same driver). Throws InputError for an unknown name or an incomplete folder.
bool isCurrentDriver(const std::string& name);

// Throws InputError naming scripts/drivers.sh when `name` is neither "system" nor
// a folder with a driver (by name under driversFolder(), or a path).
void checkDriver(const std::string& name);

// Sets this process's environment for `name` (the loaders' variables, and
// SB_DRIVER): only meaningful before an exec. Throws InputError like checkDriver.
void setDriverEnvironment(const std::string& name);

// The first thing main() does: the value of --driver NAME / --driver=NAME in
// argv, when it is not this process's driver, sets the environment and
// re-executes /proc/self/exe with the same argv (never returns then). Without
// --driver, or with this process's driver, it returns. An unknown driver: the
// message on stderr and exit status 2.
void selectDriverFromArgs(int argc, char** argv);

// Runs `strandbench ARGS` (/proc/self/exe) in a child process with `driver`'s
// environment, its output going to ours, and waits for it: how one command uses two
// drivers (one process loads one). Returns its exit status, 128 + the signal when killed.
int runSelfOnDriver(const std::string& driver, const std::vector<std::string>& args);

// The help of every --driver option.
extern const char* const kDriverHelp;

}  // namespace sb
