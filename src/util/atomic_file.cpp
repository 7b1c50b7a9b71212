#include "util/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "util/error.h"

namespace ps {

void writeFileAtomically(const std::string& path, std::initializer_list<std::span<const char>> parts,
                         const std::string& what) {
    // pid + counter: unique across processes and across threads writing the same target.
    static std::atomic<unsigned> counter{0};
    const std::string tmp = path + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    auto fail = [&](int err, bool removeTmp) {
        if (removeTmp) ::unlink(tmp.c_str());
        throw InputError(path + ": cannot write " + what + ": " + std::strerror(err));
    };

    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) fail(errno, false);
    for (std::span<const char> part : parts) {
        const char* p = part.data();
        size_t left = part.size();
        while (left > 0) {
            ssize_t n = ::write(fd, p, left);
            if (n < 0 && errno == EINTR) continue;  // a Ctrl-C while writing
            if (n <= 0) {
                int err = n < 0 ? errno : EIO;
                ::close(fd);
                fail(err, true);
            }
            p += n;
            left -= size_t(n);
        }
    }
    // Data on disk before the rename, or a crash could leave an empty file under the new name.
    if (::fsync(fd) != 0) {
        int err = errno;
        ::close(fd);
        fail(err, true);
    }
    if (::close(fd) != 0) fail(errno, true);
    if (std::rename(tmp.c_str(), path.c_str()) != 0) fail(errno, true);
    // The rename itself is durable once the directory is flushed (best effort).
    const std::filesystem::path file(path);
    const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
}

}  // namespace ps
