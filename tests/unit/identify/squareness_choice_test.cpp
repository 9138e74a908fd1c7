// Which squareness term identify circle sets: the one asked for, else the one the machine file
// already uses, else the first; none when asked for one the plane does not have.
#include <gtest/gtest.h>

#include "vc/identify/squareness_choice.hpp"

namespace vc::identify {
namespace {

SquarenessTerm term(const std::string& symbol, double in_file_rad) { return {symbol, 1e-5, in_file_rad, 0.0}; }

TEST(SquarenessChoice, TheFirstWhenTheFileUsesNone) {
  const std::vector<SquarenessTerm> terms = {term("EC0Y", 0.0), term("EC0X", 0.0)};
  EXPECT_EQ(chosen_squareness_term(terms, ""), &terms[0]);
}

TEST(SquarenessChoice, TheOneTheFileAlreadyUses) {
  const std::vector<SquarenessTerm> terms = {term("EC0Y", 0.0), term("EC0X", 2e-6)};
  EXPECT_EQ(chosen_squareness_term(terms, ""), &terms[1]);
}

TEST(SquarenessChoice, TheOneAskedForEvenWhereTheFileUsesAnother) {
  const std::vector<SquarenessTerm> terms = {term("EC0Y", 0.0), term("EC0X", 2e-6)};
  EXPECT_EQ(chosen_squareness_term(terms, "EC0Y"), &terms[0]);
}

TEST(SquarenessChoice, NoneWhenAskedForOneThePlaneDoesNotHaveOrThereAreNoTerms) {
  const std::vector<SquarenessTerm> terms = {term("EC0Y", 0.0), term("EC0X", 2e-6)};
  EXPECT_EQ(chosen_squareness_term(terms, "EB0X"), nullptr);
  EXPECT_EQ(chosen_squareness_term({}, ""), nullptr);
}

}  // namespace
}  // namespace vc::identify
