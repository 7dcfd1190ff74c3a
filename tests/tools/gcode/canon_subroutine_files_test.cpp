// Subroutines in files of their own (o<name> call finding name.ngc on the
// subroutine path) in the LinuxCNC-dialect interpreter. The oracle test
// test_subroutine_files_agree runs the same kind of program against rs274,
// which finds the files in its working directory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/tools/gcode/canon_test_support.hpp"
#include "tests/tools/unique_temp_dir.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {
namespace subroutine_files_test {

class SubroutineFiles : public ::testing::Test {
 protected:
  void SetUp() override { std::filesystem::create_directories(dir_ / "lib"); }
  void write(const std::filesystem::path& relative, const std::string& text) const {
    std::ofstream(dir_ / relative) << text;
  }
  CanonResult run(const std::string& program, std::vector<std::string> path = {}) const {
    write("main.ngc", program);
    CanonSetup setup;
    for (std::string& p : path) p = (dir_ / p).string();
    setup.subroutine_path = path;
    return interpret_canon_file((dir_ / "main.ngc").string(), setup);
  }
  tnv::test::UniqueTempDir tmp_{"tnv-subfiles"};  // its own: another checkout's tests may run beside these
  const std::filesystem::path& dir_ = tmp_.path();
};

std::vector<std::string> feeds(const CanonResult& r) {
  std::vector<std::string> out;
  for (const CanonCall& c : r.calls)
    if (c.text.rfind("STRAIGHT_FEED(", 0) == 0) out.push_back(c.text.substr(14, 22));
  return out;
}

TEST_F(SubroutineFiles, ACallFindsTheFileBesideTheProgramThenOnThePathAndFilesCallFiles) {
  write("square.ngc", "(a file LinuxCNC-style)\no<square> sub\nG1 X#1 Y0\no<corner> call [#1]\no<square> endsub\nM2\n");
  write("lib/corner.ngc", "o<corner> sub\nG1 X#1 Y#1\no<corner> endsub\n");
  const CanonResult r = run("G21 F100\no<square> call [4]\no<square> call [2]\nM2\n", {"lib"});
  ASSERT_FALSE(r.error) << to_string(*r.error);
  EXPECT_EQ(feeds(r), (std::vector<std::string>{"4.0000, 0.0000, 0.0000", "4.0000, 4.0000, 0.0000",
                                                 "2.0000, 0.0000, 0.0000", "2.0000, 2.0000, 0.0000"}));
}

TEST_F(SubroutineFiles, TheProgramsOwnDefinitionComesFirstAndTheDirectoriesInOrder) {
  write("mark.ngc", "o<mark> sub\nG1 X9\no<mark> endsub\n");
  write("lib/other.ngc", "o<other> sub\nG1 X7\no<other> endsub\n");
  std::filesystem::create_directories(dir_ / "lib2");
  write("lib2/other.ngc", "o<other> sub\nG1 X8\no<other> endsub\n");
  CanonResult r = run("o<mark> sub\nG1 X1\no<mark> endsub\nG21 F100\no<mark> call\nM2\n");
  ASSERT_FALSE(r.error) << to_string(*r.error);
  EXPECT_EQ(feeds(r), std::vector<std::string>{"1.0000, 0.0000, 0.0000"});
  r = run("G21 F100\no<other> call\nM2\n", {"lib", "lib2"});
  ASSERT_FALSE(r.error) << to_string(*r.error);
  EXPECT_EQ(feeds(r), std::vector<std::string>{"7.0000, 0.0000, 0.0000"});
}

TEST_F(SubroutineFiles, RefusalsNameTheFileAndItsLine) {
  // Not found anywhere: refused when the call runs, saying where it looked.
  CanonResult r = run("G21 F100\nG1 X1\no<nowhere> call\nM2\n");
  ASSERT_TRUE(r.error);
  EXPECT_TRUE(r.calls.empty());
  EXPECT_EQ(r.error->line, 3);
  EXPECT_NE(r.error->message.find("nor a file nowhere.ngc"), std::string::npos) << r.error->message;
  // ... but a call that never runs is no error, as in LinuxCNC.
  r = run("G21 F100\no1 if [0]\no<nowhere> call\no1 endif\nM2\n");
  EXPECT_FALSE(r.error) << to_string(*r.error);
  // A file without the definition of its name.
  write("empty.ngc", "G1 X1\nM2\n");
  r = run("G21 F100\no<empty> call\nM2\n");
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->line, 2);
  EXPECT_TRUE(r.error->file.empty());
  EXPECT_NE(r.error->message.find("has no o<empty> sub"), std::string::npos) << r.error->message;
  // An error inside the file names the file and the file's line.
  write("bad.ngc", "\n\no<bad> sub\nG1 X1 Q5\no<bad> endsub\n");
  r = run("G21 F100\no<bad> call\nM2\n");
  ASSERT_TRUE(r.error);
  EXPECT_EQ(r.error->line, 4);
  EXPECT_EQ(std::filesystem::path(r.error->file).filename(), "bad.ngc");
  EXPECT_NE(to_string(*r.error).find("bad.ngc, line 4"), std::string::npos) << to_string(*r.error);
  // A name with a path in it is never looked up as a file.
  write("lib/evil.ngc", "o<evil> sub\nG1 X1\no<evil> endsub\n");
  r = run("G21 F100\no<lib/evil> call\nM2\n");
  EXPECT_TRUE(r.error);
}

TEST_F(SubroutineFiles, RunFromLineCountsTheProgramsLinesOnly) {
  write("two.ngc", "o<two> sub\nG1 X2\nG1 Y2\no<two> endsub\n");
  write("main.ngc", "G21 F100\no<two> call\nG1 X5\nM2\n");
  CanonSetup setup;
  setup.from_line = RunFromLine{};
  setup.from_line->line = 3;
  const CanonResult r = interpret_canon_file((dir_ / "main.ngc").string(), setup);
  ASSERT_FALSE(r.error) << to_string(*r.error);
  ASSERT_FALSE(r.calls.empty());
  EXPECT_EQ(feeds(r).back(), "5.0000, 2.0000, 0.0000");  // after the file's moves, from the program's line 3
  setup.from_line->line = 5;  // the program has 4 lines (the file's are not the program's)
  EXPECT_TRUE(interpret_canon_file((dir_ / "main.ngc").string(), setup).error);
}

}  // namespace subroutine_files_test
}  // namespace tnv::gcode
