#include "study/cli/cmd_merge.hpp"

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "study/archive/hdf5_read.hpp"
#include "study/archive/study_archive.hpp"
#include "study/archive/study_summary.hpp"
#include "study/cli/command_exit.hpp"
#include "study/cli/output_paths.hpp"

namespace ballast {

using namespace h5;
namespace fs = std::filesystem;

namespace {

inline constexpr int kMergeExitIncomplete = 4;
inline constexpr std::size_t kMissingShown = 20;

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string output;
};

struct Input {
  std::string path;
  StudyArchiveHeader header;
  std::vector<ArchivedRun> runs;
};

Input read_input(const std::string& path) {
  if (!fs::exists(path)) {
    throw ArchiveRefused(path +
                         " does not exist (did its shard run?): run it with ballast study "
                         "--shard K/N, or merge without it (the merge names the runs missing)");
  }
  Handle fapl = archive_file_access();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  if (id < 0) {
    throw ArchiveRefused("cannot open " + path + " (" + last_hdf5_error() +
                         "); a shard cut short while writing is repaired by running it again "
                         "with --resume");
  }
  Handle file(id, H5Fclose, "open " + path);
  return {path, read_archive_header(file, path), read_archived_runs(file, path)};
}

void merge(const MergeOptions& o) {
  quiet_errors();
  if (fs::exists(o.output)) {
    throw ArchiveRefused(o.output + " already exists: give another -o or remove it yourself " +
                         "(nothing was changed)");
  }
  check_writable_file("-o", o.output);
  std::vector<Input> inputs;
  for (const std::string& path : o.inputs) inputs.push_back(read_input(path));
  const StudyArchiveHeader& first = inputs.front().header;
  std::map<std::string, std::pair<const Input*, const ArchivedRun*>> where;
  for (const Input& in : inputs) {
    if (in.header.fingerprint != first.fingerprint) {
      throw ArchiveRefused(in.path + " holds another study than " + inputs.front().path + " ('" +
                           in.header.study_name + "' fingerprint " + in.header.fingerprint +
                           " against '" + first.study_name + "' " + first.fingerprint +
                           "): merge only the shards of one study (nothing was written)");
    }
    for (const ArchivedRun& run : in.runs) {
      const auto [it, fresh] = where.try_emplace(run.id, &in, &run);
      if (fresh) continue;
      const bool same = it->second.second->finished == run.finished;
      throw ArchiveRefused("run '" + run.id + "' is in both " + it->second.first->path + " and " +
                           in.path +
                           (same ? " (the same run twice: was one file given twice?)"
                                 : " (two different runs of it, finished " +
                                       it->second.second->finished + " and " + run.finished + ")") +
                           ": give each run once (nothing was written)");
    }
  }

  StudyArchiveHeader header = first;
  header.shard = Shard{};
  header.created = iso8601_utc(std::chrono::system_clock::now());
  header.merged_from.clear();
  for (const Input& in : inputs) header.merged_from += in.path + "\n";
  const std::string tmp = o.output + ".tmp";
  try {
    {
      Handle fapl = archive_file_access();
      Handle out(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose,
                 "create " + tmp);
      write_archive_header(out, header);
      Handle runs = create_group(out, "runs");
      for (const Input& in : inputs) {
        Handle file(H5Fopen(in.path.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose, "open " + in.path);
        for (const ArchivedRun& run : in.runs) {
          check(H5Ocopy(file, ("runs/" + run.id).c_str(), runs, run.id.c_str(), H5P_DEFAULT,
                        H5P_DEFAULT),
                "copy run " + run.id + " from " + in.path);
        }
      }
      check(H5Fflush(out, H5F_SCOPE_GLOBAL), "flush " + tmp);
    }
  } catch (const std::exception& e) {
    // A full disk or a lost permission half-way: the inputs are untouched.
    std::error_code ec;
    fs::remove(tmp, ec);
    const fs::path dir = fs::path(o.output).parent_path();
    const fs::space_info room = fs::space(dir.empty() ? fs::path(".") : dir, ec);
    throw std::runtime_error(
        std::string(e.what()) + " (" +
        (ec ? ec.message() : std::to_string(room.available >> 10) + " KiB free there") +
        "); nothing was written to " + o.output + " and the inputs are " +
        "as they were: make room and merge again");
  }
  fs::rename(tmp, o.output);

  std::vector<std::string> missing;
  for (const auto& r : nlohmann::json::parse(header.runs_json)) {
    if (!where.count(r.at("id").get<std::string>()))
      missing.push_back(r.at("id").get<std::string>());
  }
  print_summary(std::cout, read_summary(o.output));
  std::cout << "\n"
            << o.output << ": " << where.size() << " of " << header.run_count << " runs of study '"
            << header.study_name << "' from " << inputs.size() << " files\n";
  if (missing.empty()) return;
  std::cout << missing.size() << " runs missing:";
  for (std::size_t k = 0; k < missing.size() && k < kMissingShown; ++k)
    std::cout << " " << missing[k];
  if (missing.size() > kMissingShown)
    std::cout << " ... (" << missing.size() - kMissingShown << " more)";
  std::cout << "\nrun `ballast study STUDY.json -o " << o.output
            << " --resume` to run them into it, or merge the missing shards\n";
  throw CommandExit{kMergeExitIncomplete};
}

}  // namespace

void register_merge_command(CLI::App& app) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand("merge", "Combine shards of one study into one archive");
  cmd->add_option("inputs", o->inputs, "archives written with ballast study --shard")->required();
  cmd->add_option("-o,--output", o->output, "the merged archive")->required();
  cmd->callback([o] { merge(*o); });
}

}  // namespace ballast
