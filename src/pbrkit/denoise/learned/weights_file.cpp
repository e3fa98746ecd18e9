#include "pbrkit/denoise/learned/weights_file.h"

#include <zlib.h>

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "pbrkit/util/error.h"

namespace pbrkit::learned {

namespace {

constexpr char kMagic[8] = {'P', 'B', 'R', 'K', 'I', 'T', 'N', 'N'};
constexpr std::uint32_t kFormatVersion = 1;
constexpr std::size_t kPreamble = 16;  // magic, version, header length
constexpr std::size_t kDataAlignment = 64;

static_assert(std::endian::native == std::endian::little,
              "the weights file is little-endian and read in place");

std::uint32_t read_u32(const std::vector<char>& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

std::string shape_string(const std::vector<std::int64_t>& shape) {
  std::string s = "[";
  for (std::size_t i = 0; i < shape.size(); ++i) s += (i ? ", " : "") + std::to_string(shape[i]);
  return s + "]";
}

// The header's field `key`, which must be present and of JSON type `type` ("string",
// "integer", "array", ...): the contract's "a header that ... lacks a field".
const nlohmann::json& field(const std::filesystem::path& path, const nlohmann::json& header,
                            const char* key, nlohmann::json::value_t type, const char* type_name) {
  const auto it = header.find(key);
  if (it == header.end()) fail("{}: the header lacks the field '{}'", path.string(), key);
  const bool integer_ok =
      type == nlohmann::json::value_t::number_unsigned && it->is_number_integer() && *it >= 0;
  if (it->type() != type && !integer_ok)
    fail("{}: the header's '{}' is not {}", path.string(), key, type_name);
  return *it;
}

constexpr auto kString = nlohmann::json::value_t::string;
constexpr auto kCount = nlohmann::json::value_t::number_unsigned;  // a non-negative integer

}  // namespace

NetworkWeights read_weights_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the denoiser's weights: {}", name, std::strerror(errno));
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
  if (in.bad()) fail("{}: cannot read the denoiser's weights", name);

  if (bytes.size() < kPreamble || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    fail("{}: not a pbrkit network file (no PBRKITNN magic)", name);
  if (const std::uint32_t version = read_u32(bytes, 8); version != kFormatVersion)
    fail("{}: weights format version {}, this pbrkit reads version {}", name, version,
         kFormatVersion);
  const std::size_t header_bytes = read_u32(bytes, 12);
  if (bytes.size() - kPreamble < header_bytes)
    fail("{}: truncated: {} bytes, shorter than its {}-byte header", name, bytes.size(),
         kPreamble + header_bytes);

  nlohmann::json header;
  try {
    header = nlohmann::json::parse(bytes.begin() + kPreamble,
                                   bytes.begin() + std::ptrdiff_t(kPreamble + header_bytes));
  } catch (const nlohmann::json::exception& e) {
    fail("{}: the header is not JSON ({})", name, e.what());
  }
  if (!header.is_object()) fail("{}: the header is not a JSON object", name);

  NetworkWeights weights;
  LearnedWeightsInfo& info = weights.info;
  info.file = path;
  info.network = field(path, header, "network", kString, "a string").get<std::string>();
  info.input_transform =
      field(path, header, "input_transform", kString, "a string").get<std::string>();
  const auto& tensors = field(path, header, "tensors", nlohmann::json::value_t::array, "a list");
  const auto data_bytes = field(path, header, "data_bytes", kCount, "a count").get<std::uint64_t>();
  const auto crc = field(path, header, "crc32", kCount, "a count").get<std::uint64_t>();
  // The record (not used by the inference, but the contract lists them as fields).
  info.commit = field(path, header, "commit", kString, "a string").get<std::string>();
  const auto& dataset = header.find("dataset");
  if (dataset == header.end()) fail("{}: the header lacks the field 'dataset'", name);
  info.dataset = dataset->is_string() ? dataset->get<std::string>() : dataset->dump();
  info.steps = field(path, header, "steps", kCount, "a count").get<std::int64_t>();
  info.created = field(path, header, "created", kString, "a string").get<std::string>();
  if (crc > 0xffffffffu) fail("{}: the header's crc32 {} is not a 32-bit value", name, crc);
  info.crc32 = std::uint32_t(crc);

  weights.spec = find_network(info.network);
  if (!weights.spec)
    fail("{}: network '{}', this pbrkit runs '{}' or '{}'", name, info.network, kNetworks[0].name,
         kNetworks[1].name);
  const auto& layers = weights.spec->layers;
  if (info.input_transform != kInputTransform)
    fail("{}: input transform '{}', this pbrkit computes '{}'", name, info.input_transform,
         kInputTransform);

  // The data starts at the first multiple of 64 after the header.
  const std::size_t start =
      (kPreamble + header_bytes + kDataAlignment - 1) / kDataAlignment * kDataAlignment;
  if (bytes.size() < start || bytes.size() - start < data_bytes)
    fail("{}: truncated: {} bytes, its header promises {} bytes of tensors from byte {}", name,
         bytes.size(), data_bytes, start);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data() + start);
  const std::uint32_t actual = std::uint32_t(crc32_z(0L, data, std::size_t(data_bytes)));
  if (actual != info.crc32)
    fail("{}: corrupt: the tensors' CRC-32 is {:08x}, the header says {:08x}", name, actual,
         info.crc32);

