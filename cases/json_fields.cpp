#include "cases/json_fields.hpp"

#include <algorithm>

namespace ballast {

namespace {
const nlohmann::json kEmpty = nlohmann::json::object();
}

JsonFields::JsonFields(const nlohmann::json& object, std::string path)
    : j_(object), path_(std::move(path)) {
  if (!j_.is_object())
    throw SetupError("invalid " + (path_.empty() ? std::string("/") : path_) + " = " + j_.dump() +
                     " (allowed: a JSON object)");
}

const nlohmann::json* JsonFields::find(const char* key) {
  read_.insert(key);
  const auto it = j_.find(key);
  return it == j_.end() ? nullptr : &*it;
}

void JsonFields::fail(const char* key, const std::string& value, const std::string& allowed) const {
  throw SetupError("invalid " + path_ + "/" + key + " = " + value + " (allowed: " + allowed + ")");
}

bool JsonFields::number(const char* key, double& out, const std::string& allowed,
                        const std::function<bool(double)>& ok) {
  const nlohmann::json* v = find(key);
  if (!v) return false;
  if (!v->is_number() || !ok(v->get<double>())) fail(key, v->dump(), "a number " + allowed);
  out = v->get<double>();
  return true;
}

bool JsonFields::integer(const char* key, long& out, const std::string& allowed,
                         const std::function<bool(long)>& ok) {
  const nlohmann::json* v = find(key);
  if (!v) return false;
  if (!v->is_number_integer() || !ok(v->get<long>())) fail(key, v->dump(), "an integer " + allowed);
  out = v->get<long>();
  return true;
}

bool JsonFields::integers(const char* key, std::vector<long>& out, const std::string& allowed,
                          const std::function<bool(long)>& ok) {
  const nlohmann::json* v = find(key);
  if (!v) return false;
  const auto good = [&ok](const nlohmann::json& e) {
    return e.is_number_integer() && ok(e.get<long>());
  };
  if (!v->is_array() || v->empty() || !std::all_of(v->begin(), v->end(), good))
    fail(key, v->dump(), "a non-empty array of integers " + allowed);
  out = v->get<std::vector<long>>();
  return true;
}

bool JsonFields::unsigned_integer(const char* key, std::uint64_t& out) {
  const nlohmann::json* v = find(key);
  if (!v) return false;
  // nlohmann::json holds integers above INT64_MAX as unsigned, negative ones as signed.
  const bool ok =
      v->is_number_unsigned() || (v->is_number_integer() && v->get<std::int64_t>() >= 0);
  if (!ok) fail(key, v->dump(), "an integer in [0, 2^64 - 1]");
  out = v->get<std::uint64_t>();
  return true;
}

bool JsonFields::text(const char* key, std::string& out, const std::string& allowed,
                      const std::function<bool(const std::string&)>& ok) {
  const nlohmann::json* v = find(key);
  if (!v) return false;
  if (!v->is_string() || !ok(v->get<std::string>())) fail(key, v->dump(), allowed);
  out = v->get<std::string>();
  return true;
}

bool JsonFields::boolean(const char* key, bool& out) {
  const nlohmann::json* v = find(key);
  if (!v) return false;
  if (!v->is_boolean()) fail(key, v->dump(), "true or false");
  out = v->get<bool>();
  return true;
}

const nlohmann::json& JsonFields::object(const char* key) {
  const nlohmann::json* v = find(key);
  if (!v) return kEmpty;
  if (!v->is_object()) fail(key, v->dump(), "a JSON object");
  return *v;
}

void JsonFields::finish() const {
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    if (read_.count(it.key())) continue;
    std::string known;
    for (const std::string& k : read_) known += (known.empty() ? "" : ", ") + k;
    throw SetupError("unknown key " + path_ + "/" + it.key() + " (allowed keys here: " + known +
                     ")");
  }
}

}  // namespace ballast
