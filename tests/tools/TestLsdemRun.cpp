// lsdem-run through the real program: outputs, thread independence, bit-identical restart,
// stopping on a signal, and bad input.
#include "support/TestSupport.h"

#include "lsdem/core/FolderLock.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

using namespace lsdem::test;

namespace {

const std::string kRun = LSDEM_RUN_EXE;

int countLines(const std::string& path)
{
    std::ifstream in(path);
    int n = 0;
    for (std::string line; std::getline(in, line);) ++n;
    return n;
}

/// Two small spheres thrown along a floor with friction and damping, so contacts, shear
/// history and dissipation all occur within a few hundred steps.
std::string smallScene(long long steps)
{
    return R"(
[assets.ball]
shape = "sphere"
radius = 2.0
voxel = 0.25
nodes = 200

[materials.steel]
density = 7.85e-9
[materials.floor]
density = 0.0

[[contacts]]
materials = ["steel", "steel"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.4
restitution = 0.6

[[contacts]]
materials = ["steel", "floor"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.4
restitution = 0.6

[[grains]]
asset = "ball"
material = "steel"
position = [0, 0, 1.99]
velocity = [60, 0, -20]
angular_velocity = [0, 5, 0]

[[grains]]
asset = "ball"
material = "steel"
position = [4.05, 0.3, 1.99]
velocity = [-40, 0, 0]

[[boundaries]]
name = "floor"
type = "plane"
material = "floor"
point = [0, 0, 0]
normal = [0, 0, 1]

[simulation]
gravity = [0, 0, -9810]
time_step = 1e-5
end_steps = )" + std::to_string(steps) + R"(

[output]
history_every = 10
vtk_period = 1e-3
)";
}

std::string writeScene(const ScratchDir& dir, const std::string& text)
{
    const std::string path = dir.file("scene.toml");
    std::ofstream(path) << text;
    return path;
}

const char* const kOutputs[] = {"energy.csv", "boundary_floor.csv", "grains.csv", "frames.pvd",
                                 "frames_grains_1.vtu", "frames_contacts_2.vtu"};

/// Every run output of folder @a a equals the one of folder @a b (both in @a dir), byte for byte.
void expectSameOutputs(const ScratchDir& dir, const std::string& a, const std::string& b)
{
    for (const char* name : kOutputs)
        EXPECT_EQ(readFile(dir.file(a + "/" + name)), readFile(dir.file(b + "/" + name))) << name;
}

} // namespace

TEST(LsdemRun, WritesHistoriesFramesAndCheckpoint)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(400));
    const CommandResult r = runCommand(kRun + " " + scene + " --out " + dir.file("out"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* name : kOutputs)
        EXPECT_TRUE(std::filesystem::exists(dir.file("out/") + name)) << name;
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/checkpoint.lsdem")));
    // Rows at steps 0, 10, ..., 400 plus the header.
    EXPECT_EQ(countLines(dir.file("out/energy.csv")), 1 + 41);
    EXPECT_EQ(countLines(dir.file("out/grains.csv")), 1 + 2);
    EXPECT_NE(r.output.find("where the time went"), std::string::npos) << r.output;
    // The floor carries the balls' weight and impacts: its force must be downward (onto it).
    const std::string floor = readFile(dir.file("out/boundary_floor.csv"));
    EXPECT_NE(floor.find("step,time,ux,uy,uz,fx,fy,fz"), std::string::npos);
}

