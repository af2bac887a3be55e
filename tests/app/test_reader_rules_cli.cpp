// Every validation rule of the scene reader (tests/scene/reader_error_rows.h), through
// the command line: `softsub run` exits with code 2, prints the one-line message with
// file, line and element, and writes nothing.
#include <gtest/gtest.h>

#include <fstream>

#include "app_test_util.h"
#include "reader_error_rows.h"

namespace softsub::apptest {
namespace {

TEST(ReaderRulesCli, EveryRuleExitsTwoWithFileLineElementAndWritesNothing) {
  const auto rows = scene::rules::rows();
  ASSERT_GE(rows.size(), 45u);
  TempDir tmp;
  for (const scene::rules::Row& row : rows) {
    const fs::path scene = tmp / "t.scene";
    {
      std::ofstream out(scene, std::ios::binary);
      out << row.text;
    }
    const int line = scene::testing::lineOf(row.text, scene::rules::kMark);
    const RunResult r = runSoftsub("run t.scene", tmp.path());
    EXPECT_EQ(r.code, 2) << row.name << "\n" << r.err;
    const std::string head = "error: t.scene:" + std::to_string(line) + ": " + row.element + ": ";
    EXPECT_EQ(r.err.rfind(head, 0), 0u) << row.name << ": expected '" << head << "...' got\n" << r.err;
    EXPECT_NE(r.err.find(row.problem), std::string::npos) << row.name << "\n" << r.err;
    EXPECT_EQ(listEntries(tmp.path()), std::vector<std::string>{"t.scene"}) << row.name;
  }
}

}  // namespace
}  // namespace softsub::apptest
