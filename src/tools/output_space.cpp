#include "output_space.hpp"

#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <system_error>

#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

namespace fs = std::filesystem;

// The directory a file at `path` goes into, or its nearest ancestor that exists (generate
// creates --out).
fs::path existing_directory(const std::string& path) {
  fs::path dir = fs::absolute(fs::path(path)).parent_path();
  std::error_code ec;
  while (!fs::is_directory(dir, ec) && dir.has_parent_path() && dir != dir.parent_path()) dir = dir.parent_path();
  return dir;
}

}  // namespace

std::string byte_size_text(double bytes) {
  static const char* const units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (bytes >= 999.5 && u < 6) {
    bytes /= 1000.0;
    ++u;
  }
  char text[64];
  if (u == 0) std::snprintf(text, sizeof text, "%.0f bytes", bytes);
  else std::snprintf(text, sizeof text, "%.3g %s", bytes, units[u]);
  return text;
}

double allocated_bytes(const std::vector<std::string>& paths) {
  double bytes = 0.0;
  for (const std::string& p : paths) {
    struct stat st {};
    // st_blocks counts 512-byte units whatever the filesystem's block size (POSIX).
    if (::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode)) bytes += 512.0 * static_cast<double>(st.st_blocks);
  }
  return bytes;
}

void check_output_space(const std::string& what, double needed_bytes, const std::string& directory,
                        double available_bytes) {
  if (needed_bytes * (1.0 + kOutputSpaceMargin) + kOutputSpaceReserveBytes <= available_bytes) return;
  throw InputError(what + ": " + byte_size_text(needed_bytes) + " needed (estimate), " +
                   byte_size_text(available_bytes) + " free on " + directory + " (the output and " +
                   std::to_string(static_cast<int>(kOutputSpaceMargin * 100.0 + 0.5)) + " % more must leave " +
                   byte_size_text(kOutputSpaceReserveBytes) +
                   " free); write it to a disk with more space, or make the run shorter");
}

void check_output_space(const std::vector<PlannedOutput>& outputs) {
  struct Filesystem {
    std::string what, directory;
    double needed = 0.0, available = 0.0;
  };
  std::map<dev_t, Filesystem> filesystems;
  for (const PlannedOutput& o : outputs) {
    const fs::path dir = existing_directory(o.path);
    struct stat st {};
    std::error_code ec;
    const fs::space_info space = fs::space(dir, ec);
    if (ec || ::stat(dir.c_str(), &st) != 0) continue;  // unknown: the writer reports what goes wrong
    Filesystem& f = filesystems[st.st_dev];
    if (f.directory.empty()) {
      f.directory = dir.string();
      f.available = static_cast<double>(space.available);
    }
    if (f.what.find(o.what) == std::string::npos) f.what += (f.what.empty() ? "" : ", ") + o.what;
    f.needed += o.bytes;
    // The files the output replaces free their space.
    f.available += allocated_bytes(o.replaces.empty() ? std::vector<std::string>{o.path} : o.replaces);
  }
  for (const auto& entry : filesystems) {
    const Filesystem& f = entry.second;
    check_output_space(f.what, f.needed, f.directory, f.available);
  }
}

}  // namespace bearing_sim::tool
