#include "vc/machine/machine_checksum.hpp"

#include <algorithm>
#include <boost/crc.hpp>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace vc::machine {

std::uint32_t crc32_of(std::string_view bytes) {
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

std::vector<std::string> checksummed_files(const Model& model) {
  // Model::tables is in chain order (tool chain first); the checksum takes the file's order.
  std::vector<const BoundTable*> in_file_order;
  for (const BoundTable& t : model.tables) in_file_order.push_back(&t);
  std::stable_sort(in_file_order.begin(), in_file_order.end(),
                   [](const BoundTable* a, const BoundTable* b) { return a->file_line < b->file_line; });
  std::vector<std::string> files{model.path};
  for (const BoundTable* t : in_file_order)
    if (std::find(files.begin() + 1, files.end(), t->table.path()) == files.end()) files.push_back(t->table.path());
  return files;
}

std::uint32_t machine_checksum(const Model& model) {
  boost::crc_32_type crc;  // one CRC over the concatenation: each file continues the last one's
  for (const std::string& path : checksummed_files(model)) {
    std::ifstream in(path, std::ios::binary);
    if (!in.is_open()) throw std::runtime_error("cannot read " + path + " (for the machine file's checksum)");
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw std::runtime_error("cannot read " + path + " (for the machine file's checksum)");
    crc.process_bytes(bytes.data(), bytes.size());
  }
  return crc.checksum();
}

}  // namespace vc::machine
