#include <cutroute/io/output_file.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <utility>

namespace cutroute::io {

namespace {

namespace fs = std::filesystem;

// A fresh temporary file in the folder of `target`, named apart from it (the target's own name
// may already be as long as a name can be).
std::string temp_name(const fs::path& target) {
  static std::atomic<unsigned long> counter{0};
  return (target.parent_path() / (".cutroute-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".tmp")).string();
}

// The temporary files that may exist right now, for remove_temp_files() in a signal handler:
// fixed slots a handler can read at any moment (no allocation, no lock). A batch has at most
// four outputs per sheet in flight on each core; a name that finds no free slot (or is longer
// than a path can be) is written all the same, only not removed by a hard stop.
struct TempSlot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 names a file that may exist
  char path[4096];
};
TempSlot temp_slots[64];

// Holds a temporary file's name in a slot from before the file is made until it is renamed or
// removed (a name whose file does not exist yet or any more costs the handler one failed unlink).
class TempEntry {
 public:
  explicit TempEntry(const std::string& path) {
    if (path.size() >= sizeof(TempSlot::path)) return;
    for (TempSlot& s : temp_slots) {
      int free = 0;
      if (!s.state.compare_exchange_strong(free, 1)) continue;
      std::memcpy(s.path, path.c_str(), path.size() + 1);
      s.state.store(2);
      slot_ = &s;
      return;
    }
  }
  TempEntry(const TempEntry&) = delete;
  TempEntry& operator=(const TempEntry&) = delete;
  TempEntry(TempEntry&& o) noexcept : slot_(std::exchange(o.slot_, nullptr)) {}
  TempEntry& operator=(TempEntry&& o) noexcept {
    std::swap(slot_, o.slot_);
    return *this;
  }
  ~TempEntry() {
    if (slot_ != nullptr) slot_->state.store(0);
  }

 private:
  TempSlot* slot_ = nullptr;
};

// Where an output really goes: a symbolic link is followed (the link stays; its target gets the
// new content), and a device, FIFO or socket is written in place: renaming a file over it would
// replace it (as root, `-o /dev/null` would turn /dev/null into a file).
struct Target {
  fs::path path;
  bool in_place = false;
};

Result<Target> resolve(const std::string& path) {
  Target t{path, false};
  std::error_code ec;  // a path that does not exist yet is no error: status() says not_found
  // Link by link: weakly_canonical() leaves a link to a file not written yet unresolved.
  for (int hops = 0; fs::is_symlink(fs::symlink_status(t.path, ec)); ++hops) {
    const fs::path to = fs::read_symlink(t.path, ec);
    if (ec || hops == 40) return make_error("cannot write output: " + (ec ? ec.message() : std::string("too many links")), path);
    t.path = to.is_absolute() ? to : t.path.parent_path() / to;
  }
  const fs::file_status st = fs::status(t.path, ec);
  if (fs::is_directory(st)) return make_error("cannot write output: is a folder", path);
  t.in_place = fs::exists(st) && !fs::is_regular_file(st);
  return t;
}

// Writes the whole content to `file`; on failure nothing is left there (unless in place).
Status write_to(const std::string& file, const std::string& path, std::string_view content, bool in_place) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) return make_error("cannot write output: " + std::string(std::strerror(errno)), path);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.flush();
  if (!out) {
    out.close();
    std::error_code ec;
    if (!in_place) fs::remove(file, ec);
    return make_error("writing output failed (disk full?)", path);
  }
  return Ok{};
}

Status move_into_place(const std::string& tmp, const fs::path& target, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();  // before remove() overwrites ec ("Success")
    fs::remove(tmp, ec);
    return make_error("cannot move the finished output into place: " + why, path);
  }
  return Ok{};
}

// A pipe into a full disk or a closed reader must fail the run: the program would be cut short
// with a success exit.
Status to_stdout(std::string_view content) {
  std::cout.write(content.data(), static_cast<std::streamsize>(content.size()));
  std::cout.flush();
  if (!std::cout) return make_error("writing the output to standard output failed (disk full, or the reader closed?)", "-");
  return Ok{};
}

}  // namespace

