// Outputs never replace inputs (docs/cli.md): OutputGuard resolves every spelling of a path
// (another relative form, a symlink, a hard link) to the same file, refuses an output that is an
// input or lies in an input folder whatever --force says, refuses to replace an existing file
// without --force, and lets a folder output replace only what tirpol claimed there. And the folder
// lock and the clean-up of temporary files that killed atomic writes leave behind.

#include "tirpol/core/output_guard.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>

#include "test_support.h"
#include "tirpol/core/atomic_file.h"

namespace tirpol {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

/// The message of the OutputConflict that `check` throws, or "" when it throws none.
std::string conflict(const OutputGuard& guard, bool force = false) {
    try {
        guard.check(force);
    } catch (const OutputConflict& e) {
        return e.what();
    }
    return "";
}

TEST(OutputGuard, AnOutputThatIsAnInputIsRefusedInEverySpellingEvenWithForce) {
    test::TempDir dir;
    test::write_text(dir / "m.csv", "angle_deg,e_s0\n0,0.9\n");
    fs::create_directories(dir / "sub");
    fs::create_symlink(dir / "m.csv", dir / "link.csv");
    fs::create_hard_link(dir / "m.csv", dir / "hard.csv");
    for (const fs::path& out :
         {dir / "m.csv", dir / "sub" / ".." / "m.csv", dir / "link.csv", dir / "hard.csv"}) {
        for (bool force : {false, true}) {
            const std::string message = conflict(
                OutputGuard().input(dir / "m.csv", "DATA").output_file(out, "--output"), force);
            EXPECT_THAT(message, HasSubstr("is the input DATA")) << out << " force " << force;
            EXPECT_THAT(message, HasSubstr(out.string()));
            EXPECT_THAT(message, HasSubstr((dir / "m.csv").string()));
        }
    }
    EXPECT_EQ(read_file(dir / "m.csv"), "angle_deg,e_s0\n0,0.9\n");
}

TEST(OutputGuard, NothingIsWrittenInsideAnInputFolder) {
    test::TempDir dir;
    test::write_text(dir / "session" / "session.json", "{}");
    for (const fs::path& out : {dir / "session" / "session.json", dir / "session" / "stokes.exr",
                                dir / "session" / "frames" / "x.exr"}) {
        const std::string message = conflict(
            OutputGuard().input(dir / "session", "SESSION").output_file(out, "--output"), true);
        EXPECT_THAT(message, HasSubstr("inside the input folder SESSION")) << out;
    }
    // Beside it is fine.
    EXPECT_EQ(
        conflict(
            OutputGuard().input(dir / "session", "SESSION").output_file(dir / "stokes.exr", "-o")),
        "");
}

TEST(OutputGuard, AnExistingFileIsReplacedOnlyWithForce) {
    test::TempDir dir;
    test::write_text(dir / "cal.exr", "user's file");
    const auto guard = OutputGuard().output_file(dir / "cal.exr", "--output");
    EXPECT_THAT(conflict(guard), HasSubstr("exists and was not written by this run; pass --force"));
    EXPECT_EQ(conflict(guard, true), "");
    // A folder where a file is expected, or a path through a file, is refused before any work.
    fs::create_directories(dir / "folder");
    EXPECT_THAT(conflict(OutputGuard().output_file(dir / "folder", "--output"), true),
                HasSubstr("is a folder"));
    EXPECT_THAT(conflict(OutputGuard().output_folder(dir / "cal.exr", "--output", {"*.png"}), true),
                HasSubstr("exists and is not a folder"));
    EXPECT_THAT(conflict(OutputGuard().output_file(dir / "cal.exr" / "x.exr", "--output"), true),
                HasSubstr("cal.exr is not a folder"));
    // Two outputs of one command on one path.
    EXPECT_THAT(conflict(OutputGuard()
                             .output_file(dir / "a.png", "--output")
                             .output_file(dir / "a.png", "--plot")),
                HasSubstr("is also written as --output"));
}

TEST(OutputGuard, AFolderOutputKeepsWhatItDoesNotOwnAndReplacesWhatItClaimed) {
    test::TempDir dir;
    const fs::path out = dir / "sweep";
    test::write_text(out / "results.csv", "the user's own table\n");
    test::write_text(out / "notes.txt", "kept\n");
    const auto guard = [&] {
        return OutputGuard().output_folder(out, "--output", {"manifest.json", "results.csv"});
    };
    const std::string message = conflict(guard());
    EXPECT_THAT(message, HasSubstr((out / "results.csv").string()));
    EXPECT_THAT(message, HasSubstr("no tirpol command wrote"));
    EXPECT_FALSE(fs::exists(out / kOutputLedgerName)) << "a refused check writes nothing";

    // A fresh folder: claimed with the first file written in it, so the next run into it (a resume,
    // a re-render) is not refused. Nothing is created before that (a bad input leaves no trace).
    const fs::path fresh = dir / "fresh";
    EXPECT_EQ(
        conflict(OutputGuard().output_folder(fresh, "--output", {"manifest.json", "results.csv"})),
        "");
    EXPECT_FALSE(fs::exists(fresh));
    write_file_atomic(fresh / "results.csv", "written by the sweep\n");
    EXPECT_TRUE(fs::is_regular_file(fresh / kOutputLedgerName));
    test::write_text(fresh / "mine.csv", "the user's\n");
    EXPECT_EQ(
        conflict(OutputGuard().output_folder(fresh, "--output", {"manifest.json", "results.csv"})),
        "");
    // ... but an input under a claimed name is never replaced, even with --force.
    EXPECT_THAT(conflict(OutputGuard()
                             .input(fresh / "results.csv", "--measured")
                             .output_folder(fresh, "--output", {"results.csv"}),
                         true),
                HasSubstr("over the input --measured"));
}

TEST(AtomicFile, TemporaryFileNamesAreRecognised) {
    EXPECT_EQ(temp_file_owner_pid(".stokes.exr.tmp-4242-123456.exr"), 4242);
    EXPECT_EQ(temp_file_owner_pid(".results.tmp-7-1"), 7);
    EXPECT_EQ(temp_file_owner_pid("stokes.exr.tmp-4242-1.exr"), std::nullopt);  // not hidden
    EXPECT_EQ(temp_file_owner_pid(".notes.tmp-abc-1"), std::nullopt);
    EXPECT_EQ(temp_file_owner_pid(".lock"), std::nullopt);
    EXPECT_EQ(temp_file_owner_pid(".x.tmp-12-"), std::nullopt);
}

/// The pid of a process that has ended.
pid_t ended_pid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
}

