// Driver A/B: one suite swept on two drivers (each in a process of its own, since one
// process loads one driver), then a triage page that pairs every case: both images, their
// difference heatmap and FLIP map, a toggle between the images, and the two drivers' frame
// times (medians with 95% intervals, their ratio and a verdict) and work counters side by
// side; sorted by the size of the change (mean FLIP between the two images).
#pragma once

#include <string>

namespace sb {

struct DriverAbOptions {
  std::string suitePath, out, filter;
  std::string a = "system", b;  // driver names or paths
  bool resume = false;          // --resume: continue both sweeps
};

// Runs `sweep SUITE --driver A --out OUT/A` and the same for B (child processes), then
// writeDriverAbPage(OUT). Returns 0, or 1 when a sweep failed. Throws InputError for bad
// drivers, suite or folder; Interrupted when a sweep was stopped.
int runDriverAb(const DriverAbOptions& o);

// From OUT/a and OUT/b (sweep folders; OUT/ab.json names the drivers): OUT/ab.json (the
// pairs and their numbers), OUT/ab/*.png (heatmaps and FLIP maps) and OUT/ab.html.
// Returns the number of pairs.
int writeDriverAbPage(const std::string& out);

}  // namespace sb
