#include "io/damage_png.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>

#include "io/png_file.hpp"

namespace periadapt {

namespace {

// A perceptually ordered blue-white-red-black ramp tuned so that damage 0.35-0.5 (crack
// surfaces) stands out against the intact (pale) body.
void colour(double t, double& r, double& g, double& b) {
  t = std::clamp(t, 0.0, 1.0);
  struct Stop { double t, r, g, b; };
  static const Stop stops[] = {{0.00, 0.86, 0.91, 0.97}, {0.15, 0.55, 0.75, 0.93},
                               {0.35, 0.98, 0.85, 0.25}, {0.55, 0.93, 0.35, 0.12},
                               {0.80, 0.60, 0.05, 0.05}, {1.00, 0.15, 0.00, 0.00}};
  for (int k = 1; k < 6; ++k) {
    if (t <= stops[k].t) {
      const double w = (t - stops[k - 1].t) / (stops[k].t - stops[k - 1].t);
      r = stops[k - 1].r + w * (stops[k].r - stops[k - 1].r);
      g = stops[k - 1].g + w * (stops[k].g - stops[k - 1].g);
      b = stops[k - 1].b + w * (stops[k].b - stops[k - 1].b);
      return;
    }
  }
  r = stops[5].r, g = stops[5].g, b = stops[5].b;
}

}  // namespace

void write_field_png(const std::string& path, const NodeSet& ns, const std::vector<double>& field,
                     const PngOptions& opt) {
  const int dim = ns.dim;
  std::array<std::vector<double>, 3> P = ns.x;
  if (opt.deformed)
    for (int d = 0; d < 3; ++d)
      for (std::size_t i = 0; i < ns.size(); ++i) P[d][i] = ns.current(i, d);
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY, hmax = 0;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    if (!(ns.flags[i] & kActive)) continue;
    const double h = 0.5 * ns.spacing[i];
    xmin = std::min(xmin, P[0][i] - h);
    xmax = std::max(xmax, P[0][i] + h);
    const double yv = dim > 1 ? P[1][i] : 0.0;
    ymin = std::min(ymin, yv - h);
    ymax = std::max(ymax, yv + h);
    hmax = std::max(hmax, h);
  }
  if (!(xmax > xmin)) throw std::runtime_error("nothing to draw in " + path);
  if (dim == 1) {  // a bar: draw it as a strip a tenth of its length high
    ymin = -0.05 * (xmax - xmin);
    ymax = -ymin;
  }
  const int margin = 40, bar = 90, title_h = 36;
  const int plot_w = opt.width - 2 * margin - bar;
  const double sc = plot_w / (xmax - xmin);
  const int plot_h = std::max(20, static_cast<int>(std::ceil((ymax - ymin) * sc)));
  const int W = opt.width, H = plot_h + 2 * margin + title_h;

