#pragma once
// Load amplitude as a function of time: step (constant from t0), linear ramp t0..t1, or a table
// with linear interpolation (held constant outside).
#include <algorithm>
#include <vector>

namespace periadapt {

struct TimeFunction {
  enum class Kind { Step, Ramp, Table } kind = Kind::Step;
  double t0 = 0.0, t1 = 0.0;
  std::vector<double> times, values;

  double operator()(double t) const {
    switch (kind) {
      case Kind::Step: return t >= t0 ? 1.0 : 0.0;
      case Kind::Ramp:
        if (t <= t0) return 0.0;
        if (t >= t1) return 1.0;
        return (t - t0) / (t1 - t0);
      case Kind::Table: {
        if (t <= times.front()) return values.front();
        if (t >= times.back()) return values.back();
        auto it = std::upper_bound(times.begin(), times.end(), t);
        std::size_t k = static_cast<std::size_t>(it - times.begin());
        double w = (t - times[k - 1]) / (times[k] - times[k - 1]);
        return (1 - w) * values[k - 1] + w * values[k];
      }
    }
    return 1.0;
  }
};

}  // namespace periadapt
