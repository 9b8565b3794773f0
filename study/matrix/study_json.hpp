// Reading a study file's JSON strictly. nlohmann::json keeps only the last of two equal
// keys in one object, so {"axes": {"p": [0.3], "p": [0.5]}} would silently lose an
// axis; a study file is refused instead. Comments (// and /* */) are allowed, as in the
// clump presets, so that a researcher can annotate a study.
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace ballast {

// Parses text into an ordered_json (object keys stay in the order written, which fixes
// the order of a study's axes). Throws StudyError naming `origin` and, for a duplicate
// key, its JSON Pointer; invalid JSON gives the parser's byte position.
nlohmann::ordered_json parse_study_json(std::string_view text, const std::string& origin);

// The whole file as text; throws StudyError naming the path when it cannot be read.
std::string read_study_text(const std::string& path);

// Refuses any key of `object` (at JSON Pointer `path`) that is not in `allowed`.
void allow_only_keys(const nlohmann::ordered_json& object, const std::string& path,
                     std::initializer_list<const char*> allowed, const std::string& origin);
// object[key], or a StudyError "missing key" at path/key.
const nlohmann::ordered_json& required_key(const nlohmann::ordered_json& object,
                                           const std::string& path, const char* key,
                                           const std::string& origin);

}  // namespace ballast
