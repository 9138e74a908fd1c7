// The report's own small parts, against published vectors and the real tools: SHA-256 against
// FIPS 180-2's examples (appendix B) and against coreutils' sha256sum at the padding's edge
// lengths (55, 56, 63, 64, 65 bytes: one or two final blocks); base64 against RFC 4648 sec. 10;
// HTML escaping.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "test_support.hpp"
#include "vc/report/base64.hpp"
#include "vc/report/html.hpp"
#include "vc/report/sha256.hpp"

namespace vc {
namespace {

TEST(ReportSha256, FipsExamples) {
  EXPECT_EQ(report::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(report::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(report::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(report::sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(ReportSha256, AgreesWithSha256sumAtThePaddingEdges) {
  namespace fs = std::filesystem;
  const fs::path file = fs::temp_directory_path() / ("vc_sha_" + std::to_string(::getpid()) + ".bin");
  for (const std::size_t length : {1u, 55u, 56u, 63u, 64u, 65u, 119u, 120u, 1000u}) {
    std::string bytes;
    for (std::size_t k = 0; k < length; ++k) bytes += static_cast<char>((k * 37 + 11) & 0xff);  // every byte value
    { std::ofstream(file, std::ios::binary) << bytes; }
    const test::CommandResult sum = test::run_command("sha256sum '" + file.string() + "'");
    ASSERT_EQ(sum.exit_code, 0);
    EXPECT_EQ(report::sha256_file_hex(file.string()), sum.out.substr(0, 64)) << length << " bytes";
    EXPECT_EQ(report::sha256_hex(bytes), sum.out.substr(0, 64)) << length << " bytes";
  }
  fs::remove(file);
  EXPECT_THROW(report::sha256_file_hex(file.string()), std::runtime_error);
}

TEST(ReportBase64, Rfc4648Examples) {
  EXPECT_EQ(report::base64(""), "");
  EXPECT_EQ(report::base64("f"), "Zg==");
  EXPECT_EQ(report::base64("fo"), "Zm8=");
  EXPECT_EQ(report::base64("foo"), "Zm9v");
  EXPECT_EQ(report::base64("foob"), "Zm9vYg==");
  EXPECT_EQ(report::base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(report::base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(report::base64(std::string("\x89PNG\r\n\x1a\n", 8)),
            "iVBORw0KGgo=");  // what every embedded picture starts with
  EXPECT_EQ(report::base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(ReportHtml, TextIsEscaped) {
  EXPECT_EQ(report::escaped("<a href=\"x\">R&D 'q'</a>"), "&lt;a href=&quot;x&quot;&gt;R&amp;D &#39;q&#39;&lt;/a&gt;");
  const std::string table = report::html_table({"a<b"}, {{"<script>"}});
  EXPECT_EQ(table.find("<script>"), std::string::npos);
  EXPECT_NE(table.find("&lt;script&gt;"), std::string::npos);
}

}  // namespace
}  // namespace vc