// [output] frame_spacing draws each grain's surface coarser in the frames (lighter frames of
// many grains) and changes nothing else: the histories are the same bytes.
TEST(LsdemRun, FrameSpacingDrawsLighterSurfacesOnly)
{
    ScratchDir dir;
    const std::string fine = writeScene(dir, smallScene(20));
    ASSERT_EQ(runCommand(kRun + " -q " + fine + " --out " + dir.file("fine")).exitCode, 0);
    std::string text = smallScene(20);
    text.replace(text.find("vtk_period"), 10, "frame_spacing = 1.0\nvtk_period");
    const std::string coarse = dir.file("coarse.toml");
    std::ofstream(coarse) << text;
    const CommandResult r = runCommand(kRun + " -q " + coarse + " --out " + dir.file("coarse"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const auto points = [&](const std::string& run) {
        const std::string frame = readFile(dir.file(run + "/frames_grains_0.vtu"));
        const size_t at = frame.find("NumberOfPoints=\"");
        return at == std::string::npos ? -1L : std::stol(frame.substr(at + 16));
    };
    // A sphere of radius 2 at its 200 nodes' spacing (about 0.5 mm), and at 1 mm: about a
    // sixth of the points (measured: 688 and 112 for the two grains).
    EXPECT_GT(points("fine"), 300);
    EXPECT_GT(points("coarse"), 40);
    EXPECT_LT(points("coarse"), points("fine") / 3);
    for (const char* name : {"energy.csv", "boundary_floor.csv", "grains.csv"})
        EXPECT_EQ(readFile(dir.file(std::string("fine/") + name)),
                  readFile(dir.file(std::string("coarse/") + name)))
            << name;
    // A spacing beyond a grain's bounding radius (2 here) would draw it as nothing: refused,
    // before any output.
    std::string tooCoarse = text;
    tooCoarse.replace(tooCoarse.find("frame_spacing = 1.0"), 19, "frame_spacing = 5.0");
    std::ofstream(dir.file("too-coarse.toml")) << tooCoarse;
    const CommandResult refused =
        runCommand(kRun + " -q " + dir.file("too-coarse.toml") + " --out " + dir.file("none"));
    EXPECT_EQ(refused.exitCode, 1) << refused.output;
    EXPECT_NE(refused.output.find("frame_spacing 5 is more than the smallest grain's bounding radius"),
              std::string::npos)
        << refused.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("none")));
}

TEST(LsdemRun, OneAndTwoThreadsGiveIdenticalBytes)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(300));
    // 0 is all cores, as in every tool's --threads.
    for (const char* threads : {"1", "2", "0"}) {
        const CommandResult r = runCommand(kRun + " " + scene + " -q --threads " + threads +
                                           " --out " + dir.file(std::string("t") + threads));
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    expectSameOutputs(dir, "t1", "t2");
    expectSameOutputs(dir, "t1", "t0");
}

TEST(LsdemRun, StopAndRestartContinuesBitIdentically)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(400));
    const CommandResult straight = runCommand(kRun + " " + scene + " -q --out " + dir.file("a"));
    ASSERT_EQ(straight.exitCode, 0) << straight.output;
    const CommandResult first =
        runCommand(kRun + " " + scene + " -q --stop-at-step 200 --out " + dir.file("b"));
    ASSERT_EQ(first.exitCode, 130) << first.output;
    EXPECT_NE(first.output.find("--restart"), std::string::npos) << first.output;
    const CommandResult second =
        runCommand(kRun + " -q --restart " + dir.file("b/checkpoint.lsdem"));
    ASSERT_EQ(second.exitCode, 0) << second.output;
    expectSameOutputs(dir, "a", "b");
    EXPECT_EQ(readFile(dir.file("a/frames_grains_4.vtu")), readFile(dir.file("b/frames_grains_4.vtu")));
}

// [output] micromechanics = true adds micromechanics.csv, a row at each history row, the same
// bytes on 1 and 2 threads, and whole after a stop and a restart (its rows are kept in the
// checkpoint, as energy.csv's are); and each frame's grains carry their measures.
TEST(LsdemRun, MicromechanicsHistoryIsWholeAfterARestart)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(400) + "micromechanics = true\n");
    const CommandResult straight = runCommand(kRun + " " + scene + " -q --out " + dir.file("a"));
    ASSERT_EQ(straight.exitCode, 0) << straight.output;
    const std::string rows = readFile(dir.file("a/micromechanics.csv"));
    EXPECT_EQ(countLines(dir.file("a/micromechanics.csv")), 1 + 41);
    EXPECT_EQ(rows.rfind("step,time,mxx,", 0), 0u) << rows.substr(0, 80);
    const CommandResult twoThreads =
        runCommand(kRun + " " + scene + " -q --threads 2 --out " + dir.file("t2"));
    ASSERT_EQ(twoThreads.exitCode, 0) << twoThreads.output;
    EXPECT_EQ(readFile(dir.file("t2/micromechanics.csv")), rows);
    expectSameOutputs(dir, "a", "t2");
    const CommandResult first =
        runCommand(kRun + " " + scene + " -q --stop-at-step 200 --out " + dir.file("b"));
    ASSERT_EQ(first.exitCode, 130) << first.output;
    const CommandResult second = runCommand(kRun + " -q --restart " + dir.file("b/checkpoint.lsdem"));
    ASSERT_EQ(second.exitCode, 0) << second.output;
    EXPECT_EQ(readFile(dir.file("b/micromechanics.csv")), rows);
    // The frames carry each grain's measures since the run's start, the restart's too.
    expectSameOutputs(dir, "a", "b");
    const std::string frame = readFile(dir.file("a/frames_grains_4.vtu"));
    for (const char* name : {"displacement", "rotation", "d2min", "stress"})
        EXPECT_NE(frame.find("Name=\"" + std::string(name) + "\""), std::string::npos) << name;
    EXPECT_EQ(readFile(dir.file("b/frames_grains_4.vtu")), frame);
}

