// writeFileAtomically: a target holds its old contents or its new ones, never part of either, and
// no temporary file is left behind, whatever stage a write fails at.

#include "af/text/atomic_write.h"
#include "text/text_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

namespace af {
namespace {

namespace fs = std::filesystem;

// Each test works in a fresh empty folder of its own, removed afterwards.
class AtomicWrite : public ::testing::Test {
protected:
    void SetUp() override {
        fs::remove_all(root_);
        fs::create_directories(root_);
    }
    void TearDown() override {
        fs::remove_all(root_);
    }
    // A new empty folder; a test that loops over cases takes one per case.
    fs::path scratchFolder() {
        const fs::path folder = root_ / std::to_string(folders_++);
        fs::create_directories(folder);
        return folder;
    }

private:
    const fs::path root_ = fs::temp_directory_path() / ("af_atomic_write_" + std::to_string(::getpid()));
    int folders_ = 0;
};

std::vector<std::string> listing(const fs::path& folder) {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(folder)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

std::string contentsOf(const fs::path& file) { return readWholeFile(file.string()).value_or("<unreadable>"); }

// Enough bytes for three chunks, so that a write can stop part way through.
std::string largeContents() {
    std::string text;
    for (int i = 0; text.size() < 2 * kAtomicWriteChunk + 100; ++i) text += "line " + std::to_string(i) + "\n";
    return text;
}

TEST_F(AtomicWrite, WritesANewFile) {
    const fs::path folder = scratchFolder(), target = folder / "new.map";
    const WriteResult r = writeFileAtomically(target, "Version 2\n");
    EXPECT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(contentsOf(target), "Version 2\n");
    EXPECT_EQ(listing(folder), std::vector<std::string>{"new.map"});
}

TEST_F(AtomicWrite, ReplacesAnOldFileAndKeepsItsMode) {
    const fs::path folder = scratchFolder(), target = folder / "old.map";
    ASSERT_TRUE(writeFileAtomically(target, "old contents that are longer\n").ok());
    fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
    const std::string big = largeContents();
    const WriteResult r = writeFileAtomically(target, big);
    EXPECT_TRUE(r.ok()) << r.error;
    EXPECT_EQ(contentsOf(target), big);
    EXPECT_EQ(fs::status(target).permissions() & fs::perms::all,
              fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
    EXPECT_EQ(listing(folder), std::vector<std::string>{"old.map"});
}

TEST_F(AtomicWrite, WritesAnEmptyFile) {
    const fs::path folder = scratchFolder(), target = folder / "empty.txt";
    ASSERT_TRUE(writeFileAtomically(target, "something").ok());
    EXPECT_TRUE(writeFileAtomically(target, "").ok());
    EXPECT_EQ(fs::file_size(target), 0u);
}

TEST_F(AtomicWrite, AMissingFolderIsAnErrorNamingThePathAndTheReason) {
    const fs::path folder = scratchFolder(), target = folder / "missing" / "x.map";
    const WriteResult r = writeFileAtomically(target, "text");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error.find("cannot write " + target.string()), std::string::npos) << r.error;
    EXPECT_NE(r.error.find("No such file or directory"), std::string::npos) << r.error;
    EXPECT_TRUE(listing(folder).empty());
}

TEST_F(AtomicWrite, AFolderThatIsAFileIsAnErrorAndChangesNothing) {
    const fs::path folder = scratchFolder(), notAFolder = folder / "plain";
    ASSERT_TRUE(writeFileAtomically(notAFolder, "plain file\n").ok());
    const WriteResult r = writeFileAtomically(notAFolder / "x.map", "text");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error.find("Not a directory"), std::string::npos) << r.error;
    EXPECT_EQ(contentsOf(notAFolder), "plain file\n");
    EXPECT_EQ(listing(folder), std::vector<std::string>{"plain"});
}

TEST_F(AtomicWrite, AReadOnlyFolderIsAnErrorAndTheOldFileStays) {
    if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders";
    const fs::path folder = scratchFolder(), target = folder / "old.map";
    ASSERT_TRUE(writeFileAtomically(target, "old\n").ok());
    fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
    const WriteResult r = writeFileAtomically(target, "new\n");
    fs::permissions(folder, fs::perms::owner_all);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error.find("Permission denied"), std::string::npos) << r.error;
    EXPECT_EQ(contentsOf(target), "old\n");
    EXPECT_EQ(listing(folder), std::vector<std::string>{"old.map"});
}

// A real failure at the last step: a folder of the target's name cannot be replaced by a file.
TEST_F(AtomicWrite, AFailedRenameRemovesTheTemporaryFile) {
    const fs::path folder = scratchFolder(), target = folder / "taken";
    fs::create_directories(target / "inside");
    const WriteResult r = writeFileAtomically(target, "text");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error.find("renaming into place"), std::string::npos) << r.error;
    EXPECT_EQ(listing(folder), std::vector<std::string>{"taken"});
    EXPECT_TRUE(fs::is_directory(target / "inside"));
}

