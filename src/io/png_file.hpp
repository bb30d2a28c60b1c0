#pragma once
// Writes a cairo RGB24 image surface as an 8-bit RGB PNG with a fast zlib setting: our pictures
// are mostly flat colour, which level 1 compresses almost as well as cairo's default at a small
// fraction of the time (a damage picture is written at every requested time of a run).
#include <cairo.h>

#include <string>

namespace periadapt {

// Throws std::runtime_error naming `path` when it cannot be written.
void write_png_file(cairo_surface_t* rgb24_surface, const std::string& path);

}  // namespace periadapt