  cairo_surface_t* surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
  cairo_t* cr = cairo_create(surf);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  // Draw low values first so damaged nodes stay visible in 3D projections.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns.flags[i] & kActive) order.push_back(i);
  if (dim == 3)
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return field[a] < field[b]; });
  // Node squares go straight into the pixels (a cairo fill per node costs more than the rest of
  // the picture): every pixel whose centre lies in the square, as an unantialiased fill does.
  const double x0 = margin, y0 = margin + title_h;
  cairo_surface_flush(surf);
  unsigned char* pixels = cairo_image_surface_get_data(surf);
  const int stride = cairo_image_surface_get_stride(surf);
  for (std::size_t i : order) {
    double r, g, b;
    colour((field[i] - opt.vmin) / (opt.vmax - opt.vmin), r, g, b);
    const auto byte = [](double c) { return static_cast<std::uint32_t>(std::lround(255.0 * c)); };
    const std::uint32_t rgb = byte(r) << 16 | byte(g) << 8 | byte(b);
    const double h = 0.5 * ns.spacing[i];
    const double px = x0 + (P[0][i] - h - xmin) * sc;
    const double yv = dim > 1 ? P[1][i] : 0.0;
    const double hy = dim > 1 ? h : 0.05 * (xmax - xmin);
    const double py = y0 + (ymax - (yv + hy)) * sc;
    const double w = std::max(1.0, 2 * h * sc), hh = std::max(1.0, 2 * hy * sc);
    // A millionth of a pixel of slack each side: neighbours' squares, whose shared edge is
    // computed twice with different rounding, must not leave a pixel column between them.
    const double e = 1e-6;
    const int ia = std::max(0, static_cast<int>(std::ceil(px - 0.5 - e)));
    const int ib = std::min(W, static_cast<int>(std::ceil(px + w - 0.5 + e)));
    const int ja = std::max(0, static_cast<int>(std::ceil(py - 0.5 - e)));
    const int jb = std::min(H, static_cast<int>(std::ceil(py + hh - 0.5 + e)));
    for (int y = ja; y < jb; ++y) {
      auto* row = reinterpret_cast<std::uint32_t*>(pixels + static_cast<std::size_t>(y) * stride);
      std::fill(row + ia, row + std::max(ia, ib), rgb);
    }
  }
  cairo_surface_mark_dirty(surf);

  // Colour bar.
  const double bx = W - bar + 10, by = y0, bh = std::max(60, plot_h), bw = 18;
  for (int k = 0; k < 100; ++k) {
    double r, g, b;
    colour(1.0 - k / 99.0, r, g, b);
    cairo_set_source_rgb(cr, r, g, b);
    cairo_rectangle(cr, bx, by + bh * k / 100.0, bw, bh / 100.0 + 1);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13);
  for (int k = 0; k <= 4; ++k) {
    const double v = opt.vmax - (opt.vmax - opt.vmin) * k / 4.0;
    cairo_move_to(cr, bx + bw + 4, by + bh * k / 4.0 + 4);
    cairo_show_text(cr, fmt::format("{:.2f}", v).c_str());
  }
  cairo_move_to(cr, bx - 6, by - 8);
  cairo_show_text(cr, opt.field_name.c_str());
  cairo_set_font_size(cr, 16);
  cairo_move_to(cr, margin, margin + 10);
  cairo_show_text(cr, opt.title.c_str());
  // Scale bar: a round length near a fifth of the width.
  const double span = (xmax - xmin) / 5;
  const double p10 = std::pow(10.0, std::floor(std::log10(span)));
  const double len = span >= 5 * p10 ? 5 * p10 : span >= 2 * p10 ? 2 * p10 : p10;
  const double sy = y0 + plot_h + 18;
  cairo_set_line_width(cr, 2);
  cairo_move_to(cr, x0, sy);
  cairo_line_to(cr, x0 + len * sc, sy);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 12);
  cairo_move_to(cr, x0 + len * sc + 8, sy + 4);
  cairo_show_text(cr, (len >= 1 ? fmt::format("{:g} m", len) : fmt::format("{:g} mm", len * 1e3)).c_str());

  // Axes of the picture: x right, y up; a 3D body is seen along -z (its nodes projected onto
  // the x-y plane, the most damaged drawn last).
  if (dim > 1) {
    const double ax = x0 + plot_w - 70, ay = sy + 16, len_px = 18;
    cairo_set_line_width(cr, 1.5);
    cairo_move_to(cr, ax, ay);
    cairo_line_to(cr, ax + len_px, ay);
    cairo_move_to(cr, ax, ay);
    cairo_line_to(cr, ax, ay - len_px);
    cairo_stroke(cr);
    cairo_move_to(cr, ax + len_px + 3, ay + 4);
    cairo_show_text(cr, "x");
    cairo_move_to(cr, ax - 3, ay - len_px - 4);
    cairo_show_text(cr, "y");
    if (dim == 3) {
      cairo_move_to(cr, ax - 150, ay + 4);
      cairo_show_text(cr, "projected along z");
    }
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
