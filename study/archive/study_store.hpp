// Getting finished runs into the archive without losing any (docs/ARCHIVE.md,
// "What is guaranteed").
//
// HDF5 1.10 is not crash-consistent: a process killed in the middle of a write can
// leave a file that no longer opens. So each finished run is first written as a
// complete file of its own, ARCHIVE.parts/NNNNNN.h5 (written as .tmp, fsync'ed,
// renamed: a part either exists whole or not at all), and only then copied into the
// archive, which is opened, appended to, flushed and closed for each run. Writes are
// serialised (one mutex), so a kill loses at most the runs in flight. The archive is
// closed between writes, so a study killed mid-run leaves an archive that h5py opens
// at once; a kill during the few milliseconds of a write leaves it marked as open
// (archive_file_access()), and --resume rebuilds it from the parts, after moving it
// aside. Runs the archive holds without parts (an archive made by `ballast merge`, then
// completed with --resume) are copied to ARCHIVE.parts/base.archive first. The parts
// are removed once every run of the shard is in the archive.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "study/archive/study_archive.hpp"

namespace ballast {

class StudyStore {
 public:
  using Report = std::function<void(const std::string&)>;

  // A study starting now: refuses (ArchiveRefused) an existing archive or parts
  // directory, then creates the archive with its header and no runs.
  static std::unique_ptr<StudyStore> create(const std::string& path,
                                            const StudyArchiveHeader& header, Report report);
  // --resume: checks that the archive (if any) and the parts are this study's and
  // shard's (ArchiveRefused otherwise, nothing changed), rebuilds a damaged or missing
  // archive from the parts, appends parts the archive lacks. `report` hears what it
  // found and did.
  static std::unique_ptr<StudyStore> resume(const std::string& path,
                                            const StudyArchiveHeader& header, Report report);

  // Runs in the archive: id -> ok.
  const std::map<std::string, bool>& recorded() const { return recorded_; }
  // Runs in the archive: id -> git revision of the program that ran it.
  const std::map<std::string, std::string>& revisions() const { return revisions_; }
  // Writes the part, then appends it (and any part still pending) to the archive.
  // Thread-safe; a run recorded again (a retried failure) replaces its group.
  void record(const RunRecord& record);
  // Every run of the shard is recorded: the parts are removed. Throws when some
  // parts could not be appended (the archive stayed locked): they stay for --resume.
  void finish();
  // Held while anything is written; whoever holds it knows the archive is closed.
  std::mutex& write_mutex() { return mutex_; }
  const std::string& path() const { return path_; }
  std::string parts_dir() const { return path_ + ".parts"; }

 private:
  struct Found;
  StudyStore(std::string path, StudyArchiveHeader header, Report report);
  // What is at `path`: missing, damaged, or this study's runs; refuses another study's.
  Found inspect(const std::string& path) const;
  // A copy of the archive's runs that no part holds (a merged archive being completed),
  // taken by --resume before it appends anything.
  std::string base_path() const { return parts_dir() + "/base.archive"; }
  std::string write_part(const RunRecord& record);
  // Appends the pending parts; a part whose run the archive holds with another
  // `finished` time replaces it (parts are always the newer). Returns false, the parts
  // staying pending and `append_problem_` saying why, if the archive could not be
  // opened (locked by a reader), its disk lacks the room, or a write failed.
  bool append_pending();
  // Copies the pending parts into the open archive; throws on any HDF5 failure.
  void copy_pending(hid_t file);
  void create_archive();

  std::string path_;
  StudyArchiveHeader header_;
  Report report_;
  std::mutex mutex_;
  std::map<std::string, bool> recorded_;
  std::map<std::string, std::string> revisions_;
  std::vector<std::string> pending_;  // part files not yet in the archive
  std::string append_problem_;        // why the last append left them pending
};

}  // namespace ballast
