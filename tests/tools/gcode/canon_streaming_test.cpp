// The interpreter hands each call to a sink as it makes it (no call is
// held: docs/gcode.md "Speed against rs274"), and what collects or prints
// the calls keeps a refused program's calls back.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/canon_text_spool.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::gcode {
namespace {

// Line 1 sets the feed, lines 2..n+1 move (each to a new point).
std::string moves(int n) {
  std::string text = "F600\n";
  for (int k = 1; k <= n; ++k) {
    text += "G1 X";
    text += std::to_string(k % 50);
    text += " Y";
    text += std::to_string(k % 7);
    text += '\n';
  }
  return text;
}

TEST(CanonStreaming, TheSinkGetsTheCallsInTheOrderInterpretCanonReturnsThem) {
  const std::string text = moves(200) + "o1 repeat [3]\nG0 X1\no1 endrepeat\nM2\n";
  std::vector<CanonCall> streamed;
  const CanonRun run = interpret_canon_to(text, {}, [&](const CanonCall& c) { streamed.push_back(c); });
  ASSERT_FALSE(run.error);
  const CanonResult all = interpret_canon(text);
  ASSERT_EQ(streamed.size(), all.calls.size());
  for (std::size_t k = 0; k < streamed.size(); ++k) {
    EXPECT_EQ(streamed[k].text, all.calls[k].text);
    EXPECT_EQ(streamed[k].line, all.calls[k].line);
  }
  EXPECT_EQ(run.lines_run, all.lines_run);
}

TEST(CanonStreaming, CallsGoOutBeforeTheEndAndARefusalIsKeptBackByWhoCollects) {
  // Line 103 is refused: the calls of lines 1..102 were handed out already
  // (nothing held them), and interpret_canon, which collects, returns none.
  const std::string text = moves(100) + "G0 X0\nG5.2 X1\nM2\n";
  std::size_t handed = 0;
  int last_line = 0;
  const CanonRun run = interpret_canon_to(text, {}, [&](const CanonCall& c) {
    ++handed;
    last_line = c.line;
  });
  ASSERT_TRUE(run.error);
  EXPECT_EQ(run.error->line, 103);
  EXPECT_GT(handed, 100u);
  EXPECT_EQ(last_line, 102);
  const CanonResult collected = interpret_canon(text);
  ASSERT_TRUE(collected.error);
  EXPECT_TRUE(collected.calls.empty());
}

TEST(CanonStreaming, TheSpoolGivesBackExactlyTheCallsText) {
  const std::string text = moves(500) + "M2\n";
  CanonTextSpool spool;
  const CanonRun run = interpret_canon_to(text, {}, [&spool](const CanonCall& c) { spool(c); });
  ASSERT_FALSE(run.error);
  std::ostringstream out;
  std::string error;
  ASSERT_TRUE(spool.copy_to(out, error)) << error;
  EXPECT_EQ(out.str(), canon_text(interpret_canon(text).calls));
}

TEST(CanonStreaming, SegmentsAreMadeAsTheCallsComeAndTheInterpretersErrorComesFirst) {
  const GcodeResult ok = parse_gcode(moves(300));
  ASSERT_FALSE(ok.error);
  EXPECT_EQ(ok.program.segments.size(), 300u);
  EXPECT_EQ(ok.program.segments.back().tag, 301u);
  // A move the machine cannot make (beyond the travel, line 2) and, later, a line
  // the interpreter refuses (line 4): the interpreter's error is the one
  // reported, as when the calls were converted after the run.
  const GcodeResult both = parse_gcode("G1 X1 F60\nG1 X1000\nG17 G1 X2\nG5.2 X3\nM2\n");
  ASSERT_TRUE(both.error);
  EXPECT_EQ(both.error->line, 4);
  EXPECT_TRUE(both.program.segments.empty());
  const GcodeResult z_only = parse_gcode("G1 X1 F60\nG1 X1000\nG17 G1 X2\nM2\n");
  ASSERT_TRUE(z_only.error);
  EXPECT_EQ(z_only.error->line, 2);
  EXPECT_TRUE(z_only.program.segments.empty());
}

}  // namespace
}  // namespace tnv::gcode
