#pragma once
#include <cstddef>

namespace periadapt {

// Peak resident set size of this process so far, in bytes (0 where the OS does not say).
std::size_t peak_rss_bytes();

// Resident set size now, in bytes (0 where the OS does not say): what a run holds after its
// set-up's transient buffers went back.
std::size_t current_rss_bytes();

}  // namespace periadapt
