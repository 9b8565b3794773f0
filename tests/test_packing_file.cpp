// Packing files (cases/packing_file.hpp): what is written reads back bit for bit,
// comments and blank lines are ignored, and every malformed line is refused with
// file:line, the value and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>

#include "cases/packing_file.hpp"
#include "engine/errors.hpp"
#include "test_helpers.hpp"

using namespace ballast;

using ballast::test_support::error_message;
using ballast::test_support::expect_error;

namespace {

Packing parse(const std::string& text) {
  std::istringstream in(text);
  return parse_packing(in, "bed.txt");
}

std::string error_of(const std::string& text) {
  return error_message([&] { parse(text); });
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Doubles that six or even 15 digits would not survive: random mantissas over many
// binades, plus values next to round numbers.
std::vector<double> awkward_values(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(-40, 3);
  std::vector<double> v;
  for (std::size_t k = 0; k < n; ++k) v.push_back(std::ldexp(mantissa(rng), exponent(rng)));
  v.push_back(std::nextafter(0.1, 1.0));
  v.push_back(1.0 / 3.0);
  v.push_back(std::numeric_limits<double>::min());  // smallest normal
  v.push_back(std::numeric_limits<double>::max());
  return v;
}

Packing sphere_packing(std::uint64_t seed) {
  const std::vector<double> v = awkward_values(400, seed);
  Packing p;
  for (std::size_t k = 0; k + 3 < v.size(); k += 4) {
    const double sign = k % 8 == 0 ? -1.0 : 1.0;  // negative coordinates too
    p.add_body(static_cast<long>(k / 4), {Vec3(sign * v[k], v[k + 1], v[k + 2])}, {v[k + 3]});
  }
  return p;
}

void expect_bit_identical(const Packing& a, const Packing& b) {
  ASSERT_EQ(a.balls(), b.balls());
  ASSERT_EQ(a.bodies(), b.bodies());
  EXPECT_EQ(a.clumps, b.clumps);
  EXPECT_EQ(a.body_first, b.body_first);
  for (Index k = 0; k < a.balls(); ++k) {
    for (int d = 0; d < 3; ++d)
      EXPECT_TRUE(same_bits(a.centre[k][d], b.centre[k][d]))
          << "ball " << k << " coordinate " << d << ": " << a.centre[k][d] << " vs "
          << b.centre[k][d];
    EXPECT_TRUE(same_bits(a.radius[k], b.radius[k])) << "ball " << k;
  }
}

}  // namespace

TEST(PackingFile, SpheresRoundTripBitForBit) {
  const Packing p = sphere_packing(7);
  std::ostringstream out;
  write_packing(out, p, "round trip");
  const Packing q = parse(out.str());
  EXPECT_FALSE(q.clumps);
  expect_bit_identical(p, q);
  // Written again, the text is the same: nothing drifts through repeated exchanges.
  std::ostringstream again;
  write_packing(again, q, "round trip");
  EXPECT_EQ(out.str(), again.str());
}

TEST(PackingFile, ClumpsRoundTripBitForBitWithTheirBodies) {
  const std::vector<double> v = awkward_values(120, 11);
  Packing p;
  p.clumps = true;
  std::size_t k = 0;
  for (long body = 0; k + 8 <= v.size(); ++body) {
    // Bodies of 1, 2 and 3 balls in turn (a one-ball body is allowed in a clump file).
    const int n = 1 + static_cast<int>(body % 3);
    std::vector<Vec3> c;
    std::vector<double> r;
    for (int b = 0; b < n && k + 4 <= v.size(); ++b, k += 4) {
      c.emplace_back(v[k], v[k + 1], v[k + 2]);
      r.push_back(v[k + 3]);
    }
    p.add_body(body, c, r);
  }
  std::ostringstream out;
  write_packing(out, p, "");
  const Packing q = parse(out.str());
  EXPECT_TRUE(q.clumps);
  expect_bit_identical(p, q);
  EXPECT_EQ(q.ball_count(0), 1);
  EXPECT_EQ(q.ball_count(1), 2);
  EXPECT_EQ(q.ball_count(2), 3);
}

TEST(PackingFile, FileRoundTrip) {
  const Packing p = sphere_packing(3);
  const std::string path = ::testing::TempDir() + "/ballast_packing_round_trip.txt";
  write_packing_file(path, p, "file");
  const Packing q = read_packing_file(path);
  expect_bit_identical(p, q);
  EXPECT_EQ(q.source, path);
}

TEST(PackingFile, CommentsBlankLinesAndAnyWhitespace) {
  const Packing p = parse(
      "# a bed\n"
      "\n"
      "7 0.1 0.2 0.3 0.01   # first clump\n"
      "7\t0.1 0.2 0.32 0.01\n"
      "   \n"
      "3 1 2 3 0.02\n");
  EXPECT_TRUE(p.clumps);
  ASSERT_EQ(p.bodies(), 2);
  EXPECT_EQ(p.ball_count(0), 2);
  EXPECT_EQ(p.body_id[0], 7);
  EXPECT_EQ(p.body_id[1], 3);  // ids need not be ordered, only contiguous
  EXPECT_DOUBLE_EQ(p.centre[1].z(), 0.32);
  EXPECT_EQ(p.line[2], 6);  // lines count comments and blanks
  EXPECT_EQ(p.where(2), "bed.txt:6");
}

TEST(PackingFile, WrongColumnCountNamesLineAndAllowedCounts) {
  const std::string e = error_of("# header\n0.1 0.2 0.3\n");
  EXPECT_NE(e.find("bed.txt:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("3 columns"), std::string::npos) << e;
  EXPECT_NE(e.find("4 for spheres"), std::string::npos) << e;
  EXPECT_NE(e.find("5 for clumps"), std::string::npos) << e;
}

TEST(PackingFile, MixedColumnCountsAreRefused) {
  const std::string e = error_of("0.1 0.2 0.3 0.01\n0 0.1 0.2 0.3 0.01\n");
  EXPECT_NE(e.find("bed.txt:2: 5 columns, but line 1 has 4"), std::string::npos) << e;
}

TEST(PackingFile, NonNumbersAndNonFiniteValuesAreRefused) {
  std::string e = error_of("0.1 abc 0.3 0.01\n");
  EXPECT_NE(e.find("bed.txt:1: column 2 (y) = 'abc' is not a number"), std::string::npos) << e;
  e = error_of("0.1 0.2 0.3x 0.01\n");  // trailing garbage is not silently dropped
  EXPECT_NE(e.find("column 3 (z) = '0.3x'"), std::string::npos) << e;
  e = error_of("0.1 0.2 0.3 0.01\n0.1 0.2 inf 0.01\n");
  EXPECT_NE(e.find("bed.txt:2: column 3 (z) = 'inf' (allowed: a finite number)"), std::string::npos)
      << e;
  e = error_of("0 0.1 0.2 0.3 nan\n");
  EXPECT_NE(e.find("column 5 (r) = 'nan'"), std::string::npos) << e;
}

TEST(PackingFile, NonPositiveRadiusIsRefused) {
  for (const char* r : {"0", "-0.01"}) {
    const std::string e = error_of(std::string("0.1 0.2 0.3 ") + r + "\n");
    EXPECT_NE(e.find("bed.txt:1: radius r = " + std::string(r)), std::string::npos) << e;
    EXPECT_NE(e.find("(allowed: > 0 m)"), std::string::npos) << e;
  }
}

TEST(PackingFile, BodyIdsMustBeNonNegativeIntegers) {
  for (const char* id : {"1.5", "-1", "a"}) {
    const std::string e = error_of(std::string(id) + " 0.1 0.2 0.3 0.01\n");
    EXPECT_NE(e.find("bed.txt:1: column 1 (body) = '" + std::string(id) + "'"), std::string::npos)
        << e;
    EXPECT_NE(e.find("non-negative integer"), std::string::npos) << e;
  }
}

TEST(PackingFile, BodyReappearingAfterAnotherIsRefused) {
  const std::string e = error_of(
      "0 0.1 0.2 0.3 0.01\n"
      "0 0.1 0.2 0.31 0.01\n"
      "1 0.5 0.2 0.3 0.01\n"
      "0 0.1 0.2 0.32 0.01\n");
  EXPECT_NE(e.find("bed.txt:4: body 0 reappears after body 1"), std::string::npos) << e;
  EXPECT_NE(e.find("started on line 1"), std::string::npos) << e;
}

TEST(PackingFile, EmptyAndMissingFilesAreRefused) {
  EXPECT_NE(error_of("# only a comment\n\n").find("bed.txt: no particles"), std::string::npos);
  expect_error([] { read_packing_file("/nonexistent/bed.txt"); },
               {"cannot read packing file '/nonexistent/bed.txt'"});
}
