// Fuzz entry: bytes as the stored image(s), through drivers::FileParamStorage
// and the two-generation loader. Invariants: a set is loaded whole or not at
// all (on a fault with nothing loaded the defaults are untouched, bit-exact);
// what is loaded passes validate() and is exactly what decode_image() makes
// of the generation it came from; the loaded set saves and loads back to
// itself; a fallback or nothing loaded is reported as a fault.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <span>

#include "drivers/storage/file_param_storage.hpp"
#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_table.hpp"
#include "tests/fuzz/fuzz_entries.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace tnv::fuzz {

namespace can = fw::can;
namespace fs = std::filesystem;

namespace {

const can::NodeSettings& defaults() {
  static const can::NodeSettings d = can::default_node_settings();
  return d;
}

// A per-process directory, in memory when /dev/shm exists, removed at exit.
struct WorkDir {
  WorkDir() {
    const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    path = (base / ("tnv_fuzz_image_" + std::to_string(::getpid()))).string();
    fs::create_directories(path);
  }
  ~WorkDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string path;
};
const std::string& work_dir() {
  static const WorkDir dir;
  return dir.path;
}

void put(const std::string& path, std::span<const std::uint8_t> bytes, bool present) {
  std::error_code ec;
  fs::remove(path, ec);
  if (!present) return;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// The bytes with their last four replaced by the CRC of the rest (when long enough).
std::vector<std::uint8_t> resealed(std::span<const std::uint8_t> bytes) {
  std::vector<std::uint8_t> out(bytes.begin(), bytes.end());
  if (out.size() < can::kParamImageCrcBytes) return out;
  const std::size_t body = out.size() - can::kParamImageCrcBytes;
  const std::uint32_t crc = can::crc32(std::span<const std::uint8_t>(out.data(), body));
  for (std::size_t i = 0; i < 4; ++i) out[body + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  return out;
}

}  // namespace

std::string param_image(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return {};
  const bool two = (data[0] & 1u) != 0;
  const bool reseal = (data[0] & 2u) != 0;
  const std::span<const std::uint8_t> rest(data + 1, size - 1);
  const std::size_t half = two ? rest.size() / 2 : rest.size();
  std::vector<std::uint8_t> current(rest.begin(), rest.begin() + static_cast<std::ptrdiff_t>(half));
  std::vector<std::uint8_t> previous(rest.begin() + static_cast<std::ptrdiff_t>(half), rest.end());
  if (reseal) {
    current = resealed(current);
    previous = resealed(previous);
  }
  const std::string path = work_dir() + "/node.params";
  put(path, current, true);
  put(path + ".prev", previous, two);

  drivers::FileParamStorage storage(path);
  can::NodeSettings loaded = defaults();
  const can::LoadReport report = can::load_settings_with_fallback(storage, &storage.previous(), loaded);

  // What decode_image() alone makes of each generation, from the defaults.
  can::NodeSettings from_current = defaults();
  can::NodeSettings from_previous = defaults();
  const can::ErrorCode current_result = can::decode_image(current, from_current);
  const can::ErrorCode previous_result = two ? can::decode_image(previous, from_previous) : can::ErrorCode::not_ready;

  const std::vector<std::uint8_t> got = image_of(loaded);
  switch (report.source) {
    case can::LoadSource::current:
      if (current_result != can::ErrorCode::ok || got != image_of(from_current))
        return "loaded from the current image, but that is not what decode_image() makes of it";
      if (report.fault()) return "a clean load reported as a fault";
      break;
    case can::LoadSource::previous:
      if (current_result == can::ErrorCode::ok) return "fell back although the current image decodes";
      if (previous_result != can::ErrorCode::ok || got != image_of(from_previous))
        return "loaded from the previous image, but that is not what decode_image() makes of it";
      if (!report.fault()) return "a fallback not reported as a fault";
      break;
    case can::LoadSource::rolled_back: {
      std::uint32_t current_generation = 0;
      std::uint32_t previous_generation = 0;
      if (current_result != can::ErrorCode::ok || previous_result != can::ErrorCode::ok)
        return "a rollback reported although one generation does not decode";
      if (!can::image_generation(current, current_generation) || !can::image_generation(previous, previous_generation) ||
          previous_generation <= current_generation)
        return "a rollback reported although the current image is not the older one";
      if (got != image_of(from_previous)) return "rolled back, but not to what decode_image() makes of the previous image";
      if (!report.fault()) return "a rollback not reported as a fault";
      break;
    }
    case can::LoadSource::neither:
    case can::LoadSource::nothing_stored:
      if (current_result == can::ErrorCode::ok || previous_result == can::ErrorCode::ok)
        return "nothing loaded although a generation decodes";
      if (got != image_of(defaults())) return "nothing loaded, but the defaults changed (half-applied)";
      if (report.source == can::LoadSource::neither && (!report.fault() || report.result() == can::ErrorCode::ok))
        return "damaged images not reported";
      break;
  }
  if (!can::validate(loaded).ok) return "the loaded set fails validate()";
  // Round trip: what was loaded encodes and decodes to itself.
  can::NodeSettings again = defaults();
  if (can::decode_image(got, again) != can::ErrorCode::ok || image_of(again) != got)
    return "the loaded set does not survive a save and a load";
  return {};
}

}  // namespace tnv::fuzz