// A restart from the checkpoint of a run that had already finished has nothing to add: it
// says so and leaves every file as it was (it used to write the last frame and the checkpoint
// again, so frames.pvd listed two frames at the same time and grew with each restart).
TEST(LsdemRun, RestartOfAFinishedRunWritesNothing)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(400));
    ASSERT_EQ(runCommand(kRun + " " + scene + " -q --out " + dir.file("a")).exitCode, 0);
    auto snapshot = [&] {
        std::map<std::string, std::string> files;
        for (const auto& e : std::filesystem::directory_iterator(dir.file("a")))
            files[e.path().filename().string()] = readFile(e.path().string());
        return files;
    };
    const std::map<std::string, std::string> before = snapshot();
    const CommandResult again = runCommand(kRun + " -q --restart " + dir.file("a/checkpoint.lsdem"));
    EXPECT_EQ(again.exitCode, 0) << again.output;
    EXPECT_NE(again.output.find("had already finished at step 400"), std::string::npos)
        << again.output;
    EXPECT_TRUE(snapshot() == before) << "a restart at the end changed the run's files";

    // A stop asked for at the last step is the end itself: the run finishes there (last row,
    // last frame), as the straight run did, rather than leave a checkpoint with nothing to do.
    const CommandResult stopAtEnd =
        runCommand(kRun + " " + scene + " -q --stop-at-step 400 --out " + dir.file("b"));
    EXPECT_EQ(stopAtEnd.exitCode, 0) << stopAtEnd.output;
    expectSameOutputs(dir, "a", "b");
}

// A finished run continued to a later end (--end-steps) gives the bytes of a run that went
// there straight; the checkpoint keeps that end, so a restart after a stop on the way
// continues to it without being told again.
TEST(LsdemRun, AFinishedRunContinuesToALaterEnd)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(400));
    const CommandResult straight =
        runCommand(kRun + " " + scene + " -q --end-steps 600 --out " + dir.file("s"));
    ASSERT_EQ(straight.exitCode, 0) << straight.output;
    EXPECT_NE(straight.output.find("finished at step 600"), std::string::npos) << straight.output;
    ASSERT_EQ(runCommand(kRun + " " + scene + " -q --out " + dir.file("a")).exitCode, 0);
    const std::string restart = kRun + " -q --restart " + dir.file("a/checkpoint.lsdem");
    const CommandResult further = runCommand(restart + " --end-steps 600 --stop-at-step 500");
    ASSERT_EQ(further.exitCode, 130) << further.output;
    const CommandResult rest = runCommand(restart);
    ASSERT_EQ(rest.exitCode, 0) << rest.output;
    EXPECT_NE(rest.output.find("finished at step 600"), std::string::npos) << rest.output;
    expectSameOutputs(dir, "a", "s");
    // Both ends at once, or an end that is not a count, are refused.
    EXPECT_EQ(runCommand(restart + " --end-steps 700 --end-time 1").exitCode, 1);
    EXPECT_EQ(runCommand(restart + " --end-steps 0").exitCode, 1);
    EXPECT_EQ(runCommand(restart + " --end-time nan").exitCode, 1);
}

// A restart continues frames.pvd, which lists the frames written before the checkpoint: with
// --out another folder it would list frames that folder lacks, so it is refused there (before
// anything is created); the checkpoint's own folder, however spelt, is fine.
TEST(LsdemRun, RestartWithFramesRefusesAnotherFolder)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(400));
    ASSERT_EQ(runCommand(kRun + " " + scene + " -q --stop-at-step 200 --out " + dir.file("b")).exitCode,
              130);
    const std::string restart = kRun + " -q --restart " + dir.file("b/checkpoint.lsdem");
    const CommandResult elsewhere = runCommand(restart + " --out " + dir.file("c"));
    EXPECT_EQ(elsewhere.exitCode, 1) << elsewhere.output;
    EXPECT_NE(elsewhere.output.find("frames.pvd here would list 3 earlier frames"),
              std::string::npos)
        << elsewhere.output;
    EXPECT_NE(elsewhere.output.find("drop --out to continue in " + dir.file("b")),
              std::string::npos)
        << elsewhere.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("c")));
    const CommandResult same = runCommand(restart + " --out " + dir.file("b/../b/"));
    EXPECT_EQ(same.exitCode, 0) << same.output;
}

