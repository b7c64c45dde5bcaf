// CSV points: written and read back bit for bit, header and further columns kept, bad lines
// refused naming the file and the line.

#include "geolens/io/point_csv.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geolens/core/errors.h"
#include "support/scratch_folder.h"

namespace geolens {
namespace {

bool bitwise_equal(const Eigen::MatrixX2d& a, const Eigen::MatrixX2d& b) {
  return a.rows() == b.rows() &&
         (a.size() == 0 ||  // an empty matrix's data() may be null, which memcmp refuses
          std::memcmp(a.data(), b.data(), sizeof(double) * size_t(a.size())) == 0);
}

TEST(PointCsv, WriteThenReadIsBitExact) {
  // Random doubles of every magnitude and the awkward ones.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-300, 300);
  PointTable table;
  table.points.resize(2000, 2);
  for (Eigen::Index i = 0; i < table.points.rows(); ++i)
    for (int c = 0; c < 2; ++c) table.points(i, c) = std::ldexp(mantissa(rng), exponent(rng) * 3);
  const std::vector<double> awkward = {0.1,
                                       -0.0,
                                       1.0 / 3,
                                       std::numeric_limits<double>::denorm_min(),
                                       std::numeric_limits<double>::max(),
                                       -std::numeric_limits<double>::min(),
                                       511.99999999999994,
                                       1e23};
  for (size_t k = 0; k < awkward.size(); ++k) table.points(Eigen::Index(k), 0) = awkward[k];
  table.rest.assign(size_t(table.points.rows()), "");
  table.rest[3] = ",id 3,\"quoted, with comma\"";
  table.header = "x,y,id,note";
  const std::string text = point_csv_text(table);
  const PointTable back = parse_point_csv(text, "round trip");
  EXPECT_TRUE(bitwise_equal(back.points, table.points));
  EXPECT_EQ(back.rest, table.rest);
  EXPECT_EQ(back.header, table.header);
  EXPECT_EQ(point_csv_text(back), text);
  EXPECT_TRUE(std::signbit(back.points(1, 0)));  // -0 stays -0
}

TEST(PointCsv, HeaderColumnsBlankLinesAndLineEnds) {
  const PointTable t = parse_point_csv("x,y,name\r\n\r\n1, 2.5 ,a\r\n  \n-3e2,4\n", "t.csv");
  EXPECT_EQ(t.header, "x,y,name");
  ASSERT_EQ(t.points.rows(), 2);
  EXPECT_EQ(t.points.row(0), Eigen::RowVector2d(1, 2.5));
  EXPECT_EQ(t.points.row(1), Eigen::RowVector2d(-300, 4));
  EXPECT_EQ(t.rest, (std::vector<std::string>{",a", ""}));
  EXPECT_EQ(point_csv_text(t), "x,y,name\n1,2.5,a\n-300,4\n");
  // No header when the first line holds numbers; no trailing line break needed.
  const PointTable u = parse_point_csv("5,6", "u.csv");
  EXPECT_EQ(u.header, "");
  EXPECT_EQ(u.points.rows(), 1);
  EXPECT_EQ(parse_point_csv("", "empty.csv").points.rows(), 0);
}

TEST(PointCsv, EveryCarriageReturnEndingALineIsDropped) {
  // Found by fuzz/point_csv_fuzz.cpp: "\r\r\n" left a '\r' in the header or a line's rest, which
  // the text written back lost, so a round trip changed the table or refused its own text.
  const PointTable t = parse_point_csv("x,y\r\r\n1,2,a\r\r\r\n", "t.csv");
  EXPECT_EQ(t.header, "x,y");
  EXPECT_EQ(t.rest, (std::vector<std::string>{",a"}));
  EXPECT_EQ(point_csv_text(t), "x,y\n1,2,a\n");
  // A first line whose y is a number but for its carriage returns is a point, not a header.
  EXPECT_THROW(parse_point_csv("a,0\r\r\n1,1,\n", "u.csv"), InvalidInput);
}

// A table of more points than the bound is refused at the first point beyond it, naming the file
// and its line, before it is read to the end.
TEST(PointCsv, MorePointsThanTheBoundAreRefused) {
  EXPECT_EQ(parse_point_csv("x,y\n1,2\n\n3,4\n5,6\n", "three.csv", 3).points.rows(), 3);
  try {
    parse_point_csv("x,y\n1,2\n\n3,4\n5,6\n7,8\n", "four.csv", 3);
    ADD_FAILURE() << "four points read with a bound of three";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()),
              "parse_point_csv: four.csv:6: more than the 3 points read (max_points; --max-points "
              "raises it, or split the file)");
  }
  EXPECT_EQ(kMaxCsvPoints, size_t(1) << 22);
}

TEST(PointCsv, BadLinesAreRefusedNamingTheFileAndLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"x,y\n1,2\n3,abc\n", "in.csv:3: expected two finite numbers \"x,y\" first, got \"3,abc\""},
      {"1,2\n3\n", "in.csv:2:"},
      {"1,2\nnan,4\n", "in.csv:2:"},
      {"1,2\n5,inf\n", "in.csv:2:"},
      {"1,2\n0x10,4\n", "in.csv:2:"},
      {"1,2\n\"5\",4\n", "in.csv:2:"},
      {"1,2\n1;2\n", "in.csv:2:"},
      {"x,y\nx,y\n", "in.csv:2:"},  // a second header
      {"1,2\n1e999,4\n", "in.csv:2:"},
  };
  for (const auto& [text, mentions] : cases) {
    SCOPED_TRACE(text);
    try {
      parse_point_csv(text, "in.csv");
      ADD_FAILURE() << "accepted";
    } catch (const InvalidInput& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("parse_point_csv: in.csv:", 0), 0u) << what;
      EXPECT_NE(what.find(mentions), std::string::npos) << what;
    }
  }
}

TEST(PointCsv, WritingRefusesWhatCannotBeRead) {
  PointTable t;
  t.points = Eigen::MatrixX2d::Zero(2, 2);
  t.rest = {""};
  EXPECT_THROW(point_csv_text(t), InvalidInput);  // rest rows
  t.rest = {"", ""};
  t.points(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(point_csv_text(t), InvalidInput);
}

class PointCsvFile : public testing::ScratchFolderTest {};

TEST_F(PointCsvFile, ReadsAFileAndNamesItWhenItCannot) {
  {
    std::ofstream out(path("in.csv"));
    out << "x,y\n1,2\n";
  }
  EXPECT_EQ(read_point_csv(path("in.csv")).points.rows(), 1);
  for (const std::string& bad : {path("missing.csv"), dir_.string()}) {
    try {
      read_point_csv(bad);
      ADD_FAILURE() << bad;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace geolens
