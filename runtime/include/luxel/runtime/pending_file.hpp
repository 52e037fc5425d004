#pragma once

// Files that appear whole or not at all. A writer writes to a temporary file beside the target
// and renames it into place when done: rename within one folder is atomic on POSIX, so Ctrl-C,
// a crash or a full disk half-way leaves the previous file (or none) where a good one was, never
// a truncated one.

#include <cstddef>
#include <filesystem>
#include <span>

namespace luxel {

/// A temporary file beside `target` ("<dir>/.<name>.<random>.tmp"), renamed over the target by
/// commit() and removed by the destructor if commit() never ran.
class PendingFile {
  public:
    explicit PendingFile(std::filesystem::path target);
    ~PendingFile();
    PendingFile(const PendingFile&) = delete;
    PendingFile& operator=(const PendingFile&) = delete;

    /// Where the writer writes (a path: for libraries that open the file themselves).
    [[nodiscard]] const std::filesystem::path& path() const { return temporary_; }
    [[nodiscard]] const std::filesystem::path& target() const { return target_; }
    /// Flushes the temporary file to disk and renames it over the target. Throws luxel::Error
    /// naming the target.
    void commit();

  private:
    std::filesystem::path target_;
    std::filesystem::path temporary_;
    bool committed_ = false;
};

/// Writes `bytes` to `file` through a PendingFile. Throws luxel::Error naming the file.
void write_file_atomically(const std::filesystem::path& file, std::span<const std::byte> bytes);

}  // namespace luxel
