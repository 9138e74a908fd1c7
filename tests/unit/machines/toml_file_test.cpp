// TomlFile, the TOML reading every input file shares: a syntax error and each typed getter's
// problem name the FILE:LINE:COLUMN of the key or value concerned.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "vc/machine/toml_file.hpp"

namespace vc::machine {
namespace {

namespace fs = std::filesystem;

std::string written(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("vc_toml_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  return file.string();
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const LoadError& e) {
    return e.what();
  }
  return "no error";
}

TEST(TomlFile, SyntaxErrorAtItsLineAndColumn) {
  const std::string path = written("bad.toml", "a = 1\nb = = 2\n");
  EXPECT_EQ(error_of([&] { TomlFile{path}; }).rfind(path + ":2:5: error: ", 0), 0u);
}

TEST(TomlFile, MissingFileNamesIt) {
  const std::string path = (fs::temp_directory_path() / "vc_toml_file_none.toml").string();
  EXPECT_EQ(error_of([&] { TomlFile{path}; }).rfind(path, 0), 0u);
}

TEST(TomlFile, TypedGettersNameTheirPlace) {
  const std::string path = written("ok.toml", "[head]\nname = \"mc\"\nsize = 2.5\nflag = true\nodd = 1\n");
  const TomlFile file(path);
  const toml::table& head = *file.table(file.root(), "head", true, "the file");
  EXPECT_EQ(file.text(head, "name", true, "[head]"), "mc");
  EXPECT_EQ(file.text(head, "title", false, "[head]"), "");
  EXPECT_DOUBLE_EQ(file.scalar(*head.get("size"), "size"), 2.5);
  EXPECT_DOUBLE_EQ(file.scalar(*head.get("odd"), "odd"), 1.0);
  EXPECT_EQ(file.get(head, "none", false, "[head]"), nullptr);
  EXPECT_EQ(error_of([&] { file.get(head, "none", true, "[head]"); }), path + ":1:1: error: [head] needs 'none'");
  EXPECT_EQ(error_of([&] { file.get(head, "none", true, ""); }), path + ":1:1: error: needs 'none'");
  EXPECT_EQ(error_of([&] { file.text(head, "size", true, ""); }), path + ":3:8: error: 'size' must be a string");
  EXPECT_EQ(error_of([&] { file.scalar(*head.get("flag"), "flag"); }),
            path + ":4:8: error: 'flag' must be a finite number");
  EXPECT_EQ(error_of([&] { file.table(head, "name", false, ""); }), path + ":2:8: error: 'name' must be a table");
  EXPECT_EQ(error_of([&] { file.table(file.root(), "tail", true, "the file"); }),
            path + ":1:1: error: the file needs a [tail] table");
  EXPECT_EQ(error_of([&] {
              file.check_keys(head, "[head]", {"name", "size", "flag"});
            }),
            path + ":5:1: error: unknown key 'odd' in [head] (expected one of: name, size, flag)");
}

}  // namespace
}  // namespace vc::machine
