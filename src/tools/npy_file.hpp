#pragma once
// A NumPy .npy file (format version 1.0) of float32 rows written as they come: the shape
// is fixed up front, so nothing is held in memory.
#include <cstdint>
#include <fstream>
#include <string>

namespace bearing_sim::tool {

class NpyFloatWriter {
 public:
  // Throws std::runtime_error naming the file if it cannot be created.
  NpyFloatWriter(const std::string& path, std::uint64_t rows, int columns);
  void write_row(const float* values);
  // Throws std::runtime_error unless exactly `rows` rows were written, or on an I/O error.
  void close();
  std::uint64_t rows_written() const { return written_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::uint64_t rows_ = 0, written_ = 0;
  int columns_ = 0;
};

// The header of a little-endian float32 C-order array of that shape (magic, version,
// length, dict padded so that the data starts at a multiple of 64 bytes).
std::string npy_header(std::uint64_t rows, int columns);

}  // namespace bearing_sim::tool
