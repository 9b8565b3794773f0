#include "study/archive/study_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "study/archive/file_image.hpp"
#include "study/archive/hdf5_read.hpp"

namespace ballast {

using namespace h5;
namespace fs = std::filesystem;

namespace {

// A run is copied under this name and then renamed to its id, so that a copy cut
// short (an I/O error) never looks like a run. '~' is not an id character.
constexpr const char* kIncoming = "~incoming";

// Data and name on disk before the next step relies on them (power loss, not only a
// kill: the kernel's page cache survives a killed process anyway).
void sync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// One attempt to open the archive; -1 if it cannot be (a reader holds HDF5's file
// lock, or the file is damaged), and then `why` gets HDF5's reason. It is read here
// because closing the property list clears HDF5's error stack.
hid_t try_open(const std::string& path, unsigned flags, std::string* why = nullptr) {
  Handle fapl = archive_file_access();
  const hid_t id = H5Fopen(path.c_str(), flags, fapl);
  if (id < 0 && why) *why = last_hdf5_error();
  return id;
}

struct PartInfo {
  std::string path, id, finished, git_revision;
  bool ok = false;
};

// Reads a part's header; throws ArchiveRefused if it belongs to another study, returns
// nullopt if it cannot be read at all.
std::optional<PartInfo> read_part(const std::string& path, const std::string& fingerprint) {
  const hid_t id = try_open(path, H5F_ACC_RDONLY);
  if (id < 0) return std::nullopt;
  Handle file(id, H5Fclose, "open " + path);
  if (!has_attribute(file, "format") || read_text_attribute(file, "format") != kRunPartFormat)
    return std::nullopt;
  if (read_text_attribute(file, "fingerprint") != fingerprint) {
    throw ArchiveRefused("part " + path + " belongs to another study (fingerprint " +
                         read_text_attribute(file, "fingerprint") + ", this study's is " +
                         fingerprint + "): move the parts directory away or give another -o");
  }
  Handle run(H5Gopen2(file, "run", H5P_DEFAULT), H5Gclose, "open /run in " + path);
  const ArchivedRun a = read_archived_run(run, path + ":/run");
  return PartInfo{path, a.id, a.finished, a.git_revision, a.ok};
}

std::string aside_name(const std::string& path) {
  std::string name = path + ".damaged";
  for (int k = 2; fs::exists(name); ++k) name = path + ".damaged." + std::to_string(k);
  return name;
}

}  // namespace

StudyStore::StudyStore(std::string path, StudyArchiveHeader header, Report report)
    : path_(std::move(path)), header_(std::move(header)), report_(std::move(report)) {
  quiet_errors();
}

void StudyStore::create_archive() {
  // Written under another name and renamed: an archive either has its header or does
  // not exist.
  const std::string tmp = path_ + ".tmp";
  {
    Handle fapl = archive_file_access();
    Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose,
                "create " + tmp);
    write_archive_header(file, header_);
    Handle runs = create_group(file, "runs");
  }
  sync_path(tmp);
  fs::rename(tmp, path_);
  fs::create_directories(parts_dir());
}

std::unique_ptr<StudyStore> StudyStore::create(const std::string& path,
                                               const StudyArchiveHeader& header, Report report) {
  if (fs::exists(path)) {
    throw ArchiveRefused(path + " already exists: give --resume to complete the study it holds, " +
                         "or another -o, or remove it yourself (nothing was changed)");
  }
  std::unique_ptr<StudyStore> s(new StudyStore(path, header, std::move(report)));
  if (fs::exists(s->parts_dir())) {
    throw ArchiveRefused(s->parts_dir() + " exists (finished runs of an interrupted study): " +
                         "give --resume to use them, or remove it yourself (nothing was changed)");
  }
  s->create_archive();
  return s;
}

// The archive as resume finds it.
struct StudyStore::Found {
  bool exists = false;
  std::string damage;                       // why it cannot be used as it is
  std::map<std::string, ArchivedRun> runs;  // its runs, when it is usable
};

