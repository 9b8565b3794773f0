#include "cases/duration_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ballast {

std::string duration_text(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  char text[32];
  if (s < 3600)
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%ld h %02ld min", s / 3600, (s % 3600) / 60);
  return text;
}

}  // namespace ballast
