// AtomicOutput: temporary file in the target folder, then rename.
#include "core/atomic_file.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "core/error.h"

namespace rc {
namespace fs = std::filesystem;

namespace {

// The temporaries being written, where a signal handler may read them: fixed buffers, since a
// handler may not allocate or follow a std::string that another thread is freeing. A slot is
// free (0), being filled (1), or holds a file's path (2) or the path of a folder made for the
// outputs (3).
struct TemporarySlot {
  std::atomic<int> state{0};
  char path[4096];
};
// The slots come in chunks. An OutputBatch holds its temporaries until it commits, so a check of
// many scenes holds many at once: when every slot is taken, registering takes another chunk,
// allocated there (never in the handler) and linked where the handler follows it. Chunks are
// kept for the process's life.
constexpr int kSlotsPerChunk = 256;
struct SlotChunk {
  TemporarySlot slots[kSlotsPerChunk];
  std::atomic<SlotChunk*> next{nullptr};
};
SlotChunk gFirstChunk;
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<SlotChunk*>::is_always_lock_free,
              "the signal handler reads the slots");

constexpr int kFileSlot = 2, kFolderSlot = 3;

// -1 for a path too long for a slot: that one is not removed on a signal.
int registerTemporary(const std::string& path, int kind = kFileSlot) {
  if (path.size() >= sizeof(TemporarySlot::path)) return -1;
  SlotChunk* chunk = &gFirstChunk;
  for (int base = 0;; base += kSlotsPerChunk) {
    for (int i = 0; i < kSlotsPerChunk; ++i) {
      TemporarySlot& slot = chunk->slots[i];
      int expected = 0;
      if (slot.state.compare_exchange_strong(expected, 1)) {
        std::memcpy(slot.path, path.c_str(), path.size() + 1);
        slot.state.store(kind);
        return base + i;
      }
    }
    SlotChunk* next = chunk->next.load();
    if (next == nullptr) {
      auto fresh = std::make_unique<SlotChunk>();
      if (chunk->next.compare_exchange_strong(next, fresh.get())) next = fresh.release();  // else another thread's
    }
    chunk = next;
  }
}

void releaseTemporary(int slot) {
  if (slot < 0) return;
  SlotChunk* chunk = &gFirstChunk;
  for (int k = slot / kSlotsPerChunk; k > 0; --k) chunk = chunk->next.load();
  chunk->slots[slot % kSlotsPerChunk].state.store(0);
}

// Calls fn(slot) for every slot of every chunk; async-signal-safe when fn is.
template <typename Fn>
void forEachSlot(Fn&& fn) {
  for (SlotChunk* chunk = &gFirstChunk; chunk != nullptr; chunk = chunk->next.load()) {
    for (TemporarySlot& slot : chunk->slots) fn(slot);
  }
}

extern "C" void removeTemporariesAndDie(int signal) {
  forEachSlot([](TemporarySlot& slot) {
    if (slot.state.load() == kFileSlot) unlink(slot.path);  // async-signal-safe
  });
  // Then the folders, emptied: a level goes once the levels below it have (a few passes, since
  // the slots need not hold them deepest first); rmdir leaves a folder that is not empty.
  for (int pass = 0; pass < 8; ++pass) {
    forEachSlot([](TemporarySlot& slot) {
      if (slot.state.load() == kFolderSlot) rmdir(slot.path);
    });
  }
  // SA_RESETHAND restored the default action: die of the same signal, as the shell expects.
  raise(signal);
}

std::atomic<OutputBatch*> gOpenBatch{nullptr};

}  // namespace

void removeTemporariesOnSignal() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    struct sigaction old {};
    if (sigaction(signal, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = removeTemporariesAndDie;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(signal, &action, nullptr);
  }
}

