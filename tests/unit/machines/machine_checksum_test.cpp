// volkins.checksum's definition (machine_checksum.hpp): CRC-32 of the machine file's bytes
// then its table files' in the order the machine file names them.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "test_support.hpp"
#include "vc/machine/load_machine.hpp"
#include "vc/machine/machine_checksum.hpp"

namespace vc::machine {
namespace {

// The CRC-32 check value of the IEEE 802.3 / zlib polynomial.
TEST(MachineChecksum, Crc32OfTheCheckStringIsTheKnownValue) {
  EXPECT_EQ(crc32_of("123456789"), 0xCBF43926u);
  EXPECT_EQ(crc32_of(""), 0u);
}

// mill3 names y.csv (workpiece chain first in its file), x.csv, z.csv, z_by_y.csv: the checksum
// is python's zlib.crc32 of those bytes one after the other.
TEST(MachineChecksum, IsZlibsCrc32OfTheFileThenItsTablesInTheFilesOrder) {
  const Model model = load_machine(test::machine_path("mill3"));
  const std::vector<std::string> files = checksummed_files(model);
  ASSERT_EQ(files.size(), 5u);
  const char* expected_order[] = {"mill3.toml", "y.csv", "x.csv", "z.csv", "z_by_y.csv"};
  for (std::size_t k = 0; k < files.size(); ++k)
    EXPECT_EQ(std::filesystem::path(files[k]).filename(), expected_order[k]) << k;
  std::string command = "python3 -c \"import sys, zlib; print(zlib.crc32(b''.join(open(f, 'rb').read() for f in sys.argv[1:])))\"";
  for (const std::string& f : files) command += " '" + f + "'";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  unsigned long python = 0;
  ASSERT_EQ(std::fscanf(pipe, "%lu", &python), 1);
  ASSERT_EQ(pclose(pipe), 0);
  EXPECT_EQ(machine_checksum(model), python);
  // And a file's change changes it.
  std::ifstream in(files[0], std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  EXPECT_NE(crc32_of(bytes.str() + " "), crc32_of(bytes.str()));
}

}  // namespace
}  // namespace vc::machine