Status write_files_atomic(const std::vector<OutputFile>& files) {
  std::vector<Target> targets(files.size());
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (files[k].path == "-") continue;
    auto t = resolve(files[k].path);
    if (!t) return t.error();
    targets[k] = std::move(*t);
  }
  std::vector<std::string> tmps(files.size());
  std::vector<TempEntry> live;  // released (after the renames or removals) when this returns
  live.reserve(files.size());
  auto drop = [&](std::size_t from) {
    std::error_code ec;
    for (std::size_t k = from; k < files.size(); ++k)
      if (!tmps[k].empty()) fs::remove(tmps[k], ec);
  };
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (files[k].path == "-" || targets[k].in_place) continue;
    const std::string tmp = temp_name(targets[k].path);
    live.emplace_back(tmp);
    if (Status st = write_to(tmp, files[k].path, files[k].content, false); !st) {
      drop(0);
      return st;
    }
    tmps[k] = tmp;
  }
  {
    // Renames take microseconds; a write in place (a FIFO nobody reads) may block, and a second
    // Ctrl-C must still end that.
    std::optional<CommitGuard> commit;
    if (std::none_of(targets.begin(), targets.end(), [](const Target& t) { return t.in_place; })) commit.emplace();
    for (std::size_t k = 0; k < files.size(); ++k) {
      Status st = Ok{};
      if (!tmps[k].empty()) st = move_into_place(tmps[k], targets[k].path, files[k].path);
      else if (targets[k].in_place) st = write_to(targets[k].path.string(), files[k].path, files[k].content, true);
      if (!st) {
        drop(k + 1);
        return st;
      }
    }
  }
  for (const auto& f : files)
    if (f.path == "-")
      if (Status st = to_stdout(f.content); !st) return st;
  return Ok{};
}

Status check_output(const std::string& path) {
  if (path == "-") return Ok{};
  auto t = resolve(path);
  if (!t) return t.error();
  if (t->in_place) return Ok{};
  const std::string tmp = temp_name(t->path);
  const TempEntry live(tmp);
  if (Status st = write_to(tmp, path, {}, false); !st) return st;
  std::error_code ec;
  fs::remove(tmp, ec);
  return Ok{};
}

void remove_temp_files() noexcept {
  for (TempSlot& s : temp_slots)
    if (s.state.load() == 2) ::unlink(s.path);
}

namespace {
std::atomic<int> committing{0};       // output sets being renamed into place
std::atomic<int> deferred_signal{0};  // a signal that would have ended the process meanwhile
}  // namespace

bool defer_signal_while_committing(int sig) noexcept {
  if (committing.load() == 0) return false;
  deferred_signal.store(sig);
  // The last commit may have ended between the two lines above without seeing the signal: then it
  // is the handler's again.
  return !(committing.load() == 0 && deferred_signal.exchange(0) != 0);
}

CommitGuard::CommitGuard() noexcept { committing.fetch_add(1); }

CommitGuard::~CommitGuard() {
  if (committing.fetch_sub(1) != 1) return;
  if (const int sig = deferred_signal.exchange(0); sig != 0) {
    remove_temp_files();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

bool same_output(const std::string& a, const std::string& b) {
  if (a == "-" || b == "-") return a == b;
  // Two names of one existing file (a hard link, a symbolic link) are one output.
  std::error_code ee;
  if (fs::equivalent(a, b, ee) && !ee) return true;
  std::error_code ea, eb;
  const fs::path pa = fs::weakly_canonical(fs::absolute(a, ea), ea), pb = fs::weakly_canonical(fs::absolute(b, eb), eb);
  return ea || eb ? a == b : pa == pb;
}

Status write_file_atomic(const std::string& path, std::string_view content) {
  return write_files_atomic({{path, std::string(content)}});
}

}  // namespace cutroute::io
