// The reader's numbers: the correctly rounded double of their digits, as LinuxCNC's strtod
// reads them, whichever way parse_block takes (its fast path for short numbers or
// std::from_chars for long ones).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "vc/gcode/evaluate.hpp"
#include "vc/gcode/parameters.hpp"
#include "vc/gcode/parser.hpp"

namespace vc::gcode {
namespace {

double parsed(const std::string& number) {
  Block block;
  parse_block("X" + number, block);
  EXPECT_EQ(block.words.size(), 1u) << number;
  return evaluate(block.words.front().value, Parameters(), 1);
}

// Bit for bit (so -0 and 0 differ).
void expect_strtod(const std::string& number) {
  const double expected = std::strtod(number.c_str(), nullptr), got = parsed(number);
  EXPECT_EQ(0, std::memcmp(&expected, &got, sizeof got)) << number << ": " << got << " vs strtod " << expected;
}

TEST(Parser, NumbersAtTheEdgesOfTheShortWayReadAsStrtod) {
  for (const char* n : {"0",
                        "-0",
                        "+0",
                        "-0.0000",
                        "1.",
                        ".5",
                        "-.5",
                        "007.25",
                        "0.1",
                        "-240.0000",
                        "9007199254740992",
                        "9007199254740993",
                        "9007199254740991.",
                        "900719925474099.3",
                        "1234567890123456789",
                        "12345678901234567890",
                        "0.0000000000000000000001",
                        "0.00000000000000000000001",
                        "1.0000000000000000000000",
                        "0.30000000000000004",
                        "123456789012.3456789",
                        "99999999999999999999.9",
                        "4.35",
                        "2.675",
                        "0.000001"})
    expect_strtod(n);
}

TEST(Parser, RandomNumbersReadAsStrtod) {
  std::mt19937_64 random(20261123);
  std::uniform_int_distribution<int> length(1, 26), digit(0, 9), sign(0, 3);
  for (int i = 0; i < 200000; ++i) {
    std::string n;
    const int s = sign(random);
    if (s == 0) n += '-';
    if (s == 1) n += '+';
    const int digits = length(random);
    const int point = std::uniform_int_distribution<int>(-1, digits)(random);  // -1: none
    for (int d = 0; d < digits; ++d) {
      if (d == point) n += '.';
      n += static_cast<char>('0' + digit(random));
    }
    if (point == digits) n += '.';
    expect_strtod(n);
  }
}

TEST(Parser, OWordsWithTheirKeywordAndArguments) {
  Block block;
  parse_block("N10 O0100 call [1+1] [#2] (comment)", block);
  EXPECT_EQ(block.o_word, 4);
  EXPECT_EQ(block.o.name, "100");
  EXPECT_EQ(block.o.kind, OWord::Kind::Call);
  ASSERT_EQ(block.o.args.size(), 2u);
  Parameters p;
  p.set(2, 5.0, 0);
  EXPECT_EQ(evaluate(block.o.args[1], p, 0), 5.0);
  parse_block("o< My Sub > endsub", block);
  EXPECT_EQ(block.o.name, "mysub");
  EXPECT_EQ(block.o.kind, OWord::Kind::EndSub);
  EXPECT_TRUE(block.o.args.empty());
  parse_block("O1000", block);
  EXPECT_EQ(block.o.kind, OWord::Kind::None);
  for (const char* bad : {"o1 while", "o1 if [1] [2]", "o1 frobnicate", "o1 endif [1]", "G1 o1 if [1]", "o<x sub"}) {
    EXPECT_THROW(parse_block(bad, block), SyntaxError) << bad;
  }
}

}  // namespace
}  // namespace vc::gcode
