#include "study/matrix/study_json.hpp"

#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "study/matrix/study_error.hpp"

namespace ballast {
namespace {

using ojson = nlohmann::ordered_json;

// Follows the parser's events to know where it is, so that a duplicate key can be
// reported with its JSON Pointer. One frame per open object or array.
class DuplicateKeyFinder {
 public:
  bool on_event(ojson::parse_event_t event, const ojson& parsed) {
    using E = ojson::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        stack_.push_back(Frame{event == E::array_start, {}, {}, 0});
        break;
      case E::key: {
        Frame& top = stack_.back();
        top.key = parsed.get<std::string>();
        if (!top.keys.insert(top.key).second && !duplicate_) duplicate_ = pointer();
        break;
      }
      case E::object_end:
      case E::array_end:
        stack_.pop_back();
        element_done();
        break;
      case E::value:
        element_done();
        break;
    }
    return true;  // keep everything: the finder only watches
  }

  // JSON Pointer of the first duplicate key, if any.
  const std::optional<std::string>& duplicate() const { return duplicate_; }

 private:
  struct Frame {
    bool array;
    std::set<std::string> keys;  // objects: keys seen so far
    std::string key;             // objects: the key whose value is being parsed
    std::size_t index;           // arrays: index of the element being parsed
  };

  void element_done() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
  }

  std::string pointer() const {
    std::string p;
    for (const Frame& f : stack_) p = f.array ? child_path(p, f.index) : child_path(p, f.key);
    return p;
  }

  std::vector<Frame> stack_;
  std::optional<std::string> duplicate_;
};

}  // namespace

ojson parse_study_json(std::string_view text, const std::string& origin) {
  DuplicateKeyFinder finder;
  ojson j;
  try {
    j = ojson::parse(
        text,
        [&finder](int /*depth*/, ojson::parse_event_t event, ojson& parsed) {
          return finder.on_event(event, parsed);
        },
        /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const ojson::parse_error& e) {
    throw StudyError(origin, "", std::string("not valid JSON: ") + e.what(),
                     "JSON with // or /* */ comments");
  }
  if (finder.duplicate()) {
    throw StudyError(origin, *finder.duplicate(), "duplicate key (a JSON reader keeps only one)",
                     "each key once per object");
  }
  return j;
}

std::string read_study_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw StudyError(path, "", "cannot read the study file", "a readable JSON file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void allow_only_keys(const ojson& object, const std::string& path,
                     std::initializer_list<const char*> allowed, const std::string& origin) {
  std::string list;
  for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  for (const auto& [key, value] : object.items()) {
    bool known = false;
    for (const char* a : allowed) known = known || key == a;
    if (!known)
      throw StudyError(origin, child_path(path, key), "unknown key \"" + key + "\"", list);
  }
}

const ojson& required_key(const ojson& object, const std::string& path, const char* key,
                          const std::string& origin) {
  if (!object.contains(key)) {
    throw StudyError(origin, child_path(path, key), std::string("missing key \"") + key + "\"",
                     "a study needs it");
  }
  return object.at(key);
}

}  // namespace ballast
