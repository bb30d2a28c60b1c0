#pragma once
// Minimal line charts as PNG (cairo): several named series over a shared x axis, axis ticks,
// labels and a legend. For study outputs (error profiles, convergence curves).
#include <string>
#include <vector>

namespace periadapt {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
};

struct PlotOptions {
  std::string title, x_label, y_label;
  int width = 900, height = 560;
};

void write_line_plot(const std::string& path, const std::vector<PlotSeries>& series,
                     const PlotOptions& opt);

}  // namespace periadapt
