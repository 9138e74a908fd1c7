// Lines whose meaning depends on where they are read (#<_line>), against LinuxCNC's own output.
#include <gtest/gtest.h>

#include "vc/gcode/syntax_error.hpp"
#include "vc/interpreter/line_text.hpp"

namespace vc::interpreter {
namespace {

gcode::Parameters example_parameters() {
  gcode::Parameters p;
  p.set(1, 2.5, 0);
  p.set(2, -3.14159, 0);
  p.set("depth", -0.00001);
  return p;
}

// Expected: rs274 (LinuxCNC 2.9) on line 5 of
//   #1=2.5 / #<depth>=-0.00001 / #2=-3.14159 / (DEBUG, a #1 b %d#1 ...)
// printed MESSAGE(" a 2.500000 b 2 c -3.1416 d 0.00 e ###### f # g %x .x ###### 5.00").
TEST(LineText, MessagesExpandAsLinuxCncExpandsThem) {
  const gcode::Parameters p = example_parameters();
  EXPECT_EQ(expand_message(" a #1 b %d#1 c %f#2 d %.2f#<depth> e #<nope> f # g %x %.x #9999 #<_line>", p, 5),
            " a 2.500000 b 2 c -3.1416 d 0.00 e ###### f # g %x .x ###### 5.00");
  EXPECT_EQ(expand_message("%.3f#2", p, 6), "-3.142");  // rs274: (print,%.3f#2) printed -3.142
}

TEST(LineText, LineNumberIsPinnedInWordsAndExpandedMessagesOnly) {
  const gcode::Parameters p = example_parameters();
  std::string raw = "G1 X[#< _Line >+1] (DEBUG, at #<_line> #1) (MSG, #<_line>) ; #<_line>";
  EXPECT_TRUE(pin_line_number(raw, 12, p));
  EXPECT_EQ(raw, "G1 X[12+1] (DEBUG, at 12.000000 2.500000) (MSG, #<_line>) ; #<_line>");
  std::string other = "G1 X#1 (DEBUG, #1)";
  EXPECT_FALSE(pin_line_number(other, 12, p));
  EXPECT_EQ(other, "G1 X#1 (DEBUG, #1)");
  std::string unknown = "(PRINT, #<_line> #<nope>)";  // "######" would be read again as parameters
  EXPECT_THROW(pin_line_number(unknown, 3, p), gcode::SyntaxError);
}

}  // namespace
}  // namespace vc::interpreter
