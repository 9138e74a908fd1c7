#include <iostream>
#include "vc/machine/load_machine.hpp"
#include "vc/machine/correct.hpp"
int main(int argc, char** argv) {
  try {
    auto m = vc::machine::load_machine(argv[1]);
    std::cout << m.coordinates() << "\n";
  } catch (const std::exception& e) { std::cerr << e.what() << "\n"; return 1; }
}
