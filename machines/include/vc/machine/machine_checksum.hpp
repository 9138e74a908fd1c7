// The checksum of a machine file as volkins shows it (volkins.checksum) and `volcomp check
// --ini` prints it: CRC-32 (IEEE 802.3, zlib's crc32, Boost.CRC's crc_32_type) of the machine
// file's bytes followed by the bytes of each table file it loads, in the order the machine file
// names them (Model::tables), a table file named twice counted once. Not for the servo thread.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "vc/machine/model.hpp"

namespace vc::machine {

// CRC-32 of `bytes` ("123456789" -> 0xCBF43926).
std::uint32_t crc32_of(std::string_view bytes);

// The files the checksum covers, in its order: the machine file, then its distinct table files.
std::vector<std::string> checksummed_files(const Model& model);

// CRC-32 of those files' bytes one after the other, read from disk now; throws
// std::runtime_error naming a file that cannot be read.
std::uint32_t machine_checksum(const Model& model);

}  // namespace vc::machine