  // Index the header's tensors by name.
  std::array<const nlohmann::json*, 2 * kLayerCount> found{};
  for (const auto& t : tensors) {
    if (!t.is_object() || !t.contains("name") || !t["name"].is_string())
      fail("{}: a tensor of the header has no name", name);
    const std::string tensor = t["name"].get<std::string>();
    for (int l = 0; l < kLayerCount; ++l)
      for (int part = 0; part < 2; ++part)
        if (tensor == std::string(layers[l].name) + (part ? ".bias" : ".weight")) {
          if (found[2 * l + part]) fail("{}: the tensor {} is listed twice", name, tensor);
          found[2 * l + part] = &t;
        }
  }

  info.parameters = 0;
  for (int l = 0; l < kLayerCount; ++l) {
    const LayerSpec& spec = layers[l];
    for (int part = 0; part < 2; ++part) {
      const std::string tensor = std::string(spec.name) + (part ? ".bias" : ".weight");
      const nlohmann::json* t = found[2 * l + part];
      if (!t) fail("{}: the tensor {} is missing", name, tensor);
      const std::vector<std::int64_t> expected =
          part ? std::vector<std::int64_t>{spec.out}
               : std::vector<std::int64_t>{spec.out, spec.in, 3, 3};
      std::vector<std::int64_t> shape;
      if (t->contains("shape") && (*t)["shape"].is_array())
        for (const auto& d : (*t)["shape"])
          shape.push_back(d.is_number_integer() ? d.get<std::int64_t>() : -1);
      if (shape != expected)
        fail("{}: the tensor {} has shape {}, {} needs {}", name, tensor,
             t->contains("shape") ? (*t)["shape"].dump() : "(none)", info.network,
             shape_string(expected));
      if (!t->contains("offset") || !(*t)["offset"].is_number_integer() || (*t)["offset"] < 0)
        fail("{}: the tensor {} has no valid offset", name, tensor);
      const auto offset = (*t)["offset"].get<std::uint64_t>();
      std::size_t count = 1;
      for (std::int64_t d : expected) count *= std::size_t(d);
      if (offset > data_bytes || data_bytes - offset < count * sizeof(float))
        fail("{}: the tensor {} ({} bytes at {}) lies outside the {} bytes of data", name, tensor,
             count * sizeof(float), offset, data_bytes);
      std::vector<float>& values = part ? weights.layers[l].bias : weights.layers[l].weight;
      values.resize(count);
      std::memcpy(values.data(), data + offset, count * sizeof(float));
      // Not in the contract's list, but a NaN weight would make every output NaN.
      for (float v : values)
        if (!std::isfinite(v)) fail("{}: the tensor {} holds a non-finite value", name, tensor);
      info.parameters += std::int64_t(count);
    }
  }
  return weights;
}

}  // namespace pbrkit::learned