// A checkpoint whose header reads well but whose body is damaged is refused before --out is
// created: no empty folder is left behind.
TEST(LsdemRun, DamagedCheckpointLeavesNoOutputFolder)
{
    ScratchDir dir;
    std::string text = smallScene(400);
    text.replace(text.find("vtk_period = 1e-3"), 17, "");  // no frames: --out elsewhere is fine
    const std::string scene = writeScene(dir, text);
    ASSERT_EQ(runCommand(kRun + " " + scene + " -q --stop-at-step 200 --out " + dir.file("b")).exitCode,
              130);
    const std::string checkpoint = dir.file("b/checkpoint.lsdem");
    std::filesystem::resize_file(checkpoint, std::filesystem::file_size(checkpoint) - 64);
    const CommandResult r =
        runCommand(kRun + " -q --restart " + checkpoint + " --out " + dir.file("c"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find(checkpoint + ": "), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("c")));
}

// A pile whose grains just touch (no node inside another yet: no contact stiffness at the start)
// and a fixed time_step far too long for the contacts they will make: issue 33 saw such a run
// stop at step 1 after writing three files. It is refused before the output folder exists,
// naming the limit; with a step the contacts bear it runs.
TEST(LsdemRun, AStepTheStartingContactsCannotBearIsRefusedBeforeAnyOutput)
{
    ScratchDir dir;
    std::string text = smallScene(50);
    // Both balls resting exactly on the floor, the second touching the first.
    for (const char* from : {"position = [0, 0, 1.99]", "position = [4.05, 0.3, 1.99]"})
        text.replace(text.find(from), std::string(from).size(),
                     from[13] == '0' ? "position = [0, 0, 2.0]" : "position = [4.0, 0, 2.0]");
    text.replace(text.find("time_step = 1e-5"), 16, "time_step = 1e-3");
    const CommandResult refused = runCommand(kRun + " " + writeScene(dir, text) + " -q --out " +
                                             dir.file("out"));
    EXPECT_EQ(refused.exitCode, 1) << refused.output;
    EXPECT_NE(refused.output.find("exceeds the stability limit"), std::string::npos)
        << refused.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
    text.replace(text.find("time_step = 1e-3"), 16, "time_step = 1e-6");
    const CommandResult ran = runCommand(kRun + " " + writeScene(dir, text) + " -q --out " +
                                         dir.file("out"));
    EXPECT_EQ(ran.exitCode, 0) << ran.output;
}

// One run writes a folder at a time. While another holds it (this test, standing for a run
// still writing there), a run into it and a restart from its checkpoint, in place or elsewhere,
// are refused, saying why and writing nothing; once it is free they go on.
TEST(LsdemRun, AFolderAnotherRunWritesIsRefused)
{
    ScratchDir dir;
    std::string text = smallScene(400);
    text.replace(text.find("vtk_period = 1e-3"), 17, "");  // no frames: --out elsewhere is fine
    const std::string scene = writeScene(dir, text);
    ASSERT_EQ(runCommand(kRun + " " + scene + " -q --stop-at-step 200 --out " + dir.file("b")).exitCode,
              130);
    const std::string checkpoint = dir.file("b/checkpoint.lsdem");
    const std::string before = readFile(dir.file("b/energy.csv")) + readFile(checkpoint);
    lsdem::FolderLock other;
    ASSERT_TRUE(other.tryLock(dir.file("b"), lsdem::FolderLock::Mode::Exclusive));
    const std::string restart = kRun + " -q --restart " + checkpoint;
    for (const std::string& command :
         {restart, restart + " --out " + dir.file("c"),
          kRun + " " + scene + " -q --overwrite --out " + dir.file("b")}) {
        const CommandResult r = runCommand(command);
        EXPECT_EQ(r.exitCode, 1) << command << "\n" << r.output;
        EXPECT_NE(r.output.find(dir.file("b") + ": another run is still writing this folder"),
                  std::string::npos)
            << command << "\n" << r.output;
    }
    EXPECT_EQ(readFile(dir.file("b/energy.csv")) + readFile(checkpoint), before);
    EXPECT_FALSE(std::filesystem::exists(dir.file("c")));
    other.unlock();
    const CommandResult r = runCommand(restart);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(countLines(dir.file("b/energy.csv")), 42);  // the header, steps 0, 10, ..., 400
}

