#pragma once
// Writing a whole file so that a reader sees the old contents or the new ones, never half of
// them (docs/architecture.md, "Writers write a temporary file and rename it").
//
// The contents go to a temporary file in the target's own folder (a rename is atomic only
// within one file system), `.<name>.tmp-<pid>-<n>`, which is flushed to the disk (fsync) and then
// renamed over the target. On any failure the temporary file is removed and the target is left as
// it was. A crash between the two leaves at most a stray `.<name>.tmp-…` beside a whole target.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace af {

struct WriteResult {
    std::string error;  // empty on success; otherwise names the path and the system's reason

    bool ok() const { return error.empty(); }
};

// The points at which a test can make writeFileAtomically fail.
enum class WriteStage {
    Opened,    // the temporary file exists and is empty
    Wrote,     // after each chunk of at most kAtomicWriteChunk bytes reached the temporary file
    Synced,    // the temporary file is whole and on the disk
    Renaming,  // just before the rename
};

// What the hook asks for at a stage.
enum class WriteFault {
    None,   // carry on
    Fail,   // fail here as an I/O error would: clean up and report
    Crash,  // stop here as if the process had died: return an error, clean up nothing
};

// Called at each stage with the number of bytes written so far. For tests only; production
// callers pass none.
using WriteFaultHook = std::function<WriteFault(WriteStage stage, std::size_t bytesWritten)>;

// Contents are written in chunks of this size, so that a hook can stop a write part way.
inline constexpr std::size_t kAtomicWriteChunk = 64 * 1024;

// Replaces `target` with `contents` through a temporary file and a rename. A target that exists
// keeps its permission bits; a new one gets 0666 less the umask, as an ordinary write would.
// A symbolic link as target is replaced by the file, not followed.
WriteResult writeFileAtomically(const std::filesystem::path& target, std::string_view contents,
                                const WriteFaultHook& hook = {});

}  // namespace af
