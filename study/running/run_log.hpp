// One run's log: a std::streambuf that keeps everything run_box_test writes to its
// std::ostream* log (for the archive) and hands each complete line to a callback (for
// the progress display). One per run, written by that run's thread only.
#pragma once

#include <functional>
#include <ostream>
#include <streambuf>
#include <string>

namespace ballast {

class RunLogBuffer : public std::streambuf {
 public:
  using LineHandler = std::function<void(const std::string& line)>;
  explicit RunLogBuffer(LineHandler on_line) : on_line_(std::move(on_line)) {}

  // Everything written so far, a last unfinished line included.
  const std::string& text() const { return text_; }

 protected:
  int_type overflow(int_type ch) override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;

 private:
  void put(char ch);

  LineHandler on_line_;
  std::string text_;
  std::string line_;
};

// An ostream over a RunLogBuffer, for passing as run_box_test's log.
class RunLog {
 public:
  explicit RunLog(RunLogBuffer::LineHandler on_line)
      : buffer_(std::move(on_line)), stream_(&buffer_) {}
  std::ostream& stream() { return stream_; }
  const std::string& text() const { return buffer_.text(); }

 private:
  RunLogBuffer buffer_;
  std::ostream stream_;
};

// What a log line says about a run's progress (cases/box_test_prepare.cpp's and
// box_test_load.cpp's lines): "stage 3: compaction ..." starts a stage; "  compact
// 10500 steps ..." ends a settling step.
struct LogProgress {
  std::string stage;    // "stage 3: compaction at 10 g, then 1 g", when the line starts one
  std::string step;     // "compact", when the line ends one
  long step_count = 0;  // its steps
};
LogProgress parse_log_line(const std::string& line);

}  // namespace ballast