TEST(LsdemRun, InterruptWritesACheckpointToContinueFrom)
{
    ScratchDir dir;
    const std::string scene = writeScene(dir, smallScene(100000000));  // would run for hours
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const std::string out = dir.file("out");
        const std::string log = dir.file("log.txt");
        freopen(log.c_str(), "w", stdout);
        execl(kRun.c_str(), kRun.c_str(), scene.c_str(), "-q", "--out", out.c_str(), nullptr);
        _exit(127);
    }
    // Wait until it is stepping (its first history row exists), then interrupt it.
    for (int i = 0; i < 600 && !std::filesystem::exists(dir.file("out/frames.pvd")); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    kill(child, SIGINT);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130) << readFile(dir.file("log.txt"));
    EXPECT_TRUE(std::filesystem::exists(dir.file("out/checkpoint.lsdem")));
    EXPECT_GE(countLines(dir.file("out/energy.csv")), 2);
    EXPECT_NE(readFile(dir.file("log.txt")).find("stopped at step"), std::string::npos);
}

TEST(LsdemRun, BadInputFailsCleanlyWithoutOutput)
{
    ScratchDir dir;
    struct Case
    {
        const char* what;
        std::string scene;
        const char* message;
    };
    std::string unstable = smallScene(400);
    unstable.replace(unstable.find("time_step = 1e-5"), 16, "time_step = 1e-2");
    std::string unknownKey = smallScene(400);
    unknownKey.replace(unknownKey.find("[output]"), 8, "[output]\nvtk_every = 3");
    const Case cases[] = {
        {"unstable time step", unstable, "stability limit"},
        {"unknown key", unknownKey, "vtk_every"},
    };
    int index = 0;
    for (const Case& c : cases) {
        const std::string scene = writeScene(dir, c.scene);
        const std::string out = dir.file("out-" + std::to_string(index++));
        const CommandResult r = runCommand(kRun + " " + scene + " -q --out " + out);
        EXPECT_EQ(r.exitCode, 1) << c.what << "\n" << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << c.what << "\n" << r.output;
        EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
    }
    // The unknown key (case 1) is caught before anything is written.
    EXPECT_FALSE(std::filesystem::exists(dir.file("out-1")));

    const CommandResult missing =
        runCommand(kRun + " " + dir.file("nope.toml") + " --threads 1 --out " + dir.file("x"));
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.output.find("nope.toml"), std::string::npos) << missing.output;
    // A refused run says why and nothing else (no "running on 1 process x 1 thread" first).
    EXPECT_EQ(missing.output.find("running on"), std::string::npos) << missing.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x")));
    // More threads than kMaxThreads: refused, not passed on to TBB.
    const CommandResult threads =
        runCommand(kRun + " " + dir.file("scene.toml") + " --threads 99999999999 --out " +
                   dir.file("x"));
    EXPECT_EQ(threads.exitCode, 1) << threads.output;
    EXPECT_NE(threads.output.find("--threads wants 0 (all cores) or a number up to 1024"), std::string::npos)
        << threads.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x")));
    const CommandResult noOut = runCommand(kRun + " " + dir.file("scene.toml"));
    EXPECT_EQ(noOut.exitCode, 1);
    EXPECT_NE(noOut.output.find("--out"), std::string::npos) << noOut.output;
    const CommandResult badCheckpoint = runCommand(kRun + " --restart " + dir.file("scene.toml"));
    EXPECT_EQ(badCheckpoint.exitCode, 1);
    EXPECT_NE(badCheckpoint.output.find("not an lsdem checkpoint"), std::string::npos)
        << badCheckpoint.output;
}

