// The patch init writes is a unified diff the real `patch -p1` applies: every edit (line
// replaced, deleted, inserted), CRLF files, a last line without a newline, hunks merged when
// their context overlaps; applied, the file is what FileEdits::result() says, every other
// byte unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>

#include "init_test_files.hpp"
#include "vc/init/unified_diff.hpp"

namespace vc::init {
namespace {

namespace fs = std::filesystem;

std::string numbered_lines(int count, const std::string& end = "\n") {
  std::string text;
  for (int i = 1; i <= count; ++i) text += "line " + std::to_string(i) + end;
  return text;
}

std::string joined(const std::vector<TextLine>& lines) {
  std::string text;
  for (const TextLine& l : lines) text += l.text + l.end;
  return text;
}

// Writes `original`, makes the edits, applies the diff with patch and returns the patched file
// (which must be what result() says).
std::string patched(const std::string& name, const std::string& original, const std::function<void(FileEdits&)>& edit,
                    std::string* diff_out = nullptr) {
  const fs::path dir = test::scratch_folder("diff_" + name);
  test::write_file(dir / "f.txt", original);
  const TextFile file = read_text_file((dir / "f.txt").string(), "test file");
  EXPECT_EQ(joined(file.lines), original) << "read back byte for byte";
  FileEdits edits(file);
  edit(edits);
  const std::string diff = edits.unified_diff("f.txt");
  if (diff_out) *diff_out = diff;
  test::write_file(dir / "change.diff", diff);
  EXPECT_EQ(test::apply_patch(dir, dir / "change.diff"), 0) << diff;
  const std::string result = test::file_text(dir / "f.txt");
  EXPECT_EQ(result, joined(edits.result())) << diff;
  return result;
}

TEST(UnifiedDiff, ReplacesDeletesAndInsertsWithThreeLinesOfContext) {
  std::string diff;
  const std::string result = patched(
      "basic", numbered_lines(30),
      [](FileEdits& e) {
        e.replace(2, "two");
        e.remove(4);
        e.insert_after(20, {"after 20", "and more"});
        e.remove(30);
      },
      &diff);
  std::string expected = numbered_lines(30);
  expected.replace(expected.find("line 2\n"), 7, "two\n");
  expected.erase(expected.find("line 4\n"), 7);
  expected.insert(expected.find("line 21\n"), "after 20\nand more\n");
  expected.erase(expected.find("line 30\n"));
  EXPECT_EQ(result, expected);
  EXPECT_EQ(diff.substr(0, 27), "--- a/f.txt\n+++ b/f.txt\n@@ ");
  EXPECT_NE(diff.find("@@ -1,7 +1,6 @@\n line 1\n-line 2\n+two\n line 3\n-line 4\n line 5\n"), std::string::npos)
      << "replacement and deletion in one hunk:\n"
      << diff;
  EXPECT_NE(diff.find("@@ -18,6 +17,8 @@\n"), std::string::npos) << diff;
  EXPECT_NE(diff.find("@@ -27,4 +28,3 @@\n"), std::string::npos) << diff;
}

TEST(UnifiedDiff, MergesHunksWhoseContextOverlaps) {
  std::string diff;
  patched(
      "merged", numbered_lines(20),
      [](FileEdits& e) {
        e.replace(5, "five");
        e.replace(11, "eleven");  // 5 lines between: one hunk
      },
      &diff);
  EXPECT_EQ(std::count(diff.begin(), diff.end(), '@'), 4) << diff;
  patched(
      "apart", numbered_lines(20),
      [](FileEdits& e) {
        e.replace(5, "five");
        e.replace(12, "twelve");  // 6 lines between: still one (the contexts touch)
      },
      &diff);
  EXPECT_EQ(std::count(diff.begin(), diff.end(), '@'), 4) << diff;
  patched(
      "far", numbered_lines(20),
      [](FileEdits& e) {
        e.replace(5, "five");
        e.replace(13, "thirteen");
      },
      &diff);
  EXPECT_EQ(std::count(diff.begin(), diff.end(), '@'), 8) << diff;
}

TEST(UnifiedDiff, KeepsCrlfAndTrailingBlanks) {
  const std::string original = "a  \r\nb\r\nc\t\r\nd\r\n";
  const std::string result = patched("crlf", original, [](FileEdits& e) {
    e.replace(2, "B");
    e.insert_after(4, {"e"});
  });
  EXPECT_EQ(result, "a  \r\nB\r\nc\t\r\nd\r\ne\r\n");
}

TEST(UnifiedDiff, HandlesALastLineWithoutNewline) {
  EXPECT_EQ(patched("eof_insert", "a\nb", [](FileEdits& e) { e.insert_after(2, {"c"}); }), "a\nb\nc\n");
  EXPECT_EQ(patched("eof_replace", "a\nb\nc\nd\ne", [](FileEdits& e) { e.replace(5, "E"); }), "a\nb\nc\nd\nE");
  EXPECT_EQ(patched("eof_kept", "a\nb\nc\nd\ne", [](FileEdits& e) { e.replace(3, "C"); }), "a\nb\nC\nd\ne");
  EXPECT_EQ(patched("top", "a\nb\n", [](FileEdits& e) { e.insert_after(0, {"first"}); }), "first\na\nb\n");
}

TEST(UnifiedDiff, NoEditNoDiff) {
  const TextFile file{"/x", {{"a", "\n"}}};
  FileEdits edits(file);
  EXPECT_TRUE(edits.empty());
  EXPECT_EQ(edits.unified_diff("x"), "");
  edits.replace(1, "a");  // the same text: no change
  EXPECT_EQ(edits.unified_diff("x"), "");
}

}  // namespace
}  // namespace vc::init
