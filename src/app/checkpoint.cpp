// Checkpoints of a run (checkpoint.hpp). A checkpoint file is a fixed magic line, the payload's length, the
// payload (a StateArchive) and its FNV-1a checksum, so that a file cut off by a crash or a full disk is
// recognised and the previous checkpoint used instead.
#include "checkpoint.hpp"

#include <lagfsi/output_file.hpp>

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace lagfsi {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[16] = "LAGFSI-CKPT-v1\n";

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

std::string hex(std::uint64_t h) {
  std::ostringstream o;
  o << std::hex << h;
  return o.str();
}

void serialize_phases(StateArchive& ar, PhaseTimes& p) {
  ar.io(p.remesh, p.assembly, p.factorization, p.solve, p.output);
}

/// Writes all of `s` to `fd`; 0 or the errno.
int write_all(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    done += static_cast<size_t>(n);
  }
  return 0;
}

const KeyTable kCheckpointKeys(
    "/output/checkpoint",
    "Checkpoints for `lagfsi run --restart`: OUTDIR/checkpoint.bin, written atomically, and when a signal ends a run.",
    {{"every_steps", 0, "Write a checkpoint every this many steps (0: not by steps)."},
     {"every_minutes", 0.0, "Write a checkpoint every this many minutes of wall time (0: not by time)."},
     {"keep", 2, "1: the last checkpoint only; 2: also the one before, as checkpoint.prev.bin."}});

}  // namespace

CheckpointSettings read_checkpoint_settings(Params p) {
  if (!p.json().is_object()) p.fail("expected an object, e.g. {\"every_steps\": 100} or {\"every_minutes\": 10}");
  p.validate(kCheckpointKeys);
  CheckpointSettings s;
  s.every_steps = p.integer("every_steps", 0);
  s.every_minutes = p.non_negative("every_minutes");
  s.keep = p.integer("keep", 1);
  if (s.keep > 2) p.fail("keep", "must be 1 or 2 (the last checkpoint, or also the one before)");
  return s;
}

std::uint64_t case_hash(const Json& resolved_case) {
  Json j = resolved_case;
  if (j.contains("output") && j["output"].is_object()) j["output"].erase("checkpoint");
  return fnv1a(j.dump(-1, ' ', false, Json::error_handler_t::replace));
}

void serialize_run_head(StateArchive& ar, RunPosition& pos, RunTotals& tot, const fs::path& case_file) {
  ar.section("run");
  const std::uint64_t expected = pos.case_hash;
  ar.io(pos.case_hash);
  if (ar.loading() && pos.case_hash != expected)
    throw InputError(case_file.string(), "",
                     "--restart: the case differs from the checkpointed one (resolved case " + hex(expected) +
                         ", checkpoint " + hex(pos.case_hash) +
                         "): give the same case file and --set options, or run without --restart");
  ar.io(pos.step, pos.t, pos.last_output_t, pos.probes_bytes, pos.log_bytes, pos.threads);
  ar.section("totals");
  serialize_phases(ar, tot.phases);
  std::uint64_t nb = tot.body_phases.size();
  ar.io(nb);
  if (ar.loading()) tot.body_phases.resize(nb);
  for (PhaseTimes& p : tot.body_phases) serialize_phases(ar, p);
  ar.io(tot.iterations, tot.retries, tot.max_iterations, tot.steps, tot.labelled, tot.wall_before);
  ar.io(tot.last_dt, tot.dt_by, tot.dt_by_steps, tot.dt_min, tot.dt_max);
}

void serialize_run_models(StateArchive& ar, const std::vector<PhysicsModel*>& models,
                          const std::vector<Probe*>& probes) {
  std::uint64_t nm = models.size(), np = probes.size();
  ar.io(nm, np);
  if (ar.loading() && (nm != models.size() || np != probes.size()))
    throw CheckpointError("it holds " + std::to_string(nm) + " bodies and couplings and " + std::to_string(np) +
                          " probes, the case " + std::to_string(models.size()) + " and " +
                          std::to_string(probes.size()));
  for (PhysicsModel* m : models) {
    ar.section("model " + m->name());
    m->serialize(ar);
  }
  for (size_t i = 0; i < probes.size(); ++i) {
    ar.section("probe " + std::to_string(i));
    probes[i]->serialize(ar);
  }
  ar.section("end");
  if (ar.loading() && !ar.at_end()) throw CheckpointError("it holds more than the case's state");
}

