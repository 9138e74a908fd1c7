// Base64 (RFC 4648 sec. 4, with padding): the report's pictures embedded as data: URIs, so that
// the page is one file that needs nothing else (tests/report/sha256_test.cpp has RFC 4648's
// examples).
#pragma once

#include <string>

namespace vc::report {

std::string base64(const std::string& bytes);

}  // namespace vc::report
