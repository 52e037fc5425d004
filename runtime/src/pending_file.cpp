#include "luxel/runtime/pending_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <system_error>

#include "luxel/runtime/error.hpp"

namespace luxel {
namespace {

std::string errno_text() {
    return std::strerror(errno);
}

}  // namespace

PendingFile::PendingFile(std::filesystem::path target) : target_(std::move(target)) {
    std::random_device random;
    const std::string name = "." + target_.filename().string() + "." + std::to_string(random()) +
                             std::to_string(::getpid()) + ".tmp";
    temporary_ = target_.parent_path() / name;
}

PendingFile::~PendingFile() {
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove(temporary_, ignored);
    }
}

void PendingFile::commit() {
    // fsync before rename: otherwise a power cut can leave the new name with no data yet.
    const int fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        throw Error(target_.string() + ": cannot write: the temporary file " + temporary_.string() +
                    " is gone: " + errno_text());
    }
    const bool synced = ::fsync(fd) == 0;
    const std::string sync_error = synced ? std::string() : errno_text();
    ::close(fd);
    if (!synced) {
        throw Error(target_.string() + ": cannot write: " + sync_error);
    }
    if (std::rename(temporary_.c_str(), target_.c_str()) != 0) {
        throw Error(target_.string() + ": cannot replace: " + errno_text());
    }
    committed_ = true;
}

void write_file_atomically(const std::filesystem::path& file, std::span<const std::byte> bytes) {
    PendingFile pending(file);
    std::FILE* stream = std::fopen(pending.path().c_str(), "wb");
    if (stream == nullptr) {
        throw Error(file.string() + ": cannot open for writing: " + errno_text());
    }
    const std::size_t written =
        bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), stream);
    const bool ok = written == bytes.size() && std::fflush(stream) == 0;
    const std::string write_error = ok ? std::string() : errno_text();
    if (std::fclose(stream) != 0 || !ok) {
        throw Error(file.string() +
                    ": cannot write: " + (write_error.empty() ? errno_text() : write_error));
    }
    pending.commit();
}

}  // namespace luxel
