#include "engine/state_hash.hpp"

#include <cstring>

namespace ballast {

namespace {

// FNV-1a over raw bytes: simple, and sensitive to every bit of every double.
struct Fnv1a {
  std::uint64_t h = 14695981039346656037ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  }
  template <class V>
  void all(const V& v) {
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(v[0]));
  }
};

}  // namespace

std::uint64_t state_hash(const BodyStore& bodies, const ContactList& bc, const ContactList& wc) {
  Fnv1a f;
  f.all(bodies.position);
  f.all(bodies.velocity);
  f.all(bodies.angular_velocity);
  f.all(bodies.angular_momentum);
  for (const Quat& q : bodies.orientation) f.bytes(q.coeffs().data(), 4 * sizeof(double));
  f.all(bc.a);
  f.all(bc.b);
  f.all(bc.shear_force);
  f.all(wc.a);
  f.all(wc.b);
  f.all(wc.shear_force);
  return f.h;
}

}  // namespace ballast
