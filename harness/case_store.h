// The shared case store (`strandbench figure --cases DIR`, $SB_FIGURE_CASES; one folder per
// docs refresh, scripts/docs-refresh-stale.sh): a case several figures run is measured once,
// by the first sweep that needs it, and every later sweep takes that measurement whole (its
// result: times, interval, errors; its images and trace), so every page that shows the case
// prints the same numbers. An entry is found by a hash of its key: the case's canonical
// settings (technique and scene specs with their defaults filled in), its rounds, and the
// code that runs it (commit, dirty flag, the executable's path, size and time: a rebuild is
// another key, so nothing is reused across code changes). The entry holds the whole key: a
// hash collision or a damaged entry reads as a miss (the case is measured again).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "harness/measure.h"
#include "harness/suite.h"

namespace sb {

class CaseStore {
 public:
  // Creates the folder where it is missing; InputError when it cannot.
  explicit CaseStore(std::filesystem::path dir);
  const std::filesystem::path& dir() const { return dir_; }

  // The case's key (canonical JSON text) for these rounds.
  std::string key(const SweepCase& c, const RepetitionOptions& rounds, bool interleave) const;

  // The stored measurement of `key` written into the sweep folder `sweepDir` as case `c`:
  // its images and trace copied under c's file names, "case" made c's, and "shared" naming
  // the sweep, case and machine that measured it. nullopt on a miss.
  std::optional<nlohmann::ordered_json> take(const std::string& key,
                                             const std::filesystem::path& sweepDir,
                                             const SweepCase& c) const;

  // Keeps case `c` finished in `sweepDir` (its result and the files it names) under `key`;
  // `measuredFor` names the sweep (the figure). An entry already there with this key stays.
  // A failed case, or one taken from the store, is not kept. Returns whether it is there now.
  bool put(const std::string& key, const std::filesystem::path& sweepDir, const SweepCase& c,
           const nlohmann::ordered_json& result, const std::string& measuredFor) const;

 private:
  std::filesystem::path dir_;
  nlohmann::ordered_json code_;     // commit, dirty flag, executable
  nlohmann::ordered_json machine_;  // date, cpu, load_before: where an entry was measured
};

}  // namespace sb
