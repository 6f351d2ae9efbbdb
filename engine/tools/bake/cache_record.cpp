#include "engine/tools/bake/cache_record.h"

#include <algorithm>
#include <regex>

#include <nlohmann/json.hpp>

#include "engine/tools/bake/build_identity.h"
#include "generators/asset/asset_io.h"
#include "generators/core/content_hash.h"
#include "generators/core/input_error.h"
#include "generators/core/text_file.h"

namespace forest {

namespace fs = std::filesystem;

fs::path record_path(const fs::path& entry) {
  fs::path p = entry;
  p.replace_extension(".json");
  return p;
}

std::string record_json(const CacheRecord& r) {
  nlohmann::ordered_json j;
  j["format"] = "forest species cache record 1";
  j["key"] = r.key;
  j["preset"] = r.preset;
  j["seed"] = r.seed ? nlohmann::ordered_json(*r.seed) : nlohmann::ordered_json(nullptr);
  j["bake"] = {{"priority", r.bake.priority}, {"views", r.bake.views}, {"resolution", r.bake.resolution},
               {"impostor", r.bake.impostor}};
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const CacheInputRecord& i : r.inputs) inputs.push_back({{"name", i.name}, {"file", i.file}, {"hash", i.hash}});
  j["inputs"] = std::move(inputs);
  j["build"] = r.build;
  j["device"] = r.device;
  j["driver"] = r.driver;
  j["asset"] = {{"bytes", r.asset_bytes}, {"hash", r.asset_hash}};
  return j.dump(1) + "\n";
}

CacheRecord parse_record(const std::string& text, const std::string& name) {
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  auto is_record = [&] {
    return j.is_object() && j.contains("format") && j["format"].is_string() &&
           j["format"].get<std::string>() == "forest species cache record 1";
  };
  if (j.is_discarded() || !is_record()) throw InputError(name, 0, "", "not a species cache record");
  try {
    CacheRecord r;
    r.key = j.at("key").get<std::string>();
    r.preset = j.at("preset").get<std::string>();
    if (!j.at("seed").is_null()) r.seed = j.at("seed").get<uint64_t>();
    const auto& b = j.at("bake");
    r.bake.priority = b.at("priority").get<std::string>();
    r.bake.views = b.at("views").get<uint32_t>();
    r.bake.resolution = b.at("resolution").get<uint32_t>();
    r.bake.impostor = b.at("impostor").get<bool>();
    for (const auto& i : j.at("inputs"))
      r.inputs.push_back({i.at("name").get<std::string>(), i.at("file").get<std::string>(), i.at("hash").get<std::string>()});
    r.build = j.at("build").get<std::string>();
    r.device = j.at("device").get<std::string>();
    r.driver = j.at("driver").get<std::string>();
    r.asset_bytes = j.at("asset").at("bytes").get<uint64_t>();
    r.asset_hash = j.at("asset").at("hash").get<std::string>();
    return r;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(name, 0, "", std::string("damaged species cache record: ") + e.what());
  }
}

std::vector<fs::path> cache_entries(const fs::path& dir) {
  static const std::regex kEntry(".+-[0-9a-f]{32}\\.glb");
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file(ec) && std::regex_match(e.path().filename().string(), kEntry)) out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

const char* entry_state_name(EntryState s) {
  switch (s) {
    case EntryState::ok: return "ok";
    case EntryState::stale: return "stale";
    case EntryState::corrupt: return "corrupt";
  }
  return "?";
}

EntryCheck check_entry(const fs::path& entry) {
  EntryCheck c;
  auto fail = [&](EntryState s, std::string why) {
    c.state = s;
    c.why = std::move(why);
    return c;
  };
  try {
    c.record = parse_record(read_text_file(record_path(entry), "cache record"), record_path(entry).string());
  } catch (const InputError& e) {
    return fail(EntryState::corrupt, e.what());
  }
  std::string bytes;
  try {
    bytes = read_text_file(entry, "cache entry");
  } catch (const InputError& e) {
    return fail(EntryState::corrupt, e.what());
  }
  if (bytes.size() != c.record->asset_bytes || content_hash(bytes) != c.record->asset_hash)
    return fail(EntryState::corrupt, "the .glb is not the file its record describes (" + std::to_string(bytes.size()) +
                                         " bytes, record " + std::to_string(c.record->asset_bytes) + ")");
  try {
    load_glb(entry);
  } catch (const InputError& e) {
    return fail(EntryState::corrupt, e.what());
  }
  if (c.record->build != bake_build_identity())
    return fail(EntryState::stale, "made by other generator or bake code (build " + c.record->build.substr(0, 8) +
                                       ", this binary " + std::string(bake_build_identity()).substr(0, 8) + ")");
  for (const CacheInputRecord& i : c.record->inputs) {
    std::error_code ec;
    if (!fs::is_regular_file(i.file, ec)) return fail(EntryState::stale, "input " + i.file + " is gone");
    if (content_hash(read_text_file(i.file, "species input")) != i.hash)
      return fail(EntryState::stale, "input " + i.file + " changed");
  }
  return c;
}

}  // namespace forest