// A scene reading grains.csv from its own folder, run with --out that folder (however it is
// spelt), or with a grain file that links into the output folder: the output grains.csv would
// replace the input. Refused before anything is written; the input is kept as it was.
TEST(LsdemRun, RefusesAnOutputThatWouldOverwriteAnInput)
{
    ScratchDir dir;
    std::string text = smallScene(20);
    const size_t grains = text.find("[[grains]]");
    text.replace(grains, text.find("[[boundaries]]") - grains,
                 "[[grain_files]]\nfile = \"grains.csv\"\nmaterial = \"steel\"\n\n");
    const std::string csv =
        "name,asset,x,y,z,qw,qx,qy,qz\na,ball,0,0,1.99,1,0,0,0\nb,ball,5,0,1.99,1,0,0,0\n";
    std::filesystem::create_directories(dir.file("same"));
    std::ofstream(dir.file("same/scene.toml")) << text;
    std::ofstream(dir.file("same/grains.csv")) << csv;
    std::filesystem::create_directories(dir.file("linked"));
    std::ofstream(dir.file("linked/scene.toml")) << text;
    std::filesystem::create_symlink(dir.file("same/grains.csv"), dir.file("linked/grains.csv"));

    const std::pair<std::string, std::string> runs[] = {
        {dir.file("same/scene.toml"), dir.file("same")},
        {dir.file("same/scene.toml"), dir.file("same/../same/")},
        {dir.file("linked/scene.toml"), dir.file("same")}};
    for (const auto& [scene, out] : runs) {
        const CommandResult r = runCommand(kRun + " " + scene + " -q --out " + out);
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find("scene.toml:"), std::string::npos) << r.output;  // the entry
        EXPECT_NE(r.output.find("would overwrite its input"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("choose another --out folder"), std::string::npos) << r.output;
        EXPECT_EQ(readFile(dir.file("same/grains.csv")), csv);
        EXPECT_FALSE(std::filesystem::exists(dir.file("same/energy.csv")));
    }
    // --overwrite removes an earlier run's outputs, never an input that has their names.
    const CommandResult overwriting = runCommand(kRun + " " + dir.file("same/scene.toml") +
                                                 " -q --overwrite --out " + dir.file("same"));
    EXPECT_EQ(overwriting.exitCode, 1) << overwriting.output;
    EXPECT_NE(overwriting.output.find("would overwrite its input"), std::string::npos)
        << overwriting.output;
    EXPECT_EQ(readFile(dir.file("same/grains.csv")), csv);
    const CommandResult elsewhere =
        runCommand(kRun + " " + dir.file("same/scene.toml") + " -q --out " + dir.file("out"));
    EXPECT_EQ(elsewhere.exitCode, 0) << elsewhere.output;
    EXPECT_EQ(readFile(dir.file("same/grains.csv")), csv);
}

