// Writing and reading a run's complete state as bytes: the checkpoints from which a
// killed run resumes bit for bit (cases/box_test_checkpoint.hpp).
//
// Each type lists its fields once, in a `state_fields(io, x)` free function found by
// argument-dependent lookup (or a member `x.state_fields(io)` where the fields are
// private), and that one list serves both directions: through a StateWriter it writes
// them, through a StateReader it reads them back into the same places. A field left
// out of the list is a field a resumed run lacks, which the resume tests catch
// (tests/test_checkpoint.cpp compares the state hash; tests/cli/test_checkpoint.py
// whole archives).
//
// Plain values (trivially copyable types, and the fixed-size Eigen types and the small
// structs of them that `Bytewise` names) are copied as their bytes: a checkpoint is
// read back by the same build on the same kind of machine, which the caller checks
// (the file's header names the build). Containers carry their size first. Every byte
// written goes into an FNV-1a hash, which the reader recomputes: a damaged file is
// refused, never half read.
#pragma once

#include <cstdint>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "engine/errors.hpp"
#include "engine/fnv1a.hpp"
#include "engine/types.hpp"

namespace ballast {

// Types copied as their bytes. Specialise it (true) for a struct made only of plain
// values and Eigen fixed-size members, which the standard does not call trivially
// copyable but which hold no pointer.
template <class T>
struct Bytewise : std::bool_constant<std::is_trivially_copyable_v<T>> {};
template <>
struct Bytewise<Vec3> : std::true_type {};
template <>
struct Bytewise<Quat> : std::true_type {};
template <>
struct Bytewise<Mat3> : std::true_type {};

template <class Io, class T>
concept HasMemberState = requires(Io& io, T& x) {
  x.state_fields(io);
};
template <class Io, class T>
concept HasFreeState = requires(Io& io, T& x) {
  state_fields(io, x);
};

// The dispatch both directions share: a type's own field list, else its bytes, else a
// container's elements.
template <class Io, class T>
void state_value(Io& io, T& x) {
  if constexpr (HasMemberState<Io, T>) {
    x.state_fields(io);
  } else if constexpr (HasFreeState<Io, T>) {
    state_fields(io, x);
  } else if constexpr (Bytewise<T>::value) {
    io.bytes(&x, sizeof(T));
  } else {
    static_assert(sizeof(T) == 0, "no state_fields() for this type and it is not Bytewise");
  }
}

template <class Io, class T>
void state_fields(Io& io, std::vector<T>& v) {
  std::uint64_t n = v.size();
  io.bytes(&n, sizeof n);
  if constexpr (Io::kReading) {
    io.check_count(n, sizeof(T));
    v.resize(n);
  }
  if constexpr (Bytewise<T>::value) {
    if (n) io.bytes(v.data(), n * sizeof(T));
  } else {
    for (T& x : v) state_value(io, x);
  }
}

template <class Io>
void state_fields(Io& io, std::string& s) {
  std::uint64_t n = s.size();
  io.bytes(&n, sizeof n);
  if constexpr (Io::kReading) {
    io.check_count(n, 1);
    s.resize(n);
  }
  if (n) io.bytes(s.data(), n);
}

template <class Io, class T>
void state_fields(Io& io, std::optional<T>& o) {
  std::uint8_t has = o.has_value();
  io.bytes(&has, 1);
  if constexpr (Io::kReading) {
    if (has)
      o.emplace();
    else
      o.reset();
  }
  if (has) state_value(io, *o);
}

class StateWriter {
 public:
  static constexpr bool kReading = false;
  explicit StateWriter(std::ostream& out) : out_(out) {}
  // Writing leaves every value as it was; the const_cast only lets one field list
  // serve both directions.
  template <class... T>
  void operator()(const T&... x) {
    (state_value(*this, const_cast<T&>(x)), ...);
  }
  void bytes(const void* p, std::size_t n) {
    out_.write(static_cast<const char*>(p), static_cast<std::streamsize>(n));
    hash_.bytes(p, n);
  }
  std::uint64_t hash() const { return hash_.h; }

 private:
  std::ostream& out_;
  Fnv1a hash_;
};

class StateReader {
 public:
  static constexpr bool kReading = true;
  // `what` names the source in errors ("checkpoint run.h5.checkpoint").
  StateReader(std::istream& in, std::string what) : in_(in), what_(std::move(what)) {}
  template <class... T>
  void operator()(T&... x) {
    (state_value(*this, x), ...);
  }
  void bytes(void* p, std::size_t n) {
    in_.read(static_cast<char*>(p), static_cast<std::streamsize>(n));
    if (static_cast<std::size_t>(in_.gcount()) != n)
      throw SetupError(what_ + " is truncated (it ends inside its state)");
    hash_.bytes(p, n);
  }
  // A container's size, before it is allocated: at most what the rest of the file can
  // hold, so that a damaged size is refused instead of allocating terabytes.
  void check_count(std::uint64_t n, std::size_t element) {
    if (element && n > (std::uint64_t(1) << 40) / element)
      throw SetupError(what_ + " is damaged (a container of " + std::to_string(n) + " elements)");
  }
  std::uint64_t hash() const { return hash_.h; }
  const std::string& what() const { return what_; }

 private:
  std::istream& in_;
  std::string what_;
  Fnv1a hash_;
};

}  // namespace ballast
