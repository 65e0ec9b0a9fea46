#include "npy_file.hpp"

#include <stdexcept>

namespace bearing_sim::tool {

std::string npy_header(std::uint64_t rows, int columns) {
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " +
                     std::to_string(columns) + "), }";
  const std::size_t preamble = 10;  // magic (6), version (2), header length (2)
  const std::size_t total = (preamble + dict.size() + 1 + 63) / 64 * 64;
  dict.append(total - preamble - dict.size() - 1, ' ');
  dict += '\n';
  std::string header = "\x93NUMPY";
  header += '\x01';
  header += '\x00';
  header += static_cast<char>(dict.size() & 0xff);
  header += static_cast<char>((dict.size() >> 8) & 0xff);
  return header + dict;
}

NpyFloatWriter::NpyFloatWriter(const std::string& path, std::uint64_t rows, int columns)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc), rows_(rows), columns_(columns) {
  if (!out_) throw std::runtime_error("cannot create " + path);
  static_assert(sizeof(float) == 4, "float32");
  const std::string header = npy_header(rows, columns);
  out_.write(header.data(), static_cast<std::streamsize>(header.size()));
}

void NpyFloatWriter::write_row(const float* values) {
  // x86 and ARM are little-endian, as the header says.
  out_.write(reinterpret_cast<const char*>(values), static_cast<std::streamsize>(sizeof(float) * columns_));
  ++written_;
}

void NpyFloatWriter::close() {
  out_.close();
  if (!out_) throw std::runtime_error("error writing " + path_);
  if (written_ != rows_)
    throw std::runtime_error(path_ + ": wrote " + std::to_string(written_) + " rows, the header says " +
                             std::to_string(rows_));
}

}  // namespace bearing_sim::tool