// A fresh run into a folder holding an earlier run's outputs would replace some of them (its
// checkpoint among them) and leave others (its frames, the history of a boundary the new scene
// lacks): refused before anything is written, unless --overwrite removes exactly those files.
TEST(LsdemRun, RefusesAFolderHoldingAnEarlierRunUnlessOverwriting)
{
    ScratchDir dir;
    const std::string out = dir.file("out");
    ASSERT_EQ(runCommand(kRun + " " + writeScene(dir, smallScene(20)) + " -q --out " + out).exitCode, 0);
    // A boundary the next scene lacks, as lsdem writes its history.
    std::ofstream(out + "/boundary_gone.csv") << "step,time,ux,uy,uz,fx,fy,fz\n0,0,0,0,0,0,0,0\n";
    std::ofstream(out + "/notes.txt") << "mine";
    // Named like a boundary's history, but the user's: neither reported nor removed.
    std::ofstream(out + "/boundary_conditions.csv") << "wall,load\ntop,5\n";
    const std::string checkpoint = readFile(out + "/checkpoint.lsdem");

    std::string text = smallScene(30);  // a different run, writing no frames
    text.replace(text.find("vtk_period = 1e-3"), 17, "");
    const std::string scene = writeScene(dir, text);
    const CommandResult refused = runCommand(kRun + " " + scene + " -q --out " + out);
    EXPECT_EQ(refused.exitCode, 1) << refused.output;
    EXPECT_NE(refused.output.find(out + ": the output folder holds the outputs of an earlier run ("
                                  "boundary_floor.csv, boundary_gone.csv, checkpoint.lsdem, "
                                  "energy.csv, frames.pvd and "),
              std::string::npos)
        << refused.output;
    EXPECT_NE(refused.output.find("choose another --out, or pass --overwrite to replace them"),
              std::string::npos)
        << refused.output;
    EXPECT_TRUE(readFile(out + "/checkpoint.lsdem") == checkpoint);  // (binary: not printed)
    EXPECT_TRUE(std::filesystem::exists(out + "/frames.pvd"));

    const CommandResult replaced = runCommand(kRun + " " + scene + " -q --overwrite --out " + out);
    ASSERT_EQ(replaced.exitCode, 0) << replaced.output;
    std::vector<std::string> left;
    for (const auto& entry : std::filesystem::directory_iterator(out))
        left.push_back(entry.path().filename().string());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"boundary_conditions.csv", "boundary_floor.csv",
                                              "checkpoint.lsdem", "energy.csv", "grains.csv",
                                              "notes.txt"}));
    EXPECT_EQ(readFile(out + "/notes.txt"), "mine");
    EXPECT_EQ(readFile(out + "/boundary_conditions.csv"), "wall,load\ntop,5\n");
    EXPECT_EQ(countLines(out + "/energy.csv"), 1 + 4);  // steps 0, 10, 20, 30

    const CommandResult restart =
        runCommand(kRun + " -q --overwrite --restart " + out + "/checkpoint.lsdem");
    EXPECT_EQ(restart.exitCode, 1) << restart.output;
    EXPECT_NE(restart.output.find("drop --overwrite"), std::string::npos) << restart.output;

    // A restart elsewhere starts a folder of its own: into another run's, as a fresh run.
    const std::string other = dir.file("other");
    ASSERT_EQ(runCommand(kRun + " " + scene + " -q --out " + other).exitCode, 0);
    const CommandResult elsewhere =
        runCommand(kRun + " -q --restart " + out + "/checkpoint.lsdem --out " + other);
    EXPECT_EQ(elsewhere.exitCode, 1) << elsewhere.output;
    EXPECT_NE(elsewhere.output.find("holds the outputs of an earlier run"), std::string::npos)
        << elsewhere.output;
    EXPECT_EQ(runCommand(kRun + " -q --overwrite --restart " + out + "/checkpoint.lsdem --out " +
                         other)
                  .exitCode,
              0);
}

// A file the run would write that lsdem did not write (a grains.csv from elsewhere) is the
// user's: the run is refused, with or without --overwrite, and the file is kept.
TEST(LsdemRun, RefusesToReplaceAFileLsdemDidNotWrite)
{
    ScratchDir dir;
    const std::string out = dir.file("out");
    std::filesystem::create_directories(out);
    const std::string mine = "name,asset,x,y,z\na,pebble,0,0,1\n";
    std::ofstream(out + "/grains.csv") << mine;
    const std::string scene = writeScene(dir, smallScene(20));
    for (const std::string overwrite : {"", " --overwrite"}) {
        const CommandResult r = runCommand(kRun + " " + scene + " -q --out " + out + overwrite);
        EXPECT_EQ(r.exitCode, 1) << r.output;
        EXPECT_NE(r.output.find(out + "/grains.csv: this file is not an output of lsdem"),
                  std::string::npos)
            << r.output;
        EXPECT_EQ(readFile(out + "/grains.csv"), mine);
    }
}

// An end condition far beyond what anyone means (1e30 time units at a 1e-5 step) is run, as
// asked, but the user is told at once how many steps and how long that is; a short run is not.
TEST(LsdemRun, WarnsOfAnAbsurdlyLongRun)
{
    ScratchDir dir;
    std::string text = smallScene(400);
    const std::string steps = "end_steps = 400";
    text.replace(text.find(steps), steps.size(), "end_time = 1e30");
    const std::string scene = writeScene(dir, text);
    const CommandResult r =
        runCommand(kRun + " " + scene + " --out " + dir.file("out") + " --stop-at-step 5 -q");
    EXPECT_EQ(r.exitCode, 130) << r.output;  // stopped as if interrupted
    EXPECT_NE(r.output.find("warning: the end condition (end_time = 1e+30) means 1e+35 steps"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("years"), std::string::npos) << r.output;

    const CommandResult shortRun =
        runCommand(kRun + " " + writeScene(dir, smallScene(20)) + " --out " + dir.file("short"));
    EXPECT_EQ(shortRun.exitCode, 0) << shortRun.output;
    EXPECT_EQ(shortRun.output.find("warning"), std::string::npos) << shortRun.output;
}
