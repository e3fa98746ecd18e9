#include "pbrkit/scene/asset_uri.h"

#include <cctype>

#include "pbrkit/util/error.h"

namespace pbrkit {

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// RFC 3986 section 3.1: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":".
bool has_scheme(const std::string& uri) {
  const auto colon = uri.find(':');
  if (colon == std::string::npos || colon == 0) return false;
  if (!std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  for (std::size_t i = 0; i < colon; ++i) {
    const auto c = static_cast<unsigned char>(uri[i]);
    if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return false;
  }
  return true;
}

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

}  // namespace

bool is_data_uri(const std::string& uri) {
  return uri.rfind("data:", 0) == 0;
}

std::filesystem::path resolve_relative_uri(const std::filesystem::path& base_dir,
                                           const std::string& uri, const std::string& what) {
  if (uri.empty()) fail("{}: empty URI", what);
  if (has_scheme(uri))
    fail("{}: URI '{}' has a scheme; only relative file references and data: URIs are allowed",
         what, uri);
  std::string decoded;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%') {
      const int hi = i + 2 < uri.size() ? hex_value(uri[i + 1]) : -1;
      const int lo = i + 2 < uri.size() ? hex_value(uri[i + 2]) : -1;
      if (hi < 0 || lo < 0) fail("{}: URI '{}' has a malformed %-escape", what, uri);
      decoded.push_back(char(hi * 16 + lo));
      i += 2;
    } else {
      decoded.push_back(uri[i]);
    }
  }
  if (decoded.find('\0') != std::string::npos) fail("{}: URI '{}' contains a NUL byte", what, uri);
  if (decoded.front() == '/' || decoded.front() == '\\' ||
      (decoded.size() > 1 && decoded[1] == ':'))
    fail("{}: URI '{}' is an absolute path; it must name a file inside the asset's folder", what,
         uri);
  const std::filesystem::path rel(decoded);
  for (const auto& part : rel) {
    const std::string s = part.string();
    if (s == ".." || s.find('\\') != std::string::npos)
      fail("{}: URI '{}' points outside the asset's folder", what, uri);
  }
  return base_dir / rel;
}

std::vector<unsigned char> decode_data_uri(const std::string& uri, std::size_t max_bytes,
                                           const std::string& what) {
  const auto comma = uri.find(',');
  if (!is_data_uri(uri) || comma == std::string::npos)
    fail("{}: malformed data URI (expected 'data:<mime>;base64,<data>')", what);
  const std::string header = uri.substr(5, comma - 5);
  if (header.size() < 7 || header.compare(header.size() - 7, 7, ";base64") != 0)
    fail("{}: data URI is not base64-encoded (';base64' missing)", what);
  const std::size_t payload = uri.size() - comma - 1;
  if (payload / 4 * 3 > max_bytes)
    fail("{}: data URI decodes to about {} bytes, more than the limit of {}", what, payload / 4 * 3,
         max_bytes);
  std::vector<unsigned char> out;
  out.reserve(payload / 4 * 3);
  unsigned bits = 0;
  int nbits = 0;
  std::size_t padding = 0;
  for (std::size_t i = comma + 1; i < uri.size(); ++i) {
    const char c = uri[i];
    if (c == '=') {
      ++padding;
      continue;
    }
    const int v = base64_value(c);
    if (v < 0 || padding > 0) fail("{}: data URI has invalid base64 at offset {}", what, i);
    bits = (bits << 6) | unsigned(v);
    nbits += 6;
    if (nbits >= 8) {
      nbits -= 8;
      out.push_back(static_cast<unsigned char>((bits >> nbits) & 0xFF));
    }
  }
  if (padding > 2 || nbits >= 6) fail("{}: data URI has truncated base64", what);
  return out;
}

bool path_is_inside(const std::filesystem::path& dir, const std::filesystem::path& path) {
  std::error_code ec;
  const auto d = std::filesystem::weakly_canonical(dir, ec);
  if (ec) return false;
  const auto p = std::filesystem::weakly_canonical(path, ec);
  if (ec) return false;
  auto di = d.begin(), pi = p.begin();
  for (; di != d.end(); ++di, ++pi) {
    if (di->empty()) continue;  // trailing separator
    if (pi == p.end() || *di != *pi) return false;
  }
  return true;
}

}  // namespace pbrkit
