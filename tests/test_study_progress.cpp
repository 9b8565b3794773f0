// The study's progress lines (study/running/study_progress.hpp), in plain mode: the time
// a finished run reports and the ETA drawn from it. A run resumed from a checkpoint is
// seen by the board for only the part since the resume; the run's own time, which its
// checkpoint carried over, is what it cost and what the queued runs will cost.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "study/running/study_progress.hpp"

namespace ballast {
namespace {

RunSpec spec(const std::string& id, std::size_t index) {
  RunSpec s;
  s.id = id;
  s.index = index;
  return s;
}

// The line that reports `id` finished, from the board's output.
std::string finished_line(const std::string& out, const std::string& id) {
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    if ((line.rfind("ok ", 0) == 0 || line.rfind("FAILED ", 0) == 0) &&
        line.find(" " + id + " in ") != std::string::npos)
      return line;
  }
  ADD_FAILURE() << "no line for " << id << " in:\n" << out;
  return {};
}

TEST(StudyProgress, AResumedRunReportsItsWholeTimeAndTheEtaFollowsIt) {
  std::ostringstream out;
  ProgressBoard board(out, /*live=*/false, /*to_do=*/3, /*done=*/0, /*jobs=*/1);
  RunRecord r;
  r.spec = spec("T2S1-r1", 0);
  r.ok = true;
  r.result.emplace();
  // 62 min, nearly all of it before the resume; the board has seen a moment of it.
  r.result->wall_seconds = 3720.0;
  r.wall_seconds = 0.01;
  board.started(r.spec, 1);
  board.finished(r);
  const std::string line = finished_line(out.str(), "T2S1-r1");
  EXPECT_NE(line.find(" in 1 h 02 min:"), std::string::npos) << line;
  // Two runs queued at 62 min each, one at a time.
  EXPECT_NE(line.find("[1/3 done, ETA 2 h 04 min]"), std::string::npos) << line;
}

TEST(StudyProgress, AFailedRunReportsTheTimeTheBoardSaw) {
  std::ostringstream out;
  ProgressBoard board(out, /*live=*/false, /*to_do=*/2, /*done=*/0, /*jobs=*/2);
  RunRecord r;
  r.spec = spec("spheres-r2", 1);
  r.ok = false;
  r.message = "blew up: step 12";
  r.wall_seconds = 3720.0;  // not used while the board saw the run start
  board.started(r.spec, 1);
  board.finished(r);
  const std::string line = finished_line(out.str(), "spheres-r2");
  EXPECT_EQ(line.rfind("FAILED spheres-r2 in 0:00: blew up: step 12", 0), 0u) << line;
  EXPECT_NE(line.find("(1 failed)"), std::string::npos) << line;
}

}  // namespace
}  // namespace ballast
