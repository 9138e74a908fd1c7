// SHA-256 (FIPS 180-4) of a file or a byte string, as lower-case hex: the report's checksums of
// the machine file and its tables, so that a reader can tell which files a report was made
// from (`sha256sum FILE` prints the same). Written here because .ci/setup installs no crypto
// library (libssl-dev is not among its packages); tested against FIPS 180-4's examples and
// against sha256sum (tests/report/sha256_test.cpp).
#pragma once

#include <string>

namespace vc::report {

std::string sha256_hex(const std::string& bytes);

// Throws std::runtime_error naming the file when it cannot be read.
std::string sha256_file_hex(const std::string& path);

}  // namespace vc::report
