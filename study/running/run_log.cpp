#include "study/running/run_log.hpp"

#include <cctype>

namespace ballast {

void RunLogBuffer::put(char ch) {
  text_ += ch;
  if (ch != '\n') {
    line_ += ch;
    return;
  }
  if (on_line_) on_line_(line_);
  line_.clear();
}

RunLogBuffer::int_type RunLogBuffer::overflow(int_type ch) {
  if (!traits_type::eq_int_type(ch, traits_type::eof())) put(traits_type::to_char_type(ch));
  return traits_type::not_eof(ch);
}

std::streamsize RunLogBuffer::xsputn(const char* s, std::streamsize n) {
  for (std::streamsize k = 0; k < n; ++k) put(s[k]);
  return n;
}

LogProgress parse_log_line(const std::string& line) {
  LogProgress p;
  if (line.rfind("stage ", 0) == 0) {
    p.stage = line;
    return p;
  }
  // "  <name> <spaces> <digits> steps ..." (the stage report of box_test_prepare.cpp)
  const std::size_t steps = line.find(" steps");
  if (line.rfind("  ", 0) != 0 || steps == std::string::npos) return p;
  std::size_t digits = steps;
  while (digits > 0 && std::isdigit(static_cast<unsigned char>(line[digits - 1]))) --digits;
  if (digits == steps) return p;
  std::size_t name_end = digits;
  while (name_end > 0 && line[name_end - 1] == ' ') --name_end;
  const std::size_t name_start = line.find_first_not_of(' ');
  if (name_end <= name_start) return p;
  p.step = line.substr(name_start, name_end - name_start);
  p.step_count = std::stol(line.substr(digits, steps - digits));
  return p;
}

}  // namespace ballast
