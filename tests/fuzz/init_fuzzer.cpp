// libFuzzer target: any bytes as a LinuxCNC configuration through `volcomp init` (run_init:
// the INI reader, its #INCLUDEs, the HAL files it names, the stock kinematics' geometry, the
// patch). The input is the INI file; a line "#FUZZ-HAL" in it ends the INI and starts a HAL
// file, fuzz.hal (empty without the line), beside the golden HAL files the seeds name
// (tests/golden/bad_inis/*.hal, good/xyzbc.hal), all in one configuration folder.
// Refusal (vc::LoadError) is the expected answer to bad input; a crash, a hang, a sanitizer
// report, any other exception, or an accepted configuration whose machine file volcomp then
// refuses to load (init promises a machine file; its tests `check` it) is a finding.
#include <filesystem>
#include <string>

#include "fuzz_support.hpp"
#include "vc/init/init.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/source_error.hpp"

namespace {

namespace fs = std::filesystem;

constexpr std::string_view kHalSeparator = "\n#FUZZ-HAL\n";

fs::path config_folder() {
  const fs::path folder = vc::fuzz::scratch() / "config";
  fs::create_directories(folder);
  for (const fs::path dir :
       {vc::fuzz::source_path("tests/golden/bad_inis"), vc::fuzz::source_path("tests/golden/bad_inis/good")})
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.path().extension() == ".hal")
        fs::copy_file(entry.path(), folder / entry.path().filename(), fs::copy_options::overwrite_existing);
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fs::path folder = config_folder();
  const std::string_view text = vc::fuzz::text_of(data, size);
  const std::size_t split = text.find(kHalSeparator);
  vc::fuzz::write_file(folder / "fuzz.hal",
                       split == std::string_view::npos ? "" : text.substr(split + kHalSeparator.size()));
  vc::init::InitRequest request;
  request.ini = vc::fuzz::write_file(folder / "fuzz.ini",
                                     text.substr(0, split == std::string_view::npos ? text.size() : split + 1));
  // Outside the configuration folder: an #INCLUDE cannot read a previous input's output.
  request.machine_file = (vc::fuzz::scratch() / "init-machine.toml").string();
  request.date = "2026-11-28";
  vc::init::InitResult result;
  try {
    result = vc::init::run_init(request);
  } catch (const vc::LoadError&) {
    return 0;
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("not a vc::LoadError: ") + e.what());
  }
  vc::fuzz::write_file(request.machine_file, result.machine_text);
  try {
    (void)vc::machine::load_machine(request.machine_file);
  } catch (const std::exception& e) {
    vc::fuzz::finding(std::string("init wrote a machine file volcomp refuses: ") + e.what() + "\n" +
                      result.machine_text);
  }
  return 0;
}
