#include "io/line_plot.hpp"

#include <cairo.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/png_file.hpp"

namespace periadapt {

namespace {

// About five round tick values covering [lo, hi].
std::vector<double> ticks(double lo, double hi) {
  const double span = hi - lo;
  const double raw = span / 5.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double f : {1.0, 2.0, 5.0, 10.0})
    if (raw <= f * mag) {
      step = f * mag;
      break;
    }
  std::vector<double> t;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * span; v += step)
    t.push_back(std::abs(v) < 1e-9 * span ? 0.0 : v);  // no "-0" label
  return t;
}

}  // namespace

void write_line_plot(const std::string& path, const std::vector<PlotSeries>& series,
                     const PlotOptions& opt) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const PlotSeries& s : series)
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      x0 = std::min(x0, s.x[k]), x1 = std::max(x1, s.x[k]);
      y0 = std::min(y0, s.y[k]), y1 = std::max(y1, s.y[k]);
    }
  if (!(x1 > x0)) x1 = x0 + 1;
  if (!(y1 > y0)) y1 = y0 + 1;
  const double pad = 0.05 * (y1 - y0);
  y0 -= pad, y1 += pad;
  const double L = 90, R = 30, T = 50, B = 70;
  const double W = opt.width - L - R, H = opt.height - T - B;
  auto px = [&](double x) { return L + (x - x0) / (x1 - x0) * W; };
  auto py = [&](double y) { return T + (1 - (y - y0) / (y1 - y0)) * H; };

  cairo_surface_t* surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, opt.width, opt.height);
  cairo_t* cr = cairo_create(surf);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, L, T, W, H);
  cairo_stroke(cr);
  for (double t : ticks(x0, x1)) {
    cairo_move_to(cr, px(t), T + H);
    cairo_line_to(cr, px(t), T + H + 5);
    cairo_stroke(cr);
    const std::string s = fmt::format("{:.4g}", t);
    cairo_move_to(cr, px(t) - 3.5 * s.size(), T + H + 20);
    cairo_show_text(cr, s.c_str());
  }
  for (double t : ticks(y0, y1)) {
    cairo_move_to(cr, L - 5, py(t));
    cairo_line_to(cr, L, py(t));
    cairo_stroke(cr);
    const std::string s = fmt::format("{:.4g}", t);
    cairo_move_to(cr, L - 10 - 7 * s.size(), py(t) + 4);
    cairo_show_text(cr, s.c_str());
  }
  cairo_move_to(cr, L + W / 2 - 3.5 * opt.x_label.size(), opt.height - 20);
  cairo_show_text(cr, opt.x_label.c_str());
  cairo_save(cr);
  cairo_move_to(cr, 20, T + H / 2 + 3.5 * opt.y_label.size());
  cairo_rotate(cr, -M_PI / 2);
  cairo_show_text(cr, opt.y_label.c_str());
  cairo_restore(cr);
  cairo_set_font_size(cr, 15);
  cairo_move_to(cr, L, 30);
  cairo_show_text(cr, opt.title.c_str());
  cairo_set_font_size(cr, 13);

  const double colors[6][3] = {{0.12, 0.47, 0.71}, {0.84, 0.15, 0.16}, {0.17, 0.63, 0.17},
                               {0.58, 0.40, 0.74}, {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}};
  for (std::size_t s = 0; s < series.size(); ++s) {
    const double* c = colors[s % 6];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
    cairo_set_line_width(cr, 2);
    const PlotSeries& ps = series[s];
    for (std::size_t k = 0; k < ps.x.size(); ++k) {
      if (k == 0) cairo_move_to(cr, px(ps.x[k]), py(ps.y[k]));
      else cairo_line_to(cr, px(ps.x[k]), py(ps.y[k]));
    }
    cairo_stroke(cr);
    const double ly = T + 20 + 18 * static_cast<double>(s);
    cairo_move_to(cr, L + W - 260, ly);
    cairo_line_to(cr, L + W - 235, ly);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, L + W - 228, ly + 4);
    cairo_show_text(cr, ps.name.c_str());
  }
  cairo_destroy(cr);
  try {
    write_png_file(surf, path);
  } catch (...) {
    cairo_surface_destroy(surf);
    throw;
  }
  cairo_surface_destroy(surf);
}

}  // namespace periadapt
