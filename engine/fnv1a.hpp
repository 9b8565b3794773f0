// FNV-1a, 64 bits, over raw bytes: the one hash of the project. The state hash folds
// every double of a run into it (state_hash.hpp: sensitive to every bit), and the
// study runner hashes a run's canonical text into its seed (study/matrix/run_identity.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace ballast {

struct Fnv1a {
  std::uint64_t h = 14695981039346656037ull;  // the offset basis
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;  // the FNV prime
  }
  template <class T>
  void value(const T& v) {
    bytes(&v, sizeof(v));
  }
  // The size first, so that moving an element from one vector to the next shows.
  template <class V>
  void all(const V& v) {
    value(v.size());
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(v[0]));
  }
};

inline std::uint64_t fnv1a64(std::string_view text) {
  Fnv1a f;
  f.bytes(text.data(), text.size());
  return f.h;
}

}  // namespace ballast
