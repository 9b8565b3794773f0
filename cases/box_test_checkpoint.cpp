#include "cases/box_test_checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "engine/state_io.hpp"

namespace ballast {

// The field lists of what a box test measures (cases/box_test_result.hpp). Plain
// structs of numbers (ContactStats, SleeperBearing, ZoneMotion, Zones, RotationStats,
// EnergyBudget, ClumpParams, ClumpMassOptions, ClumpShape) go as their bytes.
template <class Io>
void state_fields(Io& io, StageReport& s) {
  io(s.name, s.steps, s.simulated, s.seconds, s.unbalanced, s.ended_by, s.energy_in,
     s.energy_dissipated, s.energy_error);
}

template <class Io>
void state_fields(Io& io, ContactSnapshot& c) {
  io(c.stats, c.from, c.to, c.force, c.force_p50, c.force_p90, c.force_p99, c.sleeper);
}

template <class Io>
void state_fields(Io& io, NearPairs& n) {
  io(n.gap, n.ball_pairs, n.wall_pairs, n.intra_clump_pairs);
}

template <class Io>
void state_fields(Io& io, CycleSnapshot& c) {
  io(c.cycle, c.settlement, c.position, c.rotation_deg);
}

template <class Io>
void state_fields(Io& io, CycleRecords& c) {
  io(c.settlement_peak, c.settlement_trough, c.sleeper_work, c.rotation_mean_deg,
     c.sleeper_contacts, c.sleeper_bodies, c.porosity_under, c.snapshots);
}

template <class Io>
void state_fields(Io& io, ClumpTemplate& t) {
  io(t.offsets, t.radii, t.mass, t.principal_inertia, t.volume, t.density, t.mass_mode,
     t.integration_error, t.generation_centre, t.generation_rotation);
}

template <class Io>
void state_fields(Io& io, ClumpSampleRecord& c) {
  io(c.shape, c.params, c.mass, c.seed, c.templates, c.shapes);
}

template <class Io>
void state_fields(Io& io, BoxTestResult& r) {
  io(r.scene_name, r.stages, r.bodies, r.balls, r.dt, r.dt_critical, r.wall_seconds, r.loaded,
     r.porosity_grid, r.porosity_grid_interior, r.sphere_heights, r.porosity_spheres, r.bed_height,
     r.before, r.at_peak, r.after, r.near_before, r.zones, r.rotation_loading, r.rotation_unloading,
     r.rotation_cycle, r.max_displacement_peak, r.max_displacement_after, r.settlement_peak,
     r.permanent_settlement, r.resilient_settlement, r.max_force_error, r.rms_force_error, r.time,
     r.target_force, r.sleeper_force, r.settlement, r.cycles, r.position_start, r.position_peak,
     r.position_end, r.rotation_deg_loading, r.rotation_deg_unloading, r.rotation_deg_cycle,
     r.shape_index, r.clumps, r.energy);
}

namespace {

constexpr char kMagic[] = "ballast-checkpoint 2";

std::string cause() {
  return std::strerror(errno);
}

// Writes `bytes` to `path` so that a kill at any moment leaves either the old file or
// the new one: a temporary file beside it, synced, renamed over it, the folder synced.
void write_atomically(const std::string& path, const std::string& bytes) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write checkpoint " + tmp + ": " + cause());
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = cause();
      ::close(fd);
      ::unlink(tmp.c_str());
      throw std::runtime_error("cannot write checkpoint " + tmp + ": " + why);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const std::string why = cause();
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write checkpoint " + tmp + ": " + why);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename checkpoint " + tmp + " to " + path + ": " + cause());
  const std::string dir = std::filesystem::path(path).parent_path().string();
  const int dfd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace

namespace {

void write_state(const CheckpointPlan& plan, const Simulation& sim, const PrepPoint& point,
                 const std::vector<StageReport>& stages, double dt_spheres,
                 const BoxTestResult& result, const CycleLoop& loop,
                 const std::vector<ClumpTemplate>& templates) {
  std::ostringstream out;
  StateWriter w(out);
  std::string magic = kMagic, build = plan.build_id, scene = plan.scene_text;
  std::string log = plan.log_text ? plan.log_text() : std::string();
  w(magic, build, scene, point, stages, dt_spheres, result, loop, templates, log);
  sim.save_state(w);
  const std::uint64_t hash = w.hash();
  out.write(reinterpret_cast<const char*>(&hash), sizeof hash);
  write_atomically(plan.path, out.str());
}

}  // namespace

void write_checkpoint(const CheckpointPlan& plan, const Simulation& sim,
                      const BoxTestResult& result, const CycleLoop& loop,
                      const std::vector<ClumpTemplate>& templates) {
  write_state(plan, sim, PrepPoint{}, {}, 0.0, result, loop, templates);
}

void write_preparation_checkpoint(const CheckpointPlan& plan, const PreparedBed& bed,
                                  const PrepPoint& point) {
  write_state(plan, bed.sim, point, bed.stages, bed.dt_spheres, BoxTestResult{}, CycleLoop{},
              bed.templates);
}

RunCheckpoint read_checkpoint(const CheckpointPlan& plan, Simulation& sim) {
  const std::string what = "checkpoint " + plan.path;
  std::ifstream in(plan.path, std::ios::binary);
  if (!in) throw SetupError("cannot read " + what + ": " + cause());
  StateReader r(in, what);
  std::string magic, build, scene;
  r(magic);
  if (magic != kMagic)
    throw SetupError(what + " is not a ballast checkpoint (or one of another format)");
  r(build, scene);
  if (build != plan.build_id)
    throw SetupError(what + " was written by build " + build + ", this is " + plan.build_id +
                     ": only the build that wrote a checkpoint resumes it bit for bit (delete "
                     "it to start the run again)");
  if (scene != plan.scene_text)
    throw SetupError(what +
                     " was written for another scene than this run's (delete it to "
                     "start the run again, or run the scene it was written for)");
  RunCheckpoint c;
  r(c.point, c.stages, c.dt_spheres, c.result, c.loop, c.templates, c.log);
  sim.load_state(r);
  const std::uint64_t expected = r.hash();
  std::uint64_t stored = 0;
  in.read(reinterpret_cast<char*>(&stored), sizeof stored);
  if (in.gcount() != sizeof stored) throw SetupError(what + " is truncated (no final hash)");
  if (stored != expected) throw SetupError(what + " is damaged (its hash does not match)");
  if (in.peek() != std::char_traits<char>::eof())
    throw SetupError(what + " is damaged (bytes after its end)");
  return c;
}

}  // namespace ballast
