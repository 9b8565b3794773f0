// Reading one JSON object of a scene file field by field, so that every error names
// the JSON path, the value and what is allowed, and a misspelt key is an error
// rather than a silently ignored default:
//
//   JsonFields f(j, "/sleeper");
//   f.number("length", s.length, "> 0 m", [](double v) { return v > 0; });
//   f.finish();   // throws for any key not read
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "engine/errors.hpp"

namespace ballast {

class JsonFields {
 public:
  JsonFields(const nlohmann::json& object, std::string path);

  // Each reader leaves `out` untouched when the key is absent and returns whether
  // it was present. `ok` checks the range; `allowed` says it in words.
  bool number(const char* key, double& out, const std::string& allowed,
              const std::function<bool(double)>& ok);
  bool integer(const char* key, long& out, const std::string& allowed,
               const std::function<bool(long)>& ok);
  // A non-empty array of integers, each passing `ok`.
  bool integers(const char* key, std::vector<long>& out, const std::string& allowed,
                const std::function<bool(long)>& ok);
  // Any JSON integer in [0, 2^64 - 1] (seeds).
  bool unsigned_integer(const char* key, std::uint64_t& out);
  bool text(const char* key, std::string& out, const std::string& allowed,
            const std::function<bool(const std::string&)>& ok);
  bool boolean(const char* key, bool& out);
  // A nested object; absent gives an empty object.
  const nlohmann::json& object(const char* key);
  std::string path_of(const char* key) const { return path_ + "/" + key; }
  // Throws naming the first key that no reader asked for.
  void finish() const;

 private:
  const nlohmann::json* find(const char* key);
  [[noreturn]] void fail(const char* key, const std::string& value,
                         const std::string& allowed) const;

  const nlohmann::json& j_;
  std::string path_;
  std::set<std::string> read_;
};

}  // namespace ballast