TEST(AtomicFile, TheFirstWriteInAFolderRemovesWhatKilledWritesLeftOnly) {
    test::TempDir dir;
    const auto old = fs::file_time_type::clock::now() - std::chrono::hours(1);
    const std::string dead = std::to_string(ended_pid());
    const fs::path abandoned = dir / (".stokes.exr.tmp-" + dead + "-99.exr");
    const fs::path live_writer =
        dir / ".cal.exr.tmp-1-99.exr";  // pid 1 runs: maybe another run, still writing
    const fs::path recent = dir / (".new.csv.tmp-" + dead + "-5.csv");
    const fs::path user = dir / ".stokes.exr.bak";
    for (const auto& p : {abandoned, live_writer, recent, user})
        test::write_text(p, std::string(1000, 'x'));
    for (const auto& p : {abandoned, live_writer, user}) fs::last_write_time(p, old);
    // `recent` was written after this process started: not ours to judge.
    write_file_atomic(dir / "out.txt", "hello\n");
    EXPECT_FALSE(fs::exists(abandoned));
    EXPECT_TRUE(fs::exists(live_writer));
    EXPECT_TRUE(fs::exists(recent));
    EXPECT_TRUE(fs::exists(user));
    EXPECT_EQ(read_file(dir / "out.txt"), "hello\n");
}

TEST(FolderLock, ASecondHolderIsRefusedWithTheFirstOnesPid) {
    test::TempDir dir;
    {
        const FolderLock first(dir / "sweep", "a tirpol sweep");
        try {
            const FolderLock second(dir / "sweep", "a tirpol sweep");
            ADD_FAILURE() << "a second lock on the same folder was granted";
        } catch (const Error& e) {
            EXPECT_THAT(e.what(), HasSubstr("is in use by process " + std::to_string(::getpid())));
            EXPECT_THAT(e.what(), HasSubstr((dir / "sweep").string()));
        }
    }
    // Released with its holder.
    EXPECT_NO_THROW(FolderLock(dir / "sweep", "a tirpol sweep"));
}

}  // namespace
}  // namespace tirpol