AtomicOutput::AtomicOutput(std::string finalPath) : finalPath_(std::move(finalPath)) {
  static std::atomic<unsigned> counter{0};
  fs::path target(finalPath_);
  fs::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw ioError(finalPath_, "cannot write: folder '" + folder.string() + "' does not exist");
  }
  const fs::file_status status = fs::status(target, ec);  // through symbolic links
  if (fs::is_directory(status)) {
    throw ioError(finalPath_, "cannot write: it is a folder");
  }
  if (fs::exists(status)) {
    // The rename would replace a file its owner made read-only: it must stay as it is.
    if (access(finalPath_.c_str(), W_OK) != 0) {
      throw ioError(finalPath_, std::string("cannot write: ") + std::strerror(errno));
    }
    if (!fs::is_regular_file(status)) {
      // A device, pipe or socket (/dev/null, /dev/stdout on a terminal, a FIFO) is written
      // straight into: renaming over it would replace the device with a file.
      tempPath_ = finalPath_;
      direct_ = true;
      return;
    }
    if (fs::is_symlink(fs::symlink_status(target, ec))) {
      // Write the file the link names, and keep the link.
      target = fs::canonical(target, ec);
      if (ec) throw ioError(finalPath_, "cannot follow the link: " + ec.message());
      folder = target.parent_path();
    }
  }
  // The temporary goes into the folder: one the user may not write fails here, before the work.
  if (access(folder.c_str(), W_OK) != 0) {
    throw ioError(finalPath_, "cannot write into folder '" + folder.string() + "': " + std::strerror(errno));
  }
  tempPath_ = (folder / ("." + target.filename().string() + ".tmp-" + std::to_string(getpid()) +
                         "-" + std::to_string(counter.fetch_add(1))))
                  .string();
  renameTo_ = target.string();
  signalSlot_ = registerTemporary(tempPath_);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_ && !direct_) std::remove(tempPath_.c_str());
  releaseTemporary(signalSlot_);
}

void AtomicOutput::commit() {
  if (OutputBatch* batch = gOpenBatch.load(); batch && !direct_) {
    batch->adopt({tempPath_, renameTo_, finalPath_, signalSlot_});  // the batch owns the temporary now
    committed_ = true;
    signalSlot_ = -1;
    return;
  }
  if (!direct_ && std::rename(tempPath_.c_str(), renameTo_.c_str()) != 0) {
    int err = errno;
    std::remove(tempPath_.c_str());
    throw ioError(finalPath_, std::string("cannot write: ") + std::strerror(err));
  }
  committed_ = true;
  releaseTemporary(signalSlot_);
  signalSlot_ = -1;
}

OutputBatch::OutputBatch() {
  OutputBatch* none = nullptr;
  if (!gOpenBatch.compare_exchange_strong(none, this)) throw std::logic_error("an OutputBatch is already open");
}

void OutputBatch::adopt(Finished finished) {
  const std::lock_guard<std::mutex> lock(mutex_);
  finished_.push_back(std::move(finished));
}

void OutputBatch::addFolder(const std::string& path) {
  const std::lock_guard<std::mutex> lock(mutex_);
  folders_.push_back({path, registerTemporary(path, kFolderSlot)});
}

void OutputBatch::commit() {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t i = 0; i < finished_.size(); ++i) {
    const Finished& f = finished_[i];
    if (std::rename(f.temp.c_str(), f.target.c_str()) != 0) {
      const Error error = ioError(f.finalPath, std::string("cannot write: ") + std::strerror(errno));
      finished_.erase(finished_.begin(), finished_.begin() + std::ptrdiff_t(i));  // in place: keep them (f moves)
      throw error;
    }
    releaseTemporary(f.signalSlot);
  }
  finished_.clear();
  for (const auto& folder : folders_) releaseTemporary(folder.second);
  folders_.clear();
  close();
}

void OutputBatch::discard() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const Finished& f : finished_) {
      std::remove(f.temp.c_str());
      releaseTemporary(f.signalSlot);
    }
    finished_.clear();
    std::error_code ec;
    for (const auto& folder : folders_) {
      fs::remove(folder.first, ec);  // only if empty
      releaseTemporary(folder.second);
    }
    folders_.clear();
  }
  close();
}

void OutputBatch::close() {
  OutputBatch* self = this;
  gOpenBatch.compare_exchange_strong(self, nullptr);  // later outputs are renamed at once
}

void writeTextFile(const std::string& path, const std::string& content) {
  AtomicOutput out(path);
  {
    std::ofstream stream(out.tempPath(), std::ios::binary | std::ios::trunc);
    if (!stream) throw ioError(path, std::string("cannot write: ") + std::strerror(errno));
    stream << content;
    stream.flush();
    if (!stream) throw ioError(path, "write failed (disk full?)");
  }
  out.commit();
}

}  // namespace rc
