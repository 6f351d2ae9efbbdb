// forest cache ls | verify | clear | build: the species cache as a thing a user manages —
// what is in it, whether it is still right, and filling it ahead of time, in parallel on one
// machine (--jobs) or split across a scheduler's tasks (--shard i/n, deploy/).
#include <cstdio>

#include "engine/app/app_common.h"
#include "engine/app/commands.h"
#include "engine/tools/bake/build_identity.h"
#include "engine/tools/bake/cache_record.h"
#include "engine/tools/bake/species_cache.h"
#include "generators/core/input_error.h"
#include "generators/core/text_file.h"

namespace forest::app {

namespace {

namespace fs = std::filesystem;

fs::path cache_dir(const CacheArgs& a) { return a.cache.empty() ? default_cache_dir() : fs::path(a.cache); }

std::string mib(uint64_t bytes) {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
  return s;
}

std::string bake_text(const BakeDesc& b) {
  return b.priority + ", " + std::to_string(b.views) + " views, " + std::to_string(b.resolution) + " px" +
         (b.impostor ? ", impostor" : ", no impostor");
}

int run_ls(const CacheArgs& a) {
  fs::path dir = cache_dir(a);
  std::vector<fs::path> entries = cache_entries(dir);
  uint64_t total = 0;
  for (const fs::path& e : entries) {
    std::error_code ec;
    uint64_t bytes = fs::file_size(e, ec);
    total += bytes;
    std::printf("%s  %s\n", e.filename().c_str(), mib(bytes).c_str());
    CacheRecord r;
    try {
      r = parse_record(read_text_file(record_path(e), "cache record"), record_path(e).string());
    } catch (const InputError& err) {
      std::printf("  no readable record: %s\n", err.what());
      continue;
    }
    std::printf("  preset %s, seed %s; bake %s\n", r.preset.c_str(),
                r.seed ? std::to_string(*r.seed).c_str() : "from the preset", bake_text(r.bake).c_str());
    std::string names;
    for (const CacheInputRecord& i : r.inputs) names += (names.empty() ? "" : ", ") + i.name;
    std::printf("  inputs (%zu): %s\n", r.inputs.size(), names.c_str());
    std::printf("  build %s%s; measured on %s (%s)\n", r.build.substr(0, 12).c_str(),
                r.build == bake_build_identity() ? " (this binary)" : " (not this binary)", r.device.c_str(),
                r.driver.c_str());
  }
  std::printf("%zu entries, %s in %s\n", entries.size(), mib(total).c_str(), dir.c_str());
  return 0;
}

int run_verify(const CacheArgs& a) {
  fs::path dir = cache_dir(a);
  std::vector<fs::path> entries = cache_entries(dir);
  size_t count[3] = {0, 0, 0};
  for (const fs::path& e : entries) {
    EntryCheck c = check_entry(e);
    count[int(c.state)]++;
    if (c.state == EntryState::ok)
      std::printf("ok       %s\n", e.filename().c_str());
    else
      std::printf("%-8s %s: %s\n", entry_state_name(c.state), e.filename().c_str(), c.why.c_str());
  }
  std::printf("%zu entries in %s: %zu ok, %zu stale, %zu corrupt\n", entries.size(), dir.c_str(), count[0], count[1],
              count[2]);
  // Like fsck: 1 when something needs attention, so scripts can act on it.
  return count[1] + count[2] ? 1 : 0;
}

int run_clear(const CacheArgs& a) {
  fs::path dir = cache_dir(a);
  size_t removed = 0;
  uint64_t bytes = 0;
  std::error_code ec;
  for (const fs::path& e : cache_entries(dir)) {
    if (a.stale_only && check_entry(e).state == EntryState::ok) continue;
    bytes += fs::file_size(e, ec);
    fs::remove(e, ec);
    fs::remove(record_path(e), ec);
    removed++;
  }
  // Leftovers of killed writers (temporary files) and records whose .glb is gone.
  size_t leftovers = 0;
  if (fs::is_directory(dir, ec))
    for (const fs::directory_entry& d : fs::directory_iterator(dir, ec)) {
      std::string name = d.path().filename().string();
      bool tmp = name.find(".tmp-") != std::string::npos;
      bool orphan = d.path().extension() == ".json" && !fs::exists(fs::path(d.path()).replace_extension(".glb"), ec);
      if ((tmp && !a.stale_only) || orphan) {
        fs::remove(d.path(), ec);
        leftovers++;
      }
    }
  std::printf("removed %zu %sentries (%s) and %zu leftover files from %s\n", removed, a.stale_only ? "stale or corrupt " : "",
              mib(bytes).c_str(), leftovers, dir.c_str());
  return 0;
}

}  // namespace

int run_cache(const CacheArgs& a) {
  if (a.action == "ls") return run_ls(a);
  if (a.action == "verify") return run_verify(a);
  if (a.action == "clear") return run_clear(a);
  return run_cache_build(a);
}

}  // namespace forest::app
