#include "pbrkit/util/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>

#include "pbrkit/util/error.h"

namespace pbrkit {

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned> counter{0};
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    fail("{}: output directory {} does not exist", path.string(), dir.string());
  // Keep the real extension last: image writers pick the format from it.
  const fs::path temp = dir / fmt::format(".{}.{}.{}.tmp{}", path.stem().string(), ::getpid(),
                                          counter++, path.extension().string());
  try {
    write(temp);
  } catch (...) {
    fs::remove(temp, ec);
    throw;
  }
  fs::rename(temp, path, ec);
  if (ec) {
    fs::remove(temp, ec);
    fail("{}: cannot move the finished file into place: {}", path.string(), ec.message());
  }
}

void write_bytes_atomically(const std::filesystem::path& path, const std::string& bytes) {
  write_file_atomically(path, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    if (!out) fail("{}: cannot open for writing", path.string());
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) fail("{}: write failed (disk full?)", path.string());
  });
}

}  // namespace pbrkit
