// Replace-by-rename: readers of the target see either the old file or the complete new
// one, and a failed write (full disk, bad directory) leaves the old file as it was.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "image/image_formats.h"
#include "util/error.h"

namespace ps::imageio {

void writeFileAtomically(const std::string& path, const std::vector<char>& bytes) {
    // pid + counter: unique across processes and across threads writing the same target.
    static std::atomic<unsigned> counter{0};
    const std::string tmp = path + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(counter++);
    auto fail = [&](int err, bool removeTmp) {
        if (removeTmp) ::unlink(tmp.c_str());
        throw InputError(path + ": cannot write image: " + std::strerror(err));
    };

    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) fail(errno, false);
    const char* p = bytes.data();
    size_t left = bytes.size();
    while (left > 0) {
        ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            int err = n < 0 ? errno : EIO;
            ::close(fd);
            fail(err, true);
        }
        p += n;
        left -= size_t(n);
    }
    // Data on disk before the rename, or a crash could leave an empty file under the new name.
    if (::fsync(fd) != 0) {
        int err = errno;
        ::close(fd);
        fail(err, true);
    }
    if (::close(fd) != 0) fail(errno, true);
    if (std::rename(tmp.c_str(), path.c_str()) != 0) fail(errno, true);
}

}  // namespace ps::imageio
