#include "cases/clump_overrides.hpp"

#include <nlohmann/json.hpp>

#include "engine/clump_param_table.hpp"

namespace ballast {

namespace {

void read_fields(JsonFields& fields, ClumpParams& q, bool overridable_only) {
  for (const ClumpParamField& f : clump_param_fields()) {
    if (overridable_only && !f.overridable) continue;
    const std::string key(f.name);
    const std::string allowed = f.allowed();
    switch (f.kind) {
      case ClumpParamKind::kInteger: {
        long v = static_cast<long>(f.value(q));
        if (fields.integer(key.c_str(), v, allowed, [&](long x) { return f.allows(double(x)); }))
          f.set(q, static_cast<double>(v));
        break;
      }
      case ClumpParamKind::kNumber: {
        double v = f.value(q);
        if (fields.number(key.c_str(), v, allowed, [&](double x) { return f.allows(x); }))
          f.set(q, v);
        break;
      }
      case ClumpParamKind::kChoice: {
        std::string v = f.text(q);
        if (fields.text(key.c_str(), v, allowed,
                        [&](const std::string& x) { return f.allows_text(x); }))
          f.set_text(q, v);
        break;
      }
    }
  }
}

}  // namespace

void read_clump_overrides(JsonFields& fields, ClumpParams& q) {
  read_fields(fields, q, true);
}

void read_clump_params(JsonFields& fields, ClumpParams& q) {
  read_fields(fields, q, false);
}

void apply_clump_overrides(const nlohmann::json& params, const std::string& path, ClumpParams& q) {
  nlohmann::json clump = nlohmann::json::object();
  for (const auto& [key, value] : params.items()) {
    const ClumpParamField* f = find_clump_param(key);
    if (f && f->overridable) clump[key] = value;
  }
  JsonFields fields(clump, path);
  read_clump_overrides(fields, q);
}

}  // namespace ballast
