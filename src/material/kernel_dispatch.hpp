#pragma once
// Runs F<D, S>::run(args...) for the dimension and influence shape known only at run time, so
// the hot bond loops are compiled once per (dimension, shape) with no branch per bond.
#include <utility>

#include "material/micromodulus.hpp"

namespace periadapt {

template <template <int, InfluenceShape> class F, class... Args>
auto dispatch(int dim, InfluenceShape s, Args&&... args) {
  auto by_shape = [&]<int D>() {
    switch (s) {
      case InfluenceShape::Constant:
        return F<D, InfluenceShape::Constant>::run(std::forward<Args>(args)...);
      case InfluenceShape::Triangular:
        return F<D, InfluenceShape::Triangular>::run(std::forward<Args>(args)...);
      default:
        return F<D, InfluenceShape::InvertedTriangular>::run(std::forward<Args>(args)...);
    }
  };
  switch (dim) {
    case 1: return by_shape.template operator()<1>();
    case 2: return by_shape.template operator()<2>();
    default: return by_shape.template operator()<3>();
  }
}

}  // namespace periadapt
