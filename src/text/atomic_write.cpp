// Writing a file through a temporary file and a rename (docs/architecture.md, "Writers write a
// temporary file and rename it"). POSIX calls rather than streams: fsync needs the descriptor,
// and each step's errno makes the message say why it failed.

#include "af/text/atomic_write.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <optional>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace af {

namespace {

// Unique among the writes of this process (the counter) and of other processes (the pid); the
// leading dot keeps it out of ordinary folder listings and of globs such as *.map.
std::filesystem::path temporaryBeside(const std::filesystem::path& target) {
    static std::atomic<unsigned long> counter{0};
    const std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter.fetch_add(1));
    return target.parent_path() / name;
}

const char* stageName(WriteStage stage) {
    switch (stage) {
    case WriteStage::Opened: return "after opening";
    case WriteStage::Wrote: return "while writing";
    case WriteStage::Synced: return "after syncing";
    case WriteStage::Renaming: return "before renaming";
    }
    return "";
}

class AtomicWrite {
public:
    AtomicWrite(const std::filesystem::path& target, const WriteFaultHook& hook)
        : target_(target), temporary_(temporaryBeside(target)), hook_(hook) {}

    WriteResult run(std::string_view contents) {
        // A rewritten file keeps its permissions; only a regular file has any worth keeping.
        struct stat existing {};
        const bool keepMode = ::stat(target_.c_str(), &existing) == 0 && S_ISREG(existing.st_mode);

        fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ < 0) return failed("creating", errno);
        created_ = true;
        if (keepMode && ::fchmod(fd_, existing.st_mode & 07777) != 0) return failed("setting the mode of", errno);
        if (const auto injected = inject(WriteStage::Opened, 0)) return *injected;

        std::size_t written = 0;
        while (written < contents.size()) {
            const std::size_t chunk = std::min(kAtomicWriteChunk, contents.size() - written);
            const ssize_t n = ::write(fd_, contents.data() + written, chunk);
            if (n < 0) {
                if (errno == EINTR) continue;
                return failed("writing", errno);
            }
            written += static_cast<std::size_t>(n);
            if (const auto injected = inject(WriteStage::Wrote, written)) return *injected;
        }
        if (::fsync(fd_) != 0) return failed("syncing", errno);
        if (const auto injected = inject(WriteStage::Synced, written)) return *injected;
        const int closed = ::close(fd_);
        fd_ = -1;
        if (closed != 0) return failed("closing", errno);
        if (const auto injected = inject(WriteStage::Renaming, written)) return *injected;
        if (::rename(temporary_.c_str(), target_.c_str()) != 0) return failed("renaming into place", errno);
        return {};
    }

private:
    // The hook's answer at `stage`: nothing to carry on, or the result to return.
    std::optional<WriteResult> inject(WriteStage stage, std::size_t written) {
        const WriteFault fault = hook_ ? hook_(stage, written) : WriteFault::None;
        if (fault == WriteFault::None) return std::nullopt;
        if (fault == WriteFault::Fail) return failed(std::string("injected failure ") + stageName(stage), EIO);
        // A crash: the system closes the descriptor of a dead process, and nothing else happens.
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
        return WriteResult{"cannot write " + target_.string() + ": simulated crash " + stageName(stage) + " " +
                           temporary_.string()};
    }

    WriteResult failed(const std::string& step, int error) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
        // The target has not been touched: removing the temporary file undoes everything.
        if (created_) ::unlink(temporary_.c_str());
        return {"cannot write " + target_.string() + ": " + step + " " + temporary_.string() + ": " +
                std::generic_category().message(error)};
    }

    const std::filesystem::path& target_;
    const std::filesystem::path temporary_;
    const WriteFaultHook& hook_;
    int fd_ = -1;
    bool created_ = false;
};

}  // namespace

WriteResult writeFileAtomically(const std::filesystem::path& target, std::string_view contents,
                                const WriteFaultHook& hook) {
    if (!target.has_filename()) return {"cannot write " + target.string() + ": not a file name"};
    return AtomicWrite(target, hook).run(contents);
}

}  // namespace af
