// Golden bad inputs: every file in tests/golden/bad_tables and tests/golden/bad_machines must
// be refused with exactly the message in its .expect file (paths relative to the repository
// root). Adding a case is adding two files. VC_UPDATE_GOLDEN=1 rewrites the .expect files
// (review the wording before committing them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/tables/load_table.hpp"

namespace vc {
namespace {

namespace fs = std::filesystem;

std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

std::string relative_message(std::string message) {
  const std::string root = std::string(VC_SOURCE_DIR) + "/";
  for (std::size_t at; (at = message.find(root)) != std::string::npos;) message.erase(at, root.size());
  return message;
}

template <typename Load>
void check_folder(const std::string& folder, const std::string& extension, Load load) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(test::source_path(folder)))
    if (entry.path().extension() == extension) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  const bool update = std::getenv("VC_UPDATE_GOLDEN") != nullptr;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    std::string message;
    try {
      load(file.string());
      ADD_FAILURE() << "accepted a bad file";
      continue;
    } catch (const LoadError& e) {
      message = relative_message(e.what());
    }
    fs::path expect = file;
    expect.replace_extension(".expect");
    if (update) std::ofstream(expect) << message << '\n';
    std::ifstream in(expect);
    ASSERT_TRUE(in) << "missing " << expect.filename() << "; the message is: " << message;
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(message, trimmed(text.str()));
  }
}

TEST(BadFiles, EveryBadTableIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_tables", ".csv", [](const std::string& p) { tables::load_table(p); });
}

TEST(BadFiles, CubicOnACrossAxisTableIsRefused) {
  tables::TableOptions cubic;
  cubic.interpolation = tables::Interpolation::Cubic;
  try {
    tables::load_table(test::source_path("machines/../tables/data/mill3/z_by_y.csv"), cubic);
    FAIL() << "accepted";
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find(":5:7: error: cubic interpolation is for 1-D tables"), std::string::npos)
        << e.what();
  }
}

TEST(BadFiles, EveryBadMachineIsRefusedWithItsMessage) {
  check_folder("tests/golden/bad_machines", ".toml", [](const std::string& p) { machine::load_machine(p); });
}

}  // namespace
}  // namespace vc
