// Every validation rule of the reader (rows in reader_error_rows.h): the error names
// the file, the line, the element path, the problem and the allowed rule.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "reader_error_rows.h"
#include "scene_test_util.h"

namespace softsub::scene {
namespace {

using rules::kMark;
using rules::Row;
using rules::rows;
using testing::lineOf;
using testing::readError;

class ReaderError : public ::testing::TestWithParam<Row> {};

TEST_P(ReaderError, ReportsLineElementProblemAndRule) {
  const Row& row = GetParam();
  const int line = lineOf(row.text, kMark);
  ASSERT_GT(line, 0) << "row has no marker";
  const InputError e = readError(row.text);
  EXPECT_EQ(e.where().file, "t.scene");
  EXPECT_EQ(e.where().line, line) << e.what();
  EXPECT_EQ(e.where().element, row.element) << e.what();
  EXPECT_NE(e.problem().find(row.problem), std::string::npos) << e.what();
  if (!row.allowed.empty()) {
    EXPECT_NE(e.allowed().find(row.allowed), std::string::npos) << e.what();
  }
  // The one-line message carries every part.
  const std::string what = e.what();
  EXPECT_EQ(what.rfind("t.scene:" + std::to_string(line) + ": ", 0), 0U) << what;
  EXPECT_NE(what.find(row.element), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Rules, ReaderError, ::testing::ValuesIn(rows()),
                         [](const ::testing::TestParamInfo<Row>& row) { return row.param.name; });

TEST(ReaderErrorTable, HasARowPerRule) { EXPECT_GE(rows().size(), 45U); }

}  // namespace
}  // namespace softsub::scene