StudyStore::Found StudyStore::inspect(const std::string& path) const {
  Found f;
  f.exists = fs::exists(path);
  if (!f.exists) return f;
  std::string why;
  const hid_t id = try_open(path, H5F_ACC_RDONLY, &why);
  if (id < 0) {
    f.damage = "it does not open: " + why;
    return f;
  }
  Handle file(id, H5Fclose, "open " + path);
  const StudyArchiveHeader h = read_archive_header(file, path);  // refuses non-archives
  if (h.fingerprint != header_.fingerprint) {
    throw ArchiveRefused(path + " holds another study ('" + h.study_name + "', fingerprint " +
                         h.fingerprint + "; this study's is " + header_.fingerprint +
                         ": its runs, seeds or base scene differ): give another -o " +
                         "(nothing was changed)");
  }
  if (h.shard.index != header_.shard.index || h.shard.count != header_.shard.count) {
    throw ArchiveRefused(path + " holds shard " + h.shard.text() + " of the study, not " +
                         header_.shard.text() + ": give --shard " + h.shard.text() +
                         " (nothing was changed)");
  }
  try {
    for (const ArchivedRun& a : read_archived_runs(file, path)) f.runs[a.id] = a;
  } catch (const ArchiveRefused& e) {
    f.damage = e.what();
    f.runs.clear();
  }
  return f;
}

std::unique_ptr<StudyStore> StudyStore::resume(const std::string& path,
                                               const StudyArchiveHeader& header, Report report) {
  std::unique_ptr<StudyStore> s(new StudyStore(path, header, std::move(report)));
  // 1. Look at everything before changing anything.
  Found archive = s->inspect(path);
  const std::string base = s->base_path();
  std::vector<PartInfo> parts;
  std::vector<fs::path> cut;  // parts whose writing was cut short: their runs are redone
  std::map<std::string, const PartInfo*> part_of;
  if (fs::exists(s->parts_dir())) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(s->parts_dir())) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
      if (f.extension() == ".tmp") cut.push_back(f);
      if (f.extension() != ".h5") continue;
      const std::optional<PartInfo> p = read_part(f.string(), header.fingerprint);
      if (p) {
        parts.push_back(*p);
      } else {
        s->report_("ignoring unreadable part " + f.string() + " (its run will be redone)");
      }
    }
  }
  for (const PartInfo& p : parts) part_of[p.id] = &p;
  Found saved = fs::exists(base) ? s->inspect(base) : Found{};
  if (!saved.damage.empty()) saved = Found{};

  // 2. Act.
  if (!archive.damage.empty()) {
    if (parts.empty() && !saved.exists) {
      throw ArchiveRefused(path + " is damaged (" + archive.damage + ") and " + s->parts_dir() +
                           " holds no finished runs to rebuild it from. Move it aside to " +
                           "start the study again (nothing was changed)");
    }
    const std::string aside = aside_name(path);
    fs::rename(path, aside);
    s->report_(path + " is damaged (" + archive.damage + "): moved to " + aside +
               "; rebuilding it from " + std::to_string(parts.size()) + " finished runs in " +
               s->parts_dir() + (saved.exists ? " and the copy of its earlier runs there" : ""));
  } else if (!archive.exists) {
    s->report_(parts.empty()
                   ? "no archive at " + path + ": starting the study"
                   : "no archive at " + path + ": rebuilding it from " +
                         std::to_string(parts.size()) + " finished runs in " + s->parts_dir());
  }
  if (!archive.damage.empty() || !archive.exists) {
    if (saved.exists) {
      // Runs that were in the archive without a part (merged, or from a finished study):
      // their copy from the start of the last --resume.
      fs::copy_file(base, path + ".tmp", fs::copy_options::overwrite_existing);
      fs::rename(path + ".tmp", path);
      archive = saved;
    } else {
      s->create_archive();
      archive = Found{true, "", {}};
    }
  }
  for (const fs::path& f : cut) fs::remove(f);
  fs::create_directories(s->parts_dir());
  bool unsaved = false;  // archived runs that no part holds
  for (const auto& [id, a] : archive.runs) {
    s->recorded_[id] = a.ok;
    s->revisions_[id] = a.git_revision;
    unsaved = unsaved || !part_of.count(id);
  }
  if (unsaved && archive.runs.size() != saved.runs.size()) {
    // A kill during the next append would otherwise lose them.
    fs::copy_file(path, base + ".tmp", fs::copy_options::overwrite_existing);
    sync_path(base + ".tmp");
    fs::rename(base + ".tmp", base);
  }
  for (const PartInfo& p : parts) {
    const auto it = archive.runs.find(p.id);
    if (it == archive.runs.end() || it->second.finished != p.finished)
      s->pending_.push_back(p.path);
    s->recorded_[p.id] = p.ok;
    s->revisions_[p.id] = p.git_revision;
  }
  if (!s->pending_.empty()) {
    s->report_("appending " + std::to_string(s->pending_.size()) +
               " finished runs from the parts to " + path);
    if (!s->append_pending()) throw std::runtime_error("cannot open " + path + " to append runs");
  }
  return s;
}

