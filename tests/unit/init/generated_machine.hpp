// `volcomp init` run on a configuration in a test: its result and its machine file, written in a
// scratch folder and loaded as every tool loads it.
#pragma once

#include <filesystem>
#include <string>

#include "init_test_files.hpp"
#include "vc/init/init.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::test {

struct Generated {
  init::InitResult result;
  machine::Model model;
};

inline Generated generate(const std::filesystem::path& ini, const std::string& name) {
  const std::filesystem::path dir = scratch_folder(name);
  Generated g{init::run_init({ini.string(), (dir / "machine.toml").string(), "2026-01-01"}), {}};
  write_file(dir / "machine.toml", g.result.machine_text);
  g.model = machine::load_machine((dir / "machine.toml").string());
  return g;
}

}  // namespace vc::test
