// `volcomp init CONFIG.ini -o MACHINE.toml [--patch FILE|-]`: the machine file with the nominal
// geometry of the configuration's kinematics, and the patch that loads volkins in its place
// (preproc/init/README.md). The patch goes to stdout unless --patch names a file; the summary
// always goes to stderr, so that stdout is a clean patch. Nothing is written on a refusal.
#include <CLI/CLI.hpp>
#include <stdlib.h>
#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "vc/tables/atomic_file.hpp"
#include "commands.hpp"
#include "vc/init/init.hpp"
#include "vc/init/text_file.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::cli {
namespace {

struct InitArgs {
  std::string ini;     // the LinuxCNC configuration's INI file
  std::string output;  // the machine file to write
  std::string patch;   // the patch's file; "" or "-": stdout
  bool edit_shared = false;
};

namespace fs = std::filesystem;

std::string today() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[16];
  std::strftime(text, sizeof text, "%Y-%m-%d", &local);
  return text;
}

// The machine file must load as every other tool loads it: a failure here is init's own bug,
// caught before anything is written.
void check_loads(const std::string& toml) {
  std::string temporary = (fs::temp_directory_path() / "volcomp-init-XXXXXX.toml").string();
  const int fd = mkstemps(temporary.data(), 5);
  if (fd < 0) throw std::runtime_error("cannot create a temporary file in " + fs::temp_directory_path().string());
  close(fd);
  try {
    std::ofstream(temporary) << toml;
    machine::load_machine(temporary);
  } catch (const std::exception& e) {
    fs::remove(temporary);
    throw std::runtime_error(std::string("volcomp init wrote a machine file that does not load (a bug): ") + e.what());
  }
  fs::remove(temporary);
}

void check_folder(const std::string& file, const char* what) {
  const fs::path folder = fs::absolute(file).parent_path();
  if (!fs::is_directory(folder)) throw std::runtime_error(std::string(what) + ": no folder " + folder.string());
}

// The outputs against each other and against every file init reads (the inputs are known once
// read), before anything is written.
void check_outputs(const InitArgs& args, const std::vector<init::InputFile>& inputs) {
  const bool patch_to_file = !args.patch.empty() && args.patch != "-";
  init::refuse_input_as_output(inputs, "-o", args.output);
  if (patch_to_file) init::refuse_input_as_output(inputs, "--patch", args.patch);
}

init::InitResult read_configuration(const InitArgs& args) {
  if (args.output == "-")
    throw std::runtime_error(
        "error: -o -: the machine file needs a name (volkins' machine= names it in the INI); it is the patch that "
        "goes to stdout (no --patch, or --patch -)");
  if (!args.patch.empty() && args.patch != "-" && init::same_file(args.output, args.patch))
    throw std::runtime_error("error: -o " + init::printable(args.output) + " and --patch " +
                             init::printable(args.patch) + " are the same file: give them two (nothing was written)");
  try {
    return init::run_init({args.ini, args.output, today(), args.edit_shared});
  } catch (const std::exception& e) {
    // A message quotes lines of the user's files: no raw control bytes into the terminal.
    throw std::runtime_error(init::printable(e.what()));
  }
}

int run_init(const InitArgs& args, std::ostream& patch_out, std::ostream& report) {
  const init::InitResult r = read_configuration(args);
  check_outputs(args, r.inputs);
  std::vector<init::InputFile> created;
  for (const std::string& file : r.patch.created) created.push_back({file, "a file the patch creates"});
  check_outputs(args, created);
  check_loads(r.machine_text);
  const bool patch_to_file = !args.patch.empty() && args.patch != "-";
  check_folder(args.output, "-o");
  if (patch_to_file) check_folder(args.patch, "--patch");

  tables::write_atomically(args.output, [&](std::ostream& out) { out << r.machine_text; });
  if (patch_to_file)
    tables::write_atomically(args.patch, [&](std::ostream& out) { out << r.patch.diff; });
  else
    patch_out << r.patch.diff << std::flush;

  report << "volcomp init: " << r.machine.name << " (" << fs::absolute(args.ini).lexically_normal().string() << ")\n"
         << "  kinematics: " << r.machine.module << ", joints " << r.machine.coordinates << " -> " << r.patch.kinematics
         << '\n'
         << "  machine file: " << args.output << ": nominal geometry, zero errors; add the measured error tables "
         << "(machines/README.md section 5), then `volcomp check " << args.output << " --ini " << args.ini
         << "` (after the patch: the configuration's limits against the correction, where it homes and the room its "
         << "joint limits leave)\n"
         << "  patch (" << (patch_to_file ? args.patch : std::string("stdout")) << "):";
  for (const std::string& change : r.patch.changes) report << "\n    " << change;
  report << "\n  apply it: patch -p1 -d " << r.folder << " < " << (patch_to_file ? args.patch : std::string("PATCH"))
         << '\n';
  for (const std::string& file : r.not_read) report << "  not read: " << file << '\n';
  for (const std::string& remark : r.machine.remarks) report << "  note: " << remark << '\n';
  for (const std::string& remark : r.remarks) report << "  note: " << remark << '\n';
  return 0;
}

}  // namespace

void add_init_command(CLI::App& volcomp, int& exit_code) {
  auto args = std::make_shared<InitArgs>();
  CLI::App* cmd = volcomp.add_subcommand(
      "init",
      "From a LinuxCNC configuration: a machine file with its kinematics' nominal geometry (zero errors) "
      "and the patch that loads volkins in place of the stock module (summary on stderr)");
  cmd->add_option("CONFIG", args->ini, "the configuration's INI file")->required();
  cmd->add_option("-o,--output", args->output, "the machine file to write (.toml)")->required();
  cmd->add_option("--patch", args->patch,
                  "write the patch (unified diff, for patch -p1 -d CONFIG_DIR) to this file; - or none: stdout");
  cmd->add_flag("--edit-shared", args->edit_shared,
                "edit files other configurations use too (#INCLUDEd files, HAL files another INI of the folder "
                "names) in place; without it the patch gives this configuration its own copy of them");
  cmd->callback([args, &exit_code] { exit_code = run_init(*args, std::cout, std::cerr); });
}

}  // namespace vc::cli