// Each stage a write can fail at; Wrote at the first chunk, so the temporary file is partial.
struct Stop {
    WriteStage stage;
    std::size_t afterBytes;
};

const Stop kStops[] = {{WriteStage::Opened, 0},
                       {WriteStage::Wrote, kAtomicWriteChunk},
                       {WriteStage::Wrote, 2 * kAtomicWriteChunk},
                       {WriteStage::Synced, 0},
                       {WriteStage::Renaming, 0}};

WriteFaultHook faultAt(const Stop& stop, WriteFault fault) {
    return [stop, fault](WriteStage stage, std::size_t written) {
        const bool here = stage == stop.stage && (stage != WriteStage::Wrote || written == stop.afterBytes);
        return here ? fault : WriteFault::None;
    };
}

TEST_F(AtomicWrite, AFailureAtAnyStageLeavesTheOldFileWholeAndNoTemporaryFile) {
    const std::string big = largeContents();
    for (const Stop& stop : kStops) {
        const fs::path folder = scratchFolder(), target = folder / "pose.map";
        ASSERT_TRUE(writeFileAtomically(target, "old\n").ok());
        const WriteResult r = writeFileAtomically(target, big, faultAt(stop, WriteFault::Fail));
        SCOPED_TRACE(r.error);
        EXPECT_FALSE(r.ok());
        EXPECT_NE(r.error.find("injected failure"), std::string::npos);
        EXPECT_EQ(contentsOf(target), "old\n");
        EXPECT_EQ(listing(folder), std::vector<std::string>{"pose.map"});
    }
}

TEST_F(AtomicWrite, ACrashAtAnyStageLeavesTheOldFileWhole) {
    const std::string big = largeContents();
    for (const Stop& stop : kStops) {
        const fs::path folder = scratchFolder(), target = folder / "pose.map";
        ASSERT_TRUE(writeFileAtomically(target, "old\n").ok());
        const WriteResult r = writeFileAtomically(target, big, faultAt(stop, WriteFault::Crash));
        SCOPED_TRACE(r.error);
        EXPECT_FALSE(r.ok());
        EXPECT_EQ(contentsOf(target), "old\n");
        // The dead process leaves its temporary file, named as promised, beside the old file.
        const std::vector<std::string> names = listing(folder);
        ASSERT_EQ(names.size(), 2u);
        EXPECT_EQ(names[0].rfind(".pose.map.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << names[0];
        EXPECT_EQ(names[1], "pose.map");
        // A later write succeeds beside the leftover.
        EXPECT_TRUE(writeFileAtomically(target, "new\n").ok());
        EXPECT_EQ(contentsOf(target), "new\n");
    }
}

TEST_F(AtomicWrite, TheHookSeesEveryStageInOrder) {
    const fs::path folder = scratchFolder();
    std::vector<std::pair<WriteStage, std::size_t>> seen;
    const std::string big = largeContents();
    ASSERT_TRUE(writeFileAtomically(folder / "x", big, [&](WriteStage stage, std::size_t written) {
                    seen.emplace_back(stage, written);
                    return WriteFault::None;
                }).ok());
    const std::vector<std::pair<WriteStage, std::size_t>> expected = {
        {WriteStage::Opened, 0},           {WriteStage::Wrote, kAtomicWriteChunk},
        {WriteStage::Wrote, 2 * kAtomicWriteChunk}, {WriteStage::Wrote, big.size()},
        {WriteStage::Synced, big.size()},  {WriteStage::Renaming, big.size()}};
    EXPECT_EQ(seen, expected);
}

}  // namespace
}  // namespace af
