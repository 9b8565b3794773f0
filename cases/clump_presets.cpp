#include "cases/clump_presets.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cases/clump_overrides.hpp"
#include "cases/json_fields.hpp"
#include "engine/clump_mass.hpp"
#include "engine/clump_param_table.hpp"
#include "engine/errors.hpp"

namespace ballast {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

[[noreturn]] void fail(const std::string& origin, const std::string& what) {
  throw SetupError(origin + ": " + what);
}

bool is_documentation(const std::string& key) {
  auto ends_with = [&key](std::string_view tail) {
    return key.size() >= tail.size() &&
           key.compare(key.size() - tail.size(), tail.size(), tail) == 0;
  };
  return key == "source" || key == "description" || key == "notes" || ends_with("_source") ||
         ends_with("_note");
}

std::string read_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw SetupError("cannot read " + what + " '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

std::string clump_preset_dir() {
  return std::string(BALLAST_CASES_DIR) + "/presets";
}

std::vector<std::string> available_clump_presets() {
  std::vector<std::string> names;
  const fs::path root = clump_preset_dir();
  if (!fs::is_directory(root)) return names;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".json") continue;
    fs::path rel = fs::relative(entry.path(), root);
    rel.replace_extension();
    names.push_back(rel.generic_string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

ClumpPreset load_clump_preset(const std::string& name) {
  const std::vector<std::string> names = available_clump_presets();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw SetupError("unknown clump preset '" + name + "'; available: " +
                     (list.empty() ? "(none found in " + clump_preset_dir() + ")" : list));
  }
  const std::string path = clump_preset_dir() + "/" + name + ".json";
  ClumpPreset p =
      parse_clump_preset(read_file(path, "clump preset"), "clump preset '" + name + "'");
  p.name = name;
  return p;
}

ClumpPreset load_clump_params_file(const std::string& path) {
  ClumpPreset p = parse_clump_preset(read_file(path, "clump parameter file"), path);
  p.name = path;
  return p;
}

ClumpPreset parse_clump_preset(std::string_view json_text, const std::string& origin) {
  json j;
  try {
    j = json::parse(json_text, nullptr, true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    fail(origin, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) fail(origin, "expected a JSON object of clump parameters");

  // The clump parameters come from the parameter table (engine/clump_param_table.hpp);
  // besides them a file may give the density and the paper's counts.
  static const char* const kExtra[] = {"density", "paper"};
  for (const ClumpParamField& f : clump_param_fields()) {
    if (f.required_in_presets && !j.contains(std::string(f.name)))
      fail(origin, "missing field '" + std::string(f.name) + "'");
  }
  for (const auto& item : j.items()) {
    const std::string& key = item.key();  // a plain reference: lambdas may capture it
    const bool known =
        is_documentation(key) || find_clump_param(key) != nullptr ||
        std::any_of(std::begin(kExtra), std::end(kExtra), [&](const char* k) { return key == k; });
    if (!known) {
      fail(origin, "unknown field '" + key + "' (known: " + clump_param_names(false) +
                       ", density, paper, and documentation fields "
                       "source, description, notes, *_source, *_note)");
    }
  }

  ClumpPreset p;
  ClumpParams& q = p.params;
  const auto positive = [](double v) { return v > 0.0; };
  try {
    // One reader for the file's fields (cases/json_fields.hpp): the clump parameters
    // through the table, each checked against its range where it is read.
    JsonFields fields(j, "");
    const auto any_text = [](const std::string&) { return true; };
    fields.text("source", p.source, "a string", any_text);
    fields.text("description", p.description, "a string", any_text);
    read_clump_params(fields, q);
    fields.number("density", p.density, "> 0 kg/m^3", positive);
    if (j.contains("paper")) {
      JsonFields paper(fields.object("paper"), "/paper");
      long clumps = 0, balls = 0;
      const bool both = paper.integer("clumps", clumps, "> 0", [](long v) {
        return v > 0;
      }) && paper.integer("balls", balls, ">= /paper/clumps", [&](long v) { return v >= clumps; });
      if (!both) throw SetupError("invalid /paper (allowed: {\"clumps\": int, \"balls\": int})");
      paper.finish();
      p.paper_clumps = static_cast<int>(clumps);
      p.paper_balls = static_cast<int>(balls);
    }
    validate_clump_params(q);
    ClumpMassOptions mass;
    mass.density = p.density;
    validate_mass_options(mass);
  } catch (const SetupError& e) {
    fail(origin, e.what());
  }
  return p;
}

}  // namespace ballast
