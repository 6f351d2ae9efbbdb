// A 128-bit content hash for cache keys and cache records: FNV-1a 64 run twice with
// different offsets and a mixing step. Not cryptographic; what matters is that honest,
// different inputs never share a key.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace forest {

struct ContentHash {
  uint64_t a = 0xcbf29ce484222325ull, b = 0x84222325cbf29ce4ull;
  // One field; a separator after every field keeps ("ab","c") and ("a","bc") apart.
  void add(std::string_view bytes) {
    for (unsigned char c : bytes) {
      a = (a ^ c) * 0x100000001b3ull;
      b = (b ^ c) * 0x100000001b3ull;
      b ^= b >> 29;
    }
    a = (a ^ 0xff) * 0x100000001b3ull;
    b = (b ^ 0xfe) * 0x100000001b3ull;
  }
  // 32 hex digits.
  std::string hex() const {
    char s[33];
    std::snprintf(s, sizeof(s), "%016llx%016llx", (unsigned long long)a, (unsigned long long)b);
    return s;
  }
};

// The hash of one byte string, as 32 hex digits.
inline std::string content_hash(std::string_view bytes) {
  ContentHash h;
  h.add(bytes);
  return h.hex();
}

}  // namespace forest
