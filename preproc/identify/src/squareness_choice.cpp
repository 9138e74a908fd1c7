#include "vc/identify/squareness_choice.hpp"

namespace vc::identify {

const SquarenessTerm* chosen_squareness_term(const std::vector<SquarenessTerm>& terms, const std::string& symbol) {
  const SquarenessTerm* chosen = terms.empty() ? nullptr : &terms.front();
  for (const SquarenessTerm& t : terms)
    if (!symbol.empty() ? t.symbol == symbol : t.in_file_rad != 0.0) chosen = &t;
  if (chosen && !symbol.empty() && chosen->symbol != symbol) return nullptr;
  return chosen;
}

}  // namespace vc::identify
