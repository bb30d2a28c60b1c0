#pragma once
// PNG picture of a nodal field (damage by default) drawn with cairo: each node a filled square
// of its cell size, colour map with a colour bar, title and scale.
#include <string>
#include <vector>

#include "core/node_set.hpp"

namespace periadapt {

struct PngOptions {
  int width = 1200;
  std::string title;
  std::string field_name = "damage";
  double vmin = 0.0, vmax = 1.0;
  bool deformed = false;  // draw at current positions (reference otherwise)
};

// Writes the picture; for 3D models the xy-projection, the maximum over z drawn on top.
void write_field_png(const std::string& path, const NodeSet& nodes,
                     const std::vector<double>& field, const PngOptions& opt);

}  // namespace periadapt