void write_checkpoint(const fs::path& dir, const std::string& payload, int keep) {
  const fs::path file = dir / kCheckpointFile, tmp = dir / (std::string(kCheckpointFile) + ".tmp");
  std::string bytes(kMagic, sizeof kMagic);
  std::uint64_t n = payload.size(), h = fnv1a(payload);
  bytes.append(reinterpret_cast<const char*>(&n), sizeof n);
  bytes += payload;
  bytes.append(reinterpret_cast<const char*>(&h), sizeof h);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError(file.string(), errno_reason(errno));
  int err = write_all(fd, bytes);
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    throw OutputError(file.string(), errno_reason(err));
  }
  std::error_code ec;
  if (keep >= 2 && fs::exists(file)) fs::rename(file, dir / kCheckpointPrevFile, ec);
  if (!ec) fs::rename(tmp, file, ec);
  if (ec) {
    ::unlink(tmp.c_str());
    throw OutputError(file.string(), ec.message());
  }
  if (keep < 2) fs::remove(dir / kCheckpointPrevFile, ec);
  // The renames reach the disk with the folder.
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

std::string read_checkpoint(const fs::path& dir, const fs::path& case_file) {
  std::string why;
  for (const char* name : {kCheckpointFile, kCheckpointPrevFile}) {
    const fs::path file = dir / name;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) continue;
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::uint64_t n = 0, h = 0;
    const size_t head = sizeof kMagic + sizeof n;
    if (bytes.size() < head + sizeof h || bytes.compare(0, sizeof kMagic, std::string(kMagic, sizeof kMagic)) != 0) {
      why = file.string() + " is not a lagfsi checkpoint";
      continue;
    }
    std::memcpy(&n, bytes.data() + sizeof kMagic, sizeof n);
    if (bytes.size() != head + n + sizeof h) {
      why = file.string() + " is cut off";
      continue;
    }
    std::memcpy(&h, bytes.data() + head + n, sizeof h);
    std::string payload = bytes.substr(head, n);
    if (fnv1a(payload) != h) {
      why = file.string() + " is damaged (checksum)";
      continue;
    }
    return payload;
  }
  throw InputError(case_file.string(), "",
                   "--restart: no checkpoint in " + dir.string() +
                       (why.empty() ? " (the run needs \"output\": {\"checkpoint\": {\"every_steps\": N}} or "
                                      "\"every_minutes\")"
                                    : " (" + why + ")"));
}

void check_checkpointable(const std::vector<PhysicsModel*>& models, const Params& output, bool restart,
                          const fs::path& case_file) {
  for (const PhysicsModel* m : models)
    if (!m->can_checkpoint()) {
      const std::string why =
          "body '" + m->name() + "' (" + m->type() +
          ") cannot be checkpointed in this version (solids, shells, fluids, MPM, DEM and EFG bodies and "
          "their couplings can)";
      if (restart) throw InputError(case_file.string(), "", "--restart: " + why);
      output.fail("checkpoint", why);
    }
}

void save_checkpoint(const fs::path& dir, int keep, RunPosition& pos, const RunTotals& tot,
                     const std::vector<PhysicsModel*>& models, const std::vector<Probe*>& probes,
                     const fs::path& case_file) {
  RunTotals saved = tot;
  StateArchive ar;
  serialize_run_head(ar, pos, saved, case_file);
  serialize_run_models(ar, models, probes);
  write_checkpoint(dir, ar.data(), keep);
}

StateArchive open_restart(const fs::path& dir, RunPosition& pos, RunTotals& tot, const fs::path& case_file) {
  StateArchive ar(read_checkpoint(dir, case_file));
  try {
    serialize_run_head(ar, pos, tot, case_file);
  } catch (const CheckpointError& e) {
    throw InputError(case_file.string(), "",
                     "--restart: the checkpoint in " + dir.string() + " cannot be read (" + e.what() + ")");
  }
  for (const auto& [file, bytes] : {std::pair{"probes.csv", pos.probes_bytes}, std::pair{"log.csv", pos.log_bytes}}) {
    std::error_code ec;
    const auto size = fs::file_size(dir / file, ec);
    if (ec || size < bytes)
      throw InputError(
          case_file.string(), "",
          "--restart: " + (dir / file).string() + " is " + (ec ? "missing" : "shorter than at the checkpoint"));
  }
  return ar;
}

}  // namespace lagfsi
