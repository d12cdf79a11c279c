#pragma once
// A hash that is the same on every machine, standard library and run (std::hash is not):
// for choices that must be reproducible from names alone (a parameter's random stream, a
// random route's turn at a fork).
#include <cstdint>
#include <string_view>

namespace orch {

// FNV-1a, 64 bits.
inline std::uint64_t stable_hash(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace orch
