#include "io/png_file.hpp"

#include <png.h>

#include <cerrno>
#include <cstring>

#include "io/atomic_output.hpp"
#include "io/temporary_files.hpp"

#include <cstdint>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

namespace periadapt {

void write_png_file(cairo_surface_t* surf, const std::string& path) {
  cairo_surface_flush(surf);
  if (cairo_image_surface_get_format(surf) != CAIRO_FORMAT_RGB24)
    throw std::logic_error("write_png_file: RGB24 surfaces only");
  const int w = cairo_image_surface_get_width(surf), h = cairo_image_surface_get_height(surf);
  const int stride = cairo_image_surface_get_stride(surf);
  const unsigned char* data = cairo_image_surface_get_data(surf);
  // Through a temporary name (io/atomic_output.hpp): a failed write leaves the old picture.
  const std::string tmp = path + ".tmp";
  const TemporaryFileGuard guard(tmp);
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> fp(std::fopen(tmp.c_str(), "wb"), &std::fclose);
  if (!fp) throw OutputError("cannot write " + path + ": " + std::strerror(errno));
  auto fail = [&](const std::string& why) {
    fp.reset();
    std::remove(tmp.c_str());
    return OutputError("cannot write " + path + ": " + why);
  };
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("cannot write " + path + ": out of memory");
  }
  std::vector<unsigned char> row(3 * static_cast<std::size_t>(w));
  // libpng reports errors by longjmp: nothing with a destructor may be created below.
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw fail("the PNG encoder stopped (disk full?)");
  }
  png_init_io(png, fp.get());
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
               PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) {
    // RGB24: one native-endian 32-bit word per pixel, 0x00RRGGBB.
    const auto* px = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
    for (int x = 0; x < w; ++x) {
      row[3 * x] = static_cast<unsigned char>(px[x] >> 16);
      row[3 * x + 1] = static_cast<unsigned char>(px[x] >> 8);
      row[3 * x + 2] = static_cast<unsigned char>(px[x]);
    }
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fflush(fp.get()) != 0 || std::ferror(fp.get())) throw fail(std::strerror(errno));
  if (std::fclose(fp.release()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw OutputError("cannot write " + path + ": " + why);
  }
  commit_file(tmp, path);
}

}  // namespace periadapt
