// A wall-clock duration for a person reading a log or a progress line.
#pragma once

#include <string>

namespace ballast {

// "1:05" (minutes:seconds) under an hour, "2 h 03 min" from an hour; negative reads as
// zero. Study ETAs, run times and the load cycles' time to go use it alike.
std::string duration_text(double seconds);

}  // namespace ballast
