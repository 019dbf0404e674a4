// Summary statistics over repetitions (median, min, max, mean, standard deviation).
#pragma once

#include <vector>

namespace sb {

struct Stats {
  double median = 0, min = 0, max = 0, mean = 0, stddev = 0;
  int count = 0;
};

Stats summarize(std::vector<double> values);

}  // namespace sb