std::string StudyStore::write_part(const RunRecord& r) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu.h5", r.spec.index);
  const std::string part = (fs::path(parts_dir()) / name).string();
  MemoryFile file(part);
  string_attribute(file, "format", kRunPartFormat);
  number_attribute(file, "format_version", kStudyArchiveVersion);
  string_attribute(file, "fingerprint", header_.fingerprint);
  {
    Handle run = create_group(file, "run");
    write_run_group(run, r);
  }
  file.save(part);
  return part;
}

bool StudyStore::append_pending() {
  const std::string waiting =
      std::to_string(pending_.size()) + " finished runs wait in " + parts_dir();
  // A disk that fills half-way through HDF5's writes leaves the archive damaged (resume
  // rebuilds it from the parts, but that is a night's archive to rebuild): look for
  // the room first, twice the parts' size for the copies and HDF5's own bookkeeping.
  std::uintmax_t needed = std::uintmax_t(1) << 20;
  std::error_code ec;
  for (const std::string& part : pending_) {
    const std::uintmax_t size = fs::file_size(part, ec);
    if (!ec) needed += 2 * size;
  }
  const fs::path dir = fs::path(path_).parent_path();
  const fs::space_info room = fs::space(dir.empty() ? fs::path(".") : dir, ec);
  if (!ec && room.available < needed) {
    append_problem_ = "no room to append to " + path_ + ": " +
                      std::to_string(room.available >> 10) + " KiB free, about " +
                      std::to_string(needed >> 10) + " KiB needed";
    report_(append_problem_ + "; " + waiting);
    return false;
  }
  // A reader (h5py, h5dump) holding the archive open keeps HDF5's file lock: wait a
  // little for it, then leave the runs pending (they are safe in their parts).
  hid_t id = -1;
  std::string why;
  for (int attempt = 0; attempt < 10 && id < 0; ++attempt) {
    if (attempt > 0) std::this_thread::sleep_for(std::chrono::seconds(1));
    id = try_open(path_, H5F_ACC_RDWR, &why);
  }
  if (id < 0) {
    append_problem_ = "cannot open " + path_ + " to append (" + why + ")";
    report_(append_problem_ + ": " + waiting);
    return false;
  }
  try {
    Handle file(id, H5Fclose, "open " + path_);
    copy_pending(file);
  } catch (const std::exception& e) {
    append_problem_ = e.what();
    report_(append_problem_ + ": " + waiting +
            " (--resume appends them, and rebuilds the archive should this have damaged it)");
    return false;
  }
  pending_.clear();
  return true;
}

void StudyStore::copy_pending(hid_t file) {
  Handle runs(H5Gopen2(file, "runs", H5P_DEFAULT), H5Gclose, "open /runs in " + path_);
  if (has_link(runs, kIncoming))
    check(H5Ldelete(runs, kIncoming, H5P_DEFAULT), "remove a cut copy");
  for (const std::string& part : pending_) {
    Handle pf(try_open(part, H5F_ACC_RDONLY), H5Fclose, "open " + part);
    Handle run(H5Gopen2(pf, "run", H5P_DEFAULT), H5Gclose, "open /run in " + part);
    const std::string run_id = read_text_attribute(run, "id");
    check(H5Ocopy(pf, "run", runs, kIncoming, H5P_DEFAULT, H5P_DEFAULT),
          "copy " + part + " into " + path_);
    if (has_link(runs, run_id))
      check(H5Ldelete(runs, run_id.c_str(), H5P_DEFAULT), "replace " + run_id);
    check(H5Lmove(runs, kIncoming, runs, run_id.c_str(), H5P_DEFAULT, H5P_DEFAULT),
          "name run " + run_id);
  }
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path_);
}

void StudyStore::record(const RunRecord& r) {
  std::lock_guard<std::mutex> lock(mutex_);
  quiet_errors();  // this worker thread's HDF5 error setting
  try {
    pending_.push_back(write_part(r));
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(e.what()) + "; run " + r.spec.id +
                             " is lost, every run finished before it is kept in " + path_ + " or " +
                             parts_dir() +
                             ": once that is mended, run the same command with --resume");
  }
  recorded_[r.spec.id] = r.ok;
  revisions_[r.spec.id] = r.git_revision;
  append_pending();
}

void StudyStore::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  quiet_errors();
  if (!pending_.empty() && !append_pending()) {
    throw std::runtime_error(std::to_string(pending_.size()) + " finished runs could not be " +
                             "appended to " + path_ + " (" + append_problem_ +
                             "); they are safe in " + parts_dir() +
                             ": run the same command with --resume to append them");
  }
  sync_path(path_);
  fs::remove_all(parts_dir());
}

}  // namespace ballast
