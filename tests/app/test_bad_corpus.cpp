// The bad-input corpus (tests/data/bad/manifest.txt, docs/robustness.md): every case is run
// through the softsub binary from a copy of the folder and must give its exit code, its
// message, `<file>:<line>` where a line is known, one line, nothing written, in under 2 s.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "app_test_util.h"

namespace softsub::apptest {
namespace {

struct Case {
  int manifestLine = 0;
  std::string args;
  int exitCode = 0;
  std::string where;  // "<file>:<line>", "<file>" or "-"
  std::string pattern;
};

std::string trim(std::string s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.erase(s.begin());
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.pop_back();
  return s;
}

fs::path corpusDir() { return fs::path(SOFTSUB_SOURCE_DIR) / "tests/data/bad"; }

std::vector<Case> readManifest() {
  std::ifstream in(corpusDir() / "manifest.txt");
  std::vector<Case> cases;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    std::vector<std::string> parts;
    std::size_t start = 0;
    // Four fields: the pattern (last) may itself hold '|'.
    for (int k = 0; k < 3; ++k) {
      const std::size_t bar = line.find('|', start);
      if (bar == std::string::npos) break;
      parts.push_back(trim(line.substr(start, bar - start)));
      start = bar + 1;
    }
    parts.push_back(trim(line.substr(start)));
    if (parts.size() != 4) {
      ADD_FAILURE() << "manifest line " << n << " has no 4 fields: " << line;
      continue;
    }
    cases.push_back({n, parts[0], std::stoi(parts[1]), parts[2], parts[3]});
  }
  return cases;
}

/// Every file and folder under dir with its size, relative, sorted.
std::vector<std::string> snapshot(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    std::string entry = fs::relative(e.path(), dir).string();
    if (e.is_regular_file()) {
      entry.append(" ").append(std::to_string(e.file_size()));
    } else {
      entry.append("/");
    }
    out.push_back(std::move(entry));
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The files the manifest names (the first argument that is a file of the folder).
std::vector<std::string> namedFiles(const std::vector<Case>& cases, const fs::path& dir) {
  std::vector<std::string> out;
  for (const Case& c : cases) {
    std::istringstream words(c.args);
    std::string w;
    while (words >> w) {
      if (fs::is_regular_file(dir / w)) out.push_back(w);
    }
  }
  return out;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr double kSecondsAllowed = 20;  // the sanitizers slow everything down
#else
constexpr double kSecondsAllowed = 2;
#endif

TEST(BadCorpus, EveryCaseGivesItsExitCodeMessageAndLineAndWritesNothing) {
  const std::vector<Case> cases = readManifest();
  ASSERT_GE(cases.size(), 60U);
  TempDir tmp;
  fs::copy(corpusDir(), tmp.path(), fs::copy_options::recursive);
  const std::vector<std::string> before = snapshot(tmp.path());
  for (const Case& c : cases) {
    SCOPED_TRACE("manifest line " + std::to_string(c.manifestLine) + ": softsub " + c.args);
    const auto t0 = std::chrono::steady_clock::now();
    const RunResult r = runSoftsub(c.args, tmp.path());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(r.code, c.exitCode) << r.err;
    EXPECT_LT(seconds, kSecondsAllowed);
    EXPECT_EQ(snapshot(tmp.path()), before) << "the case wrote or changed files";
    if (c.exitCode == 0) {
      // A warning with a sane result: every stderr line is a warning, one holds the
      // pattern, and the result is on stdout.
      EXPECT_NE(r.err.find("warning: "), std::string::npos) << r.err;
      std::istringstream lines(r.err);
      bool found = false;
      for (std::string l; std::getline(lines, l);) {
        EXPECT_EQ(l.rfind("warning: ", 0), 0U) << l;
        found = found || l.find(c.pattern) != std::string::npos;
      }
      EXPECT_TRUE(found) << "no warning with '" << c.pattern << "' in\n" << r.err;
      EXPECT_FALSE(r.out.empty());
      continue;
    }
    EXPECT_EQ(r.err.rfind("error: ", 0), 0U) << r.err;
    EXPECT_NE(r.err.find(c.pattern), std::string::npos) << "expected '" << c.pattern << "' in\n" << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line expected:\n" << r.err;
    if (c.where != "-") {
      // (append, not operator+: GCC 12 warns -Wrestrict inside it)
      const std::string start = std::string("error: ").append(c.where).append(": ");
      EXPECT_EQ(r.err.rfind(start, 0), 0U) << r.err;
    }
  }
  // Every corpus file is used by some case (a file nobody runs is dead weight).
  const std::vector<std::string> named = namedFiles(cases, tmp.path());
  for (const auto& e : fs::recursive_directory_iterator(tmp.path())) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), tmp.path()).string();
    if (rel == "manifest.txt" || rel.rfind("meshes/", 0) == 0) continue;  // meshes: named in scenes too
    EXPECT_NE(std::find(named.begin(), named.end(), rel), named.end()) << rel << " is in no case";
  }
}

}  // namespace
}  // namespace softsub::apptest
