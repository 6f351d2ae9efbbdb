// The record beside every species cache entry (`<entry>.json` next to `<entry>.glb`): what
// the entry was made from (the preset and every file it names, each with its content hash;
// seed; bake settings; the build identity of the code) and what measured it (the device and
// driver that rendered its PR tables and impostor), plus the hash of the .glb itself. It lets
// `forest cache ls` say what an entry is and `forest cache verify` find entries whose inputs
// changed (stale) or whose file is damaged (corrupt). The record holds no clock time, so two
// runs that make the same entry write the same record bytes.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene_file.h"

namespace forest {

struct CacheInputRecord {
  std::string name;   // relative to the preset's folder, as species_inputs() names it
  std::string file;   // where it was read (absolute), for verify
  std::string hash;   // content_hash() of its bytes
};

struct CacheRecord {
  std::string key;     // the entry's key (species_cache_key)
  std::string preset;  // preset file, absolute
  std::optional<uint64_t> seed;
  BakeDesc bake;
  std::vector<CacheInputRecord> inputs;  // the preset first
  std::string build;                     // bake_build_identity() of the writer
  std::string device, driver;            // what measured the tables
  uint64_t asset_bytes = 0;
  std::string asset_hash;                // content_hash() of the .glb
};

// `<entry>.json` for `<entry>.glb`.
std::filesystem::path record_path(const std::filesystem::path& entry);
std::string record_json(const CacheRecord& record);  // deterministic, one key per line
// InputError naming `name` when the text is not a record.
CacheRecord parse_record(const std::string& text, const std::string& name);

// The entries of a cache folder: `<stem>-<32 hex>.glb` files, sorted by name.
std::vector<std::filesystem::path> cache_entries(const std::filesystem::path& dir);

enum class EntryState { ok, stale, corrupt };
struct EntryCheck {
  EntryState state = EntryState::ok;
  std::string why;  // empty when ok
  std::optional<CacheRecord> record;  // when the record could be read
};
// Re-hashes the entry's .glb against its record (corrupt when they differ, when the record
// is missing or unreadable, or when the .glb does not load) and its inputs against the
// files now (stale when one changed, vanished or when the build identity is not this
// binary's).
EntryCheck check_entry(const std::filesystem::path& entry);
const char* entry_state_name(EntryState s);

}  // namespace forest
