// regress --coverage's reading of Verilator coverage files (sim/eda/verilator/coverage.h), on
// hand-made .dat files whose figures are counted by hand here, and its reading of the RTL's
// exclusion pragmas.
#include "sim/eda/verilator/coverage.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace shadesim {
namespace {

namespace fs = std::filesystem;

// One point as Verilator 5 writes it: C '\001f\002file\001l\002line...' count.
std::string point(const std::string& file, int line, const std::string& page,
                  const std::string& comment, const std::string& lines_covered, long long count) {
  std::string key = std::string("\001f\002") + file + "\001l\002" + std::to_string(line) +
                    "\001n\0023\001page\002" + page + "\001o\002" + comment;
  if (!lines_covered.empty()) key += "\001S\002" + lines_covered;
  key += "\001h\002TOP.shade_unit";
  return "C '" + key + "' " + std::to_string(count) + "\n";
}

class CoverageTest : public ::testing::Test {
 protected:
  fs::path dir =
      fs::temp_directory_path() / ("shadesim_coverage_test_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir / "rtl"); }
  void TearDown() override { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir / name;
    std::ofstream(p) << text;
    return p.string();
  }
};

TEST_F(CoverageTest, CountsLinesTogglesAndUserPointsPerFile) {
  const std::string a = (dir / "rtl" / "a.sv").string(), b = (dir / "rtl" / "b.sv").string();
  const std::string other = (dir / "cover.sv").string();
  const std::string dat = write(
      "cov.dat",
      std::string("# SystemC::Coverage-3\n") +
          // a.sv: a block over lines 10-12 run, an if-branch on 11 never taken (11 stays covered:
          // the block naming it ran), an else on 14 never taken, a branch on 20-21 taken.
          point(a, 10, "v_line/a", "block", "10-12", 7) +
          point(a, 11, "v_branch/a", "if", "11", 0) + point(a, 14, "v_branch/a", "else", "14", 0) +
          point(a, 20, "v_branch/a", "if", "20-21", 3) + point(a, 5, "v_toggle/a", "x[0]", "", 2) +
          point(a, 5, "v_toggle/a", "x[1]", "", 0) +
          // b.sv: one line, run; three toggles, two toggled.
          point(b, 3, "v_line/b", "block", "3", 1) + point(b, 4, "v_toggle/b", "y", "", 1) +
          point(b, 4, "v_toggle/b", "z", "", 9) + point(b, 4, "v_toggle/b", "w", "", 0) +
          // Outside rtl/: counted in its own row, not in the total; user points merge by name.
          point(other, 8, "v_line/c", "block", "8", 0) +
          point(other, 30, "v_user/c", "cov_edge", "", 2) +
          point(other, 30, "v_user/c", "cov_edge", "", 3) +
          point(other, 31, "v_user/c", "cov_never", "", 0));
  // never.sv: a module no run elaborated, 5 code lines (its comments and blank line are not);
  // pkg.sv: a package, no points and not counted.
  const std::string missing = write("rtl/never.sv",
                                    "// a header\nmodule never (\n  input logic a_i\n);\n\n"
                                    "  // why\n  assign x = a_i;\nendmodule\n");
  const std::string pkg = write("rtl/pkg.sv", "// constants\npackage p;\nendpackage\n");
  const CoverageSummary s = summarize_coverage(dat, (dir / "rtl").string(), {a, b, missing, pkg});
  ASSERT_EQ(s.files.size(), 4u);
  const CoverageFile& fa = s.files[1].path == a ? s.files[1] : s.files[0];
  ASSERT_EQ(fa.path, a);
  EXPECT_EQ(fa.lines, 6);  // 10, 11, 12, 14, 20, 21
  EXPECT_EQ(fa.lines_hit, 5);
  EXPECT_EQ(fa.uncovered_lines, std::vector<int>{14});
  EXPECT_EQ(fa.toggles, 2);
  EXPECT_EQ(fa.toggles_hit, 1);
  EXPECT_EQ(s.lines, 7 + 5);  // a's 6 + b's 1 + never's 5; cover.sv's line is not rtl/
  EXPECT_EQ(s.lines_hit, 6);
  EXPECT_EQ(s.toggles, 5);
  EXPECT_EQ(s.toggles_hit, 3);
  EXPECT_NEAR(s.line_pct(), 100.0 * 6 / 12, 1e-9);
  ASSERT_EQ(s.user.size(), 2u);
  EXPECT_EQ(s.user[0].name, "cov_edge");
  EXPECT_EQ(s.user[0].count, 5);
  EXPECT_EQ(s.user[1].name, "cov_never");
  EXPECT_EQ(s.user[1].count, 0);
  EXPECT_EQ(s.files_without_points, std::vector<std::string>{missing});
  EXPECT_EQ(s.packages, std::vector<std::string>{pkg});
  const auto never = std::find_if(s.files.begin(), s.files.end(),
                                  [&](const CoverageFile& f) { return f.path == missing; });
  ASSERT_NE(never, s.files.end());
  EXPECT_FALSE(never->elaborated);
  EXPECT_EQ(never->lines, 5);
  EXPECT_EQ(never->lines_hit, 0);
}

TEST_F(CoverageTest, NamesTheLineOfAMalformedPoint) {
  const std::string dat = write("bad.dat", "# SystemC::Coverage-3\nC 'no fields' 3\n");
  try {
    summarize_coverage(dat, (dir / "rtl").string(), {});
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.dat:2"), std::string::npos) << e.what();
  }
}

TEST_F(CoverageTest, ReadsExclusionsWithTheirReasons) {
  const std::string f =
      write("rtl/x.sv",
            "module x;\n"
            "  /* verilator coverage_off */  // parameter checks: never fail in a legal build\n"
            "  initial if (0) $fatal(1, \"no\");\n"
            "  /* verilator coverage_on */\n"
            "endmodule\n");
  const auto ex = list_exclusions({f});
  ASSERT_EQ(ex.size(), 1u);
  EXPECT_EQ(ex[0].first_line, 2);
  EXPECT_EQ(ex[0].last_line, 4);
  EXPECT_EQ(ex[0].reason, "parameter checks: never fail in a legal build");
}

TEST_F(CoverageTest, RefusesAnExclusionWithoutAReasonOrAnEnd) {
  const std::string bare = write(
      "rtl/bare.sv",
      "module y;\n  /* verilator coverage_off */\n  /* verilator coverage_on */\nendmodule\n");
  EXPECT_THROW(list_exclusions({bare}), std::runtime_error);
  const std::string open =
      write("rtl/open.sv", "module z;\n  /* verilator coverage_off */  // why\nendmodule\n");
  try {
    list_exclusions({open});
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("open.sv:2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace shadesim
