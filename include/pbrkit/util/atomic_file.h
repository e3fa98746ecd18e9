#pragma once
// Atomic output: every file pbrkit writes is first written to a temporary file in the
// same directory and then renamed over the destination, so a crash, a full disk or a
// Ctrl-C never leaves a half-written image behind.
#include <filesystem>
#include <functional>
#include <string>

namespace pbrkit {

/// Calls write(temp_path) to produce the file's content at a temporary path next to
/// `path`, then renames it to `path`. If write throws, the temporary file is removed and
/// the exception propagates; `path` is untouched. Throws pbrkit::Error if the directory is
/// not writable or the rename fails.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(const std::filesystem::path&)>& write);

/// Convenience: atomically writes `bytes` to `path`.
void write_bytes_atomically(const std::filesystem::path& path, const std::string& bytes);

}  // namespace pbrkit
