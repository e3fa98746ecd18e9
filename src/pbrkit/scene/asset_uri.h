#pragma once
// Resolving the URIs inside a glTF file safely: files come from the internet, so a URI
// may only name a file inside the asset's own folder (no "..", no absolute path, no
// network scheme), and data: URIs must be well-formed base64.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace pbrkit {

/// Percent-decodes a relative URI reference and returns the path it names below
/// `base_dir`, or throws pbrkit::Error "<what>: <reason>" when it is absolute, has a
/// scheme (http:, file:, ...), climbs out with "..", or contains a NUL byte.
std::filesystem::path resolve_relative_uri(const std::filesystem::path& base_dir,
                                           const std::string& uri, const std::string& what);

/// Whether `uri` is a data: URI.
bool is_data_uri(const std::string& uri);

/// Decodes a "data:[<mime>];base64,<payload>" URI; throws pbrkit::Error "<what>: <reason>"
/// when it is malformed or its decoded size exceeds `max_bytes`.
std::vector<unsigned char> decode_data_uri(const std::string& uri, std::size_t max_bytes,
                                           const std::string& what);

/// True when `path` (after resolving symlinks) lies inside `dir`.
bool path_is_inside(const std::filesystem::path& dir, const std::filesystem::path& path);

}  // namespace pbrkit
