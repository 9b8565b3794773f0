// The registry of contact laws: one list of types, and the dispatch that turns a
// scene's law (an index into the list) into a call compiled for that law. A law is
// a header of its own (contact_law.hpp says what it holds); adding one is that
// header, its entry in ContactLaws below, and its closed-form test
// (docs/ARCHITECTURE.md, "Where to add things").
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>

#include "engine/errors.hpp"
#include "engine/law_hertz_mindlin.hpp"
#include "engine/law_linear.hpp"

namespace ballast {

using ContactLaws = std::tuple<LinearLaw, HertzMindlinLaw>;

inline constexpr int kContactLawCount = std::tuple_size_v<ContactLaws>;

// Calls f(Law{}) for law number `law` of ContactLaws (0 <= law < kContactLawCount),
// so that f is compiled once per law and each call runs that law's code only.
template <class F>
decltype(auto) with_contact_law(int law, F&& f) {
  return [&]<std::size_t... I>(std::index_sequence<I...>)->decltype(auto) {
    using Result = decltype(f(std::tuple_element_t<0, ContactLaws>{}));
    if constexpr (std::is_void_v<Result>) {
      ((law == int(I) ? (f(std::tuple_element_t<I, ContactLaws>{}), true) : false) || ...);
    } else {
      Result r{};
      ((law == int(I) ? (r = f(std::tuple_element_t<I, ContactLaws>{}), true) : false) || ...);
      return r;
    }
  }
  (std::make_index_sequence<kContactLawCount>{});
}

// The law's number, or -1 for a name no law has.
inline int contact_law_index(std::string_view name) {
  int found = -1;
  for (int i = 0; i < kContactLawCount; ++i)
    with_contact_law(i, [&](auto law) {
      if (decltype(law)::kName == name) found = i;
    });
  return found;
}

inline std::string_view contact_law_name(int law) {
  return with_contact_law(law, [](auto l) { return decltype(l)::kName; });
}

// The Material members law number `law` reads, with their ranges.
inline std::span<const LawParameter> law_parameters(int law) {
  return with_contact_law(
      law, [](auto l) { return std::span<const LawParameter>(decltype(l)::kParameters); });
}

// "linear, hertz_mindlin", for error messages.
inline std::string contact_law_names() {
  std::string names;
  for (int i = 0; i < kContactLawCount; ++i)
    names += (i ? ", " : "") + std::string(contact_law_name(i));
  return names;
}

// Refuses a Material that holds one of the law's parameters out of its range:
// "invalid <what>young_modulus = -1 (allowed: > 0 Pa)". A law number out of the
// table checks nothing (the caller refuses the law's name itself).
inline void check_law_parameters(int law, const Material& m, const std::string& what) {
  if (law < 0 || law >= kContactLawCount) return;
  for (const LawParameter& p : law_parameters(law))
    require_setup(p.allows(m.*p.member), what + std::string(p.name), m.*p.member,
                  std::string(p.allowed));
}

}  // namespace ballast
