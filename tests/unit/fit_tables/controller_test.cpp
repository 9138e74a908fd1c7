// The controller files: the shipped ones load and resolve against the shipped machines as the
// source and LinuxCNC define them; a bad file is refused naming its file and line.
#include "vc/fit_tables/controller.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "test_support.hpp"
#include "vc/fit_tables/table_set.hpp"
#include "vc/machine/load_machine.hpp"

namespace vc::fit_tables {
namespace {

namespace fs = std::filesystem;

fs::path scratch() {
  return fs::temp_directory_path() / ("vc_fit_tables_controller_test_" + std::to_string(::getpid()));
}

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path dir = scratch();
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  return file.string();
}

// The message of the LoadError `path` raises (empty if it loads).
std::string refusal(const std::string& path) {
  try {
    load_controller(path);
  } catch (const LoadError& e) {
    return e.what();
  }
  return "";
}

const char* const kHead = "[controller]\nname = \"test\"\n";

TEST(FitTablesController, ShippedFilesLoad) {
  EXPECT_EQ(shipped_controllers(), (std::vector<std::string>{"linuxcnc", "source14"}));
  const Controller lc = load_controller(controller_file("linuxcnc"));
  EXPECT_EQ(lc.name, "linuxcnc");
  ASSERT_EQ(lc.tables.size(), 1u);
  EXPECT_EQ(lc.tables[0].kind, TableKind::Positioning);
  EXPECT_EQ(lc.tables[0].input, "all");
  EXPECT_TRUE(lc.tables[0].direction_dependent);
  EXPECT_FALSE(lc.tables[0].modulo);
  EXPECT_EQ(lc.tables[0].max_nodes, 256);  // EMCMOT_COMP_SIZE
  EXPECT_FALSE(lc.checked_against.empty());

  const Controller s14 = load_controller(controller_file("source14"));
  ASSERT_EQ(s14.tables.size(), 10u);
  int cross = 0, square = 0;
  for (const TableSpec& t : s14.tables) {
    cross += t.kind == TableKind::Cross;
    square += t.kind == TableKind::Squareness;
    EXPECT_TRUE(t.modulo);
    EXPECT_EQ(t.resolution_um, 0.1);
  }
  EXPECT_EQ(cross, 6);
  EXPECT_EQ(square, 3);
}

TEST(FitTablesController, ResolvesAgainstTheShippedMachines) {
  const machine::Model mc300 = machine::load_machine(test::machine_path("mc300"));
  const machine::Model mill3 = machine::load_machine(test::machine_path("mill3"));
  const Controller lc = load_controller(controller_file("linuxcnc"));
  const Controller s14 = load_controller(controller_file("source14"));

  const TableSet a = resolve_tables(lc, mc300);
  ASSERT_EQ(a.tables.size(), 5u);  // X Y Z B C, each its own joint
  for (const Table& t : a.tables) {
    EXPECT_EQ(t.kind, TableKind::Positioning);
    EXPECT_EQ(t.input, t.output);
    EXPECT_EQ(t.nodes.size(), 7u);
    EXPECT_FALSE(t.modulo);  // LinuxCNC reads C at 370 deg as 370
  }
  EXPECT_EQ(a.unknowns, 35);
  EXPECT_EQ(a.tables[4].own_deviations, (std::vector<std::string>{"ECC"}));
  EXPECT_TRUE(a.notes.empty());

  const TableSet b = resolve_tables(s14, mc300, 13);
  ASSERT_EQ(b.tables.size(), 14u);  // the source's 14: 5 + 6 + 3
  EXPECT_TRUE(b.tables[4].modulo);  // C over 0..360: one unknown for 0 and 360
  EXPECT_EQ(b.tables[4].unknowns(), 12);
  EXPECT_EQ(b.unknowns, 4 * 13 + 12 + 6 * 13 + 3);
  EXPECT_EQ(b.name(mc300, b.tables[5]), "X->Y");
  EXPECT_EQ(b.tables[5].own_deviations, (std::vector<std::string>{"EYX"}));
  EXPECT_EQ(b.tables[11].own_deviations, (std::vector<std::string>{"EC0Y", "EC0X"}));  // Y -> X
  EXPECT_EQ(b.tables[12].own_deviations, (std::vector<std::string>{"EA0Z", "EA0Y"}));  // Z -> Y
  EXPECT_EQ(b.tables[13].own_deviations, (std::vector<std::string>{"EB0Z", "EB0X"}));  // Z -> X

  const TableSet c = resolve_tables(s14, mill3);
  EXPECT_EQ(c.tables.size(), 12u);  // no rotary axes: 3 + 6 + 3
  EXPECT_THROW(resolve_tables(lc, mc300, 257), std::invalid_argument);
  EXPECT_THROW(resolve_tables(lc, mc300, 1), std::invalid_argument);
}

TEST(FitTablesController, TablesOfAxesTheMachineLacksAreSkippedWithANote) {
  const std::string path = write_file("abc.toml", std::string(kHead) +
                                                      "[[table]]\nkind = \"positioning\"\naxis = \"B\"\n"
                                                      "[[table]]\nkind = \"positioning\"\naxis = \"X\"\n"
                                                      "[[table]]\nkind = \"cross\"\ninput = \"C\"\noutput = \"X\"\n");
  const machine::Model mill3 = machine::load_machine(test::machine_path("mill3"));
  const TableSet set = resolve_tables(load_controller(path), mill3);
  ASSERT_EQ(set.tables.size(), 1u);
  ASSERT_EQ(set.notes.size(), 2u);
  EXPECT_NE(set.notes[0].find("abc.toml:3:1: positioning table B skipped: mill3 has no axis B"), std::string::npos)
      << set.notes[0];
  EXPECT_NE(set.notes[1].find("has no axis C"), std::string::npos) << set.notes[1];
  fs::remove_all(scratch());
}

TEST(FitTablesController, BadFilesAreRefusedWithTheirLine) {
  const std::string unknown = write_file(
      "unknown.toml", std::string(kHead) + "[[table]]\nkind = \"positioning\"\naxis = \"all\"\ncolour = \"red\"\n");
  EXPECT_NE(refusal(unknown).find("unknown.toml:6:1: error: unknown key 'colour' in a positioning [[table]]"),
            std::string::npos)
      << refusal(unknown);
  const std::string kind = write_file("kind.toml", std::string(kHead) + "[[table]]\nkind = \"helical\"\n");
  EXPECT_NE(refusal(kind).find("kind.toml:4:8: error: unknown kind 'helical'"), std::string::npos) << refusal(kind);
  const std::string same =
      write_file("same.toml", std::string(kHead) + "[[table]]\nkind = \"cross\"\ninput = \"X\"\noutput = \"X\"\n");
  EXPECT_NE(refusal(same).find("same.toml:6:10: error: a cross table's output must be another axis"), std::string::npos)
      << refusal(same);
  const std::string square = write_file(
      "square.toml", std::string(kHead) + "[[table]]\nkind = \"squareness\"\ninput = \"B\"\noutput = \"X\"\n");
  EXPECT_NE(refusal(square).find("square.toml:5:9: error: 'input' must be a linear axis letter"), std::string::npos)
      << refusal(square);
  const std::string spacing = write_file(
      "spacing.toml",
      std::string(kHead) + "[defaults]\nspacing = \"chebyshev\"\n[[table]]\nkind = \"positioning\"\naxis = \"X\"\n");
  EXPECT_NE(refusal(spacing).find("spacing.toml:4:11: error: 'spacing' must be \"equal\""), std::string::npos)
      << refusal(spacing);
  const std::string nodes = write_file("nodes.toml", std::string(kHead) +
                                                         "[[table]]\nkind = \"positioning\"\naxis = \"X\"\n"
                                                         "max_nodes = 10\ndefault_nodes = 11\n");
  EXPECT_NE(refusal(nodes).find("nodes.toml:3:1: error: default_nodes (11) is above max_nodes (10)"), std::string::npos)
      << refusal(nodes);
  const std::string none = write_file("none.toml", kHead);
  EXPECT_NE(refusal(none).find("none.toml:1:1: error: the controller file needs at least one [[table]]"),
            std::string::npos)
      << refusal(none);
  const std::string syntax = write_file("syntax.toml", "[controller\n");
  EXPECT_NE(refusal(syntax).find("syntax.toml:1:"), std::string::npos) << refusal(syntax);
  EXPECT_THROW(controller_file("fanuc"), std::invalid_argument);
  fs::remove_all(scratch());
}

}  // namespace
}  // namespace vc::fit_tables
