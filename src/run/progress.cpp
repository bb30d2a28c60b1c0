#include "run/progress.hpp"

#include <unistd.h>

#include <fmt/format.h>

namespace periadapt {

Progress::Progress(long total, bool quiet)
    : total_(total), quiet_(quiet), tty_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

static std::string hms(double s) {
  if (!(s >= 0) || s > 1e7) return "--:--";
  const long t = static_cast<long>(s + 0.5);
  return t >= 3600 ? fmt::format("{}:{:02d}:{:02d}", t / 3600, (t / 60) % 60, t % 60)
                   : fmt::format("{:02d}:{:02d}", t / 60, t % 60);
}

void Progress::update(long done, const std::string& note) {
  if (quiet_ || total_ <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double el = std::chrono::duration<double>(now - start_).count();
  const double frac = static_cast<double>(done) / static_cast<double>(total_);
  const double eta = frac > 0 ? el * (1 - frac) / frac : -1;
  if (tty_) {
    if (std::chrono::duration<double>(now - last_draw_).count() < 0.2 && done < total_) return;
    last_draw_ = now;
    const int w = 30, fill = static_cast<int>(frac * w);
    fmt::print(stderr, "\r[{}{}] {:5.1f}%  step {}/{}  elapsed {}  ETA {}  {}   ",
               std::string(static_cast<std::size_t>(fill), '#'),
               std::string(static_cast<std::size_t>(w - fill), '.'), 100 * frac, done, total_,
               hms(el), hms(eta), note);
  } else {
    const int decile = static_cast<int>(frac * 10);
    if (decile == last_decile_) return;
    last_decile_ = decile;
    fmt::print(stderr, "progress {:3d}%  step {}/{}  elapsed {}  ETA {}  {}\n", decile * 10, done,
               total_, hms(el), hms(eta), note);
  }
}

void Progress::finish() {
  if (!quiet_ && tty_) fmt::print(stderr, "\n");
}

}  // namespace periadapt
