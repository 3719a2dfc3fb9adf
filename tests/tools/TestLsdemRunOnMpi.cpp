// lsdem-run under `mpirun --oversubscribe -n N` as a user runs it: one simulation split by
// space over N ranks, each owning its sub-domain's grains with ghosts of its neighbours'
// (lsdem/simulation/GhostDecomposition.h), rank 0 writing the histories and checkpoints, each
// rank its piece of every ParaView frame. Every history, grains.csv and checkpoint must be the
// single process's, byte for byte, for 1 to 4 ranks, with a rank that owns no grain, across
// a restart on another rank count and for the interlocked slab's loaded flat faces; each frame
// is the single process's file, or a .pvtu whose pieces hold together exactly its points and
// cells. A run killed with kill -9 at any moment, on 1, 2 or 3 processes, continues on any of
// those counts to the uninterrupted run's bytes. Skipped when lsdem was built without MPI.
// Open MPI refuses to start as root without OMPI_ALLOW_RUN_AS_ROOT*: ctest sets those for this
// program (tests/CMakeLists.txt).
#include "studies/SlabModel.h"
#include "studies/SlabScene.h"

#include "support/TestSupport.h"

#include "lsdem/ls/AssetIO.h"
#include "lsdem/core/CsvText.h"
#include "lsdem/run/Checkpoint.h"
#include "lsdem/scene/BuildWorld.h"
#include "lsdem/scene/SceneFile.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

using namespace lsdem::test;

namespace {

const std::string kRun = LSDEM_RUN_EXE;
const std::string kMpiexec = LSDEM_MPIEXEC;

std::set<std::string> filesIn(const std::string& dir)
{
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.is_regular_file()) names.insert(e.path().filename().string());
    return names;
}

/// A .vtu's point and cell counts, as its Piece tag declares them.
std::pair<long long, long long> pointsAndCells(const std::string& path)
{
    static const std::regex piece(R"__(<Piece NumberOfPoints="(\d+)" NumberOfCells="(\d+)">)__");
    const std::string text = readFile(path);
    std::smatch m;
    const std::string head = text.substr(0, text.find("<AppendedData"));
    if (!std::regex_search(head, m, piece)) return {-1, -1};
    return {std::stoll(m[1]), std::stoll(m[2])};
}

/// A Float64 array @a name of a .vtu written with raw appended data (VtkSeries.cpp): its
/// values, read from the byte count and numbers at its offset past the '_' that starts the data.
std::vector<double> float64Array(const std::string& path, const std::string& name)
{
    const std::string text = readFile(path);
    const size_t appended = text.find("<AppendedData");
    const std::regex array("<DataArray type=\"Float64\" Name=\"" + name +
                           "\" NumberOfComponents=\"\\d+\" format=\"appended\" offset=\"(\\d+)\"");
    std::smatch m;
    const std::string head = text.substr(0, appended);
    if (appended == std::string::npos || !std::regex_search(head, m, array)) return {};
    const size_t at = text.find('_', appended) + 1 + std::stoull(m[1]);
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, text.data() + at, sizeof bytes);
    std::vector<double> values(bytes / sizeof(double));
    std::memcpy(values.data(), text.data() + at + sizeof bytes, values.size() * sizeof(double));
    return values;
}

/// The files a parallel frame's .pvtu names as its pieces.
std::vector<std::string> piecesOf(const std::string& path)
{
    static const std::regex source(R"__(<Piece Source="([^"]*)"/>)__");
    const std::string text = readFile(path);
    std::vector<std::string> pieces;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), source);
         it != std::sregex_iterator(); ++it)
        pieces.push_back((*it)[1]);
    return pieces;
}

/// @a actual's folder holds what @a expected's (one process's) does: every file but the frames
/// with the same bytes; each frame either the same file, byte for byte, or a .pvtu whose pieces
/// together have its points and cells; the .pvd naming whichever it is; and no other file.
void expectSameFiles(const std::string& expected, const std::string& actual,
                     const std::string& what)
{
    const std::set<std::string> names = filesIn(expected);
    EXPECT_TRUE(names.count("checkpoint.lsdem") && names.count("energy.csv")) << what;
    std::set<std::string> accounted;
    std::string pvd = readFile(expected + "/frames.pvd");
    for (const std::string& name : names) {
        if (name == "frames.pvd") continue;  // below
        const bool frame = name.rfind("frames_", 0) == 0;
        const std::string parallel = name.substr(0, name.size() - 4) + ".pvtu";
        if (!frame || std::filesystem::exists(actual + "/" + name)) {
            accounted.insert(name);
            EXPECT_TRUE(readFile(expected + "/" + name) == readFile(actual + "/" + name))
                << what << ": " << name << " differs";
            continue;
        }
        accounted.insert(parallel);
        const std::vector<std::string> pieces = piecesOf(actual + "/" + parallel);
        EXPECT_GE(pieces.size(), 2u) << what << ": " << parallel;
        long long points = 0, cells = 0;
        for (const std::string& piece : pieces) {
            accounted.insert(piece);
            const auto [p, c] = pointsAndCells(actual + "/" + piece);
            points += p;
            cells += c;
        }
        EXPECT_EQ(std::make_pair(points, cells), pointsAndCells(expected + "/" + name))
            << what << ": the pieces of " << parallel;
        const std::string listed = "file=\"" + name + "\"";
        if (pvd.find(listed) != std::string::npos)
            pvd.replace(pvd.find(listed), listed.size(), "file=\"" + parallel + "\"");
    }
    if (names.count("frames.pvd")) {
        accounted.insert("frames.pvd");
        EXPECT_EQ(readFile(actual + "/frames.pvd"), pvd) << what;
    }
    EXPECT_EQ(filesIn(actual), accounted) << what;
}

size_t count(const std::string& text, const std::string& what)
{
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

/// The number printed before @a label in @a text ("... 12 changes of rank ..."), or -1.
long long numberBefore(const std::string& text, const std::string& label)
{
    const size_t at = text.find(label);
    if (at == std::string::npos || at < 2) return -1;
    size_t begin = at - 1;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(text[begin - 1]))) --begin;
    return std::stoll(text.substr(begin, at - 1 - begin));
}

/// Spheres of radius 2.5 dropped from a loose column (2 × 2 × @a layers, jittered) into a box
/// of a floor and four walls, with friction and damping, @a endTime seconds. Tall and narrow,
/// so the sub-domains are cut across its height and the grains fall through the cuts; the
/// spheres hit the walls, the floor and each other, so shear histories load and travel.
std::string column(int layers, double endTime)
{
    std::ostringstream s;
    s << R"(
[assets.ball]
shape = "sphere"
radius = 2.5
voxel = 0.25
nodes = 300

[materials.rock]
density = 2.65e-9
[materials.wall]
density = 0.0

[[contacts]]
materials = ["rock", "rock"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.5
restitution = 0.3

[[contacts]]
materials = ["rock", "wall"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.5
restitution = 0.3

[[lattices]]
asset = "ball"
material = "rock"
origin = [-2.8, -2.8, 2.6]
count = [2, 2, )" << layers << R"(]
spacing = [5.6, 5.6, 5.6]
jitter = 0.4
seed = 3
)";
    const char* walls[][3] = {{"floor", "[0, 0, 0]", "[0, 0, 1]"},
                              {"west", "[-6, 0, 0]", "[1, 0, 0]"},
                              {"east", "[6, 0, 0]", "[-1, 0, 0]"},
                              {"south", "[0, -6, 0]", "[0, 1, 0]"},
                              {"north", "[0, 6, 0]", "[0, -1, 0]"}};
    for (const auto& w : walls)
        s << "\n[[boundaries]]\nname = \"" << w[0] << "\"\ntype = \"plane\"\nmaterial = \"wall\"\n"
          << "point = " << w[1] << "\nnormal = " << w[2] << "\n";
    s << R"(
[simulation]
gravity = [0, 0, -9810]
global_damping = 0.1
time_step = "auto"
end_time = )" << endTime << R"(

[output]
history_period = 1e-3
vtk_period = 1e-2
)";
    return s.str();
}

/// Three spheres, side by side on the floor and pushed together: fewer grains than 4 ranks.
std::string threeSpheres()
{
    std::string scene = column(1, 0.01);
    const size_t begin = scene.find("[[lattices]]"), end = scene.find("[[boundaries]]");
    const std::string lattice = scene.substr(begin, end - begin);
    scene.replace(scene.find(lattice), lattice.size(), R"([[grains]]
asset = "ball"
material = "rock"
position = [-3.5, 0, 2.6]
velocity = [200, 0, 0]

[[grains]]
asset = "ball"
material = "rock"
position = [1.2, 0.5, 4]
angular_velocity = [0, 30, 0]

[[grains]]
asset = "ball"
material = "rock"
position = [3.3, -2.5, 3]
velocity = [-100, 200, 0]

)");
    return scene;
}

/// 64 spheres (a jittered 4 × 4 × 4 lattice, some overlapping at the start) in a periodic cell
/// of 22.4 mm: z compressed at 8 /s, x and y servo-held at 0.02 MPa, with friction, for
/// @a endTime seconds. Grains touch the images of grains across every face, leave through
/// faces, and the cell's stress steers it.
std::string periodicCell(double endTime)
{
    std::ostringstream s;
    s << R"(
[assets.ball]
shape = "sphere"
radius = 2.5
voxel = 0.25
nodes = 300

[materials.rock]
density = 2.65e-9

[[contacts]]
materials = ["rock", "rock"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.5
restitution = 0.3

[[lattices]]
asset = "ball"
material = "rock"
origin = [2.8, 2.8, 2.8]
count = [4, 4, 4]
spacing = [5.6, 5.6, 5.6]
jitter = 0.5
seed = 5

[simulation]
time_step = "auto"
end_time = )" << endTime << R"(
periodic_cell = [22.4, 22.4, 22.4]
periodic_stress = [0.02, 0.02, 0]
periodic_max_strain_rate = [8, 8, 0]
periodic_strain_rate = [0, 0, -8]

[output]
history_period = 1e-3
vtk_period = 1e-2
micromechanics = true
)";
    return s.str();
}

std::string writeScene(const ScratchDir& dir, const std::string& name, const std::string& text)
{
    const std::string path = dir.file(name);
    std::ofstream(path) << text;
    return path;
}

std::string onRanks(int ranks, const std::string& args)
{
    return kMpiexec + " --oversubscribe -n " + std::to_string(ranks) + " " + kRun + " " + args;
}

/// @a scene on 2 ranks of 2 threads and on 3, each into "ranksN" in @a dir: every file the
/// single process's in @a serial, ghosts held. Returns the 2 ranks' folder.
std::string expectSerialBytesOnTwoAndThreeRanks(const ScratchDir& dir, const std::string& scene,
                                                const std::string& serial)
{
    for (int ranks : {2, 3}) {
        const int threads = ranks == 2 ? 2 : 1;
        const std::string out = dir.file("ranks" + std::to_string(ranks));
        const CommandResult r = runCommand(onRanks(
            ranks, "-q --threads " + std::to_string(threads) + " " + scene + " --out " + out));
        EXPECT_EQ(r.exitCode, 0) << r.output;
        expectSameFiles(serial, out, std::to_string(ranks) + " ranks");
        EXPECT_GT(numberBefore(r.output, "ghosts at the end"), 0) << r.output;
    }
    return dir.file("ranks2");
}

/// @a scene stopped at @a step on @a before ranks and continued on @a after: the files of the
/// uninterrupted single process in @a serial.
void expectRestartOnOtherRanks(const ScratchDir& dir, const std::string& scene, long long step,
                               int before, int after, const std::string& serial)
{
    const std::string out = dir.file("restarted");
    const CommandResult first = runCommand(onRanks(
        before, "-q " + scene + " --stop-at-step " + std::to_string(step) + " --out " + out));
    ASSERT_EQ(first.exitCode, 130) << first.output;
    const CommandResult second = runCommand(onRanks(after, "-q --restart " + out + "/checkpoint.lsdem"));
    ASSERT_EQ(second.exitCode, 0) << second.output;
    expectSameFiles(serial, out,
                    std::to_string(before) + " ranks, then " + std::to_string(after));
}

/// The interlocked slab as `lsdem-study slab` writes it for lsdem-run (its 5×5 blocks in a
/// frame of fixed level-set blocks, the indenter a prescribed sphere pushed down onto the
/// central block), with the block baked coarse (SDP @a sdp, VDP @a vdp, adapted contacts): the
/// scene file and its block asset in @a dir. Returns the scene's path.
std::string slabScene(const ScratchDir& dir, double sdp, double vdp)
{
    lsdem::SlabStudyOptions o;
    o.deltaMax = 0.3;  // mm: the periods below are fractions of the whole push
    o.samples = 300;   // a history row every 1e-6 s of the 3e-4 s push
    const lsdem::SlabPanel panel(o.panel);
    const auto block = lsdem::bakeSlabBlock(panel, vdp, sdp);
    const double dt = lsdem::slabTimeStep(o, panel, *block, lsdem::Formulation::Adapted);
    lsdem::Scene scene = lsdem::makeSlabScene(o, lsdem::Formulation::Adapted, block, dt);
    scene.assets.front().file = dir.file("block.vdb");
    lsdem::saveAsset(*block, scene.assets.front().file);
    const std::string path = dir.file("slab_scene.toml");
    lsdem::writeSlabScene(scene, o, path);
    return path;
}

/// The last row's value in column @a column of a CSV file (its header names the columns).
double lastValue(const std::string& path, const std::string& column)
{
    const auto records = lsdem::readCsvRecords(readFile(path), path);
    if (records.size() < 2) throw std::runtime_error(path + ": no rows");
    const auto& names = records.front();
    const auto& last = records.back();
    for (size_t k = 0; k < names.size() && k < last.size(); ++k)
        if (names[k] == column) return std::stod(last[k]);
    throw std::runtime_error(path + ": no column '" + column + "'");
}

/// How many block pairs, and how many (block, boundary) pairs, carry shear force in the
/// checkpoint @a checkpoint of the scene @a scene.
std::pair<int, int> contactsWithShear(const std::string& scene, const std::string& checkpoint)
{
    std::vector<std::string> warnings;
    lsdem::World world = lsdem::buildWorld(lsdem::readSceneFile(scene), warnings);
    lsdem::restoreWorldState(checkpoint, world);
    auto loaded = [](const lsdem::ShearHistory& h) {
        for (const auto& e : h.entries())
            if (e.force.norm() > 0.0) return true;
        return false;
    };
    int pairs = 0, boundaries = 0;
    for (const auto& [ids, h] : world.pairHistory)
        pairs += loaded(h.shearOnFirstNodes) || loaded(h.shearOnSecondNodes);
    for (const auto& [ids, h] : world.boundaryHistory) boundaries += loaded(h);
    return {pairs, boundaries};
}

/// Ellipsoids and boxes dropped into a box of walls, with friction, and a sphere pushed down
/// and sideways into them; a checkpoint every 2e-4 s (117 steps, about 10 history rows), so a
/// kill at a random moment falls anywhere between two checkpoints or inside the writing of one.
std::string shapesUnderASphere()
{
    std::ostringstream s;
    s << R"(
[assets.egg]
shape = "ellipsoid"
size = [2.5, 1.8, 1.4]
voxel = 0.2
nodes = 200

[assets.brick]
shape = "box"
size = [3.5, 2.5, 2]
voxel = 0.2
nodes = 200

[materials.rock]
density = 2.65e-9
[materials.wall]
density = 0.0

[[contacts]]
materials = ["rock", "rock"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.5
restitution = 0.3

[[contacts]]
materials = ["rock", "wall"]
normal_stiffness = 1e3
shear_stiffness = 5e2
friction = 0.5
restitution = 0.3
)";
    const char* layers[][3] = {{"egg", "3", "3"}, {"brick", "8.5", "4"}};
    for (const auto& l : layers)
        s << "\n[[lattices]]\nasset = \"" << l[0] << "\"\nmaterial = \"rock\"\n"
          << "origin = [-5.5, -5.5, " << l[1] << "]\ncount = [3, 3, 1]\n"
          << "spacing = [5.5, 5.5, 5.5]\njitter = 0.2\nrandom_orientation = true\nseed = " << l[2]
          << "\n";
    const char* walls[][3] = {{"floor", "[0, 0, 0]", "[0, 0, 1]"},
                              {"west", "[-8.5, 0, 0]", "[1, 0, 0]"},
                              {"east", "[8.5, 0, 0]", "[-1, 0, 0]"},
                              {"south", "[0, -8.5, 0]", "[0, 1, 0]"},
                              {"north", "[0, 8.5, 0]", "[0, -1, 0]"}};
    for (const auto& w : walls)
        s << "\n[[boundaries]]\nname = \"" << w[0] << "\"\ntype = \"plane\"\nmaterial = \"wall\"\n"
          << "point = " << w[1] << "\nnormal = " << w[2] << "\n";
    s << R"(
[[boundaries]]
name = "ball"
type = "sphere"
material = "wall"
center = [0, 0, 16]
radius = 4
velocity = [-150, 0, -700]

[simulation]
gravity = [0, 0, -1e5]
global_damping = 0.1
time_step = "auto"
end_time = 0.012

[output]
history_period = 2e-5
checkpoint_period = 2e-4
)";
    return s.str();
}

/// lsdem-run with @a args on @a count processes: one as a user starts it, more under mpirun.
std::vector<std::string> onProcesses(int count, const std::vector<std::string>& args)
{
    std::vector<std::string> command = {kRun};
    if (count > 1)
        command = {kMpiexec, "--oversubscribe", "-n", std::to_string(count), kRun};
    command.insert(command.end(), args.begin(), args.end());
    return command;
}

/// Starts @a command in a session of its own, its output into @a log. Returns its pid, which
/// is also the session's id: mpirun's ranks stay in it even once mpirun is gone.
pid_t startInOwnSession(const std::vector<std::string>& command, const std::string& log)
{
    std::fflush(nullptr);  // or the child would print this program's pending output again
    const pid_t pid = fork();
    if (pid != 0) return pid;
    setsid();
    if (!std::freopen(log.c_str(), "w", stdout) || dup2(STDOUT_FILENO, STDERR_FILENO) < 0)
        _exit(126);
    std::vector<char*> argv;
    for (const std::string& a : command) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
}

/// The processes of session @a session still running (zombies do not count: they hold no
/// file or lock any more).
std::vector<pid_t> liveProcessesOf(pid_t session)
{
    std::vector<pid_t> found;
    for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
        const std::string name = entry.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        // "pid (command) state ppid pgrp session ...": the command may hold spaces.
        const std::string stat = readFile(entry.path().string() + "/stat");
        const size_t end = stat.rfind(')');
        if (end == std::string::npos) continue;
        std::istringstream fields(stat.substr(end + 1));
        char state = 0;
        long long parent = 0, group = 0, itsSession = 0;
        if (fields >> state >> parent >> group >> itsSession && itsSession == session &&
            state != 'Z')
            found.push_back(static_cast<pid_t>(std::stoll(name)));
    }
    return found;
}

/// kill -9 every process of session @a session and wait until none runs (up to 30 s).
void killSession(pid_t session)
{
    for (int i = 0; i < 3000; ++i) {
        const std::vector<pid_t> live = liveProcessesOf(session);
        if (live.empty()) return;
        for (pid_t pid : live) kill(pid, SIGKILL);
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ADD_FAILURE() << "session " << session << " still runs after kill -9";
}

/// Runs @a command in a session of its own, up to @a seconds (then kills it: exit code -1).
CommandResult runInOwnSession(const std::vector<std::string>& command, const std::string& log,
                              double seconds)
{
    const pid_t pid = startInOwnSession(command, log);
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    CommandResult result;
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > until) {
            killSession(pid);
            waitpid(pid, &status, 0);
            result.output = readFile(log) + "\n(killed after " + std::to_string(seconds) + " s)";
            return result;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.output = readFile(log);
    return result;
}

/// The files of a run's folder but the hidden ones: a write cut by kill -9 leaves its
/// temporary (.NAME.tmp-PID-N, lsdem/core/AtomicFile.h), never a half-written output.
std::set<std::string> outputsIn(const std::string& dir)
{
    std::set<std::string> names;
    for (const std::string& name : filesIn(dir))
        if (name.front() != '.') names.insert(name);
    return names;
}

/// With no process writing @a dir: its histories hold at least the rows of its checkpoint,
/// which a restart continues from (the files are written first).
void expectHistoriesNotBehindTheCheckpoint(const std::string& dir, const std::string& what)
{
    if (!std::filesystem::exists(dir + "/checkpoint.lsdem")) return;
    const lsdem::Checkpoint checkpoint = lsdem::readCheckpoint(dir + "/checkpoint.lsdem");
    const auto rows = lsdem::readCsvRecords(readFile(dir + "/energy.csv"), "energy.csv");
    EXPECT_GE(rows.size(), checkpoint.record.energyRows.size() + 1) << what;  // + the header
}

#define SKIP_WITHOUT_MPI() \
    if (kMpiexec.empty()) GTEST_SKIP() << "built without MPI"

} // namespace

// A settling column of 20 spheres: on 1, 2, 3 and 4 ranks, every file is the single process's
// (the frames of 2 or more ranks as a parallel series holding the same points and cells).
// The run must be what it claims: split over N ranks (the header, the exchange summary), grains
// changing rank as they fall through the sub-domains, rank 0 alone printing.
TEST(LsdemRunOnMpi, SettlingColumnGivesTheSerialBytesOnOneToFourRanks)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    const std::string scene = writeScene(dir, "column.toml", column(5, 0.03));
    const CommandResult serial = runCommand(kRun + " -q " + scene + " --out " + dir.file("serial"));
    ASSERT_EQ(serial.exitCode, 0) << serial.output;
    // The grains' own sums travel with them between ranks: friction slipped and dashpots
    // damped, so energy.csv's split of the dissipation is compared below, not zeros.
    EXPECT_GT(lastValue(dir.file("serial/energy.csv"), "dissipated_friction"), 0.0);
    EXPECT_GT(lastValue(dir.file("serial/energy.csv"), "dissipated_dashpot"), 0.0);
    for (int ranks = 1; ranks <= 4; ++ranks) {
        // Threads inside the ranks too: 2 ranks of 2 threads.
        const int threads = ranks == 2 ? 2 : 1;
        const std::string out = dir.file("ranks" + std::to_string(ranks));
        const CommandResult r = runCommand(onRanks(
            ranks, "-q --threads " + std::to_string(threads) + " " + scene + " --out " + out));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        expectSameFiles(dir.file("serial"), out, std::to_string(ranks) + " ranks");
        // One rank writes whole frames; more write a parallel series, a piece each.
        EXPECT_EQ(std::filesystem::exists(out + "/frames_grains_0.pvtu"), ranks > 1);
        if (ranks > 1) {
            EXPECT_EQ(piecesOf(out + "/frames_grains_0.pvtu").size(), size_t(ranks));
        }
        const std::string header =
            "running on " + std::to_string(ranks) + (ranks == 1 ? " rank x " : " ranks x ") +
            std::to_string(threads) + (threads == 1 ? " thread" : " threads");
        EXPECT_EQ(count(r.output, header), 1u) << r.output;
        EXPECT_EQ(count(r.output, "where the time went"), 1u) << r.output;
        if (ranks > 1) {
            // Grains crossed between rank 0 and the others, one way or the other.
            EXPECT_GT(numberBefore(r.output, "grains migrated in") +
                          numberBefore(r.output, "out, "),
                      0)
                << r.output;
            EXPECT_GT(numberBefore(r.output, "ghosts at the end"), 0) << r.output;
            EXPECT_NE(r.output.find("split over " + std::to_string(ranks) + " ranks"),
                      std::string::npos)
                << r.output;
        }
    }
}

// The interlocked slab at a coarse resolution (SDP 0.5 mm, VDP 0.1 mm): flat faces against
// flat faces carrying load and shear history, fixed level-set frame blocks, a prescribed
// indenter. Stopped at step 460 (the indenter 0.26 mm down, pressing the central block), every
// file of 2 ranks of 2 threads, 3 and 4 ranks is the single process's, byte for byte: the
// histories, grains.csv, each frame (or its pieces' points and cells) and the checkpoint, so
// the contacts' shear springs too.
TEST(LsdemRunOnMpi, SlabGivesTheSerialBytesOnTwoToFourRanks)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    const std::string scene = slabScene(dir, 0.5, 0.1);
    const std::string steps = " --stop-at-step 460";
    const CommandResult serial =
        runCommand(kRun + " -q " + scene + steps + " --out " + dir.file("serial"));
    ASSERT_EQ(serial.exitCode, 130) << serial.output;
    // Loaded: nodes of the indenter, the frame and the blocks' faces penetrating at the end.
    const double contactNodes = lastValue(dir.file("serial/energy.csv"), "contact_nodes");
    EXPECT_GT(contactNodes, 0.0);
    EXPECT_LT(lastValue(dir.file("serial/boundary_indenter.csv"), "uz"), -0.25);
    EXPECT_GT(lastValue(dir.file("serial/boundary_indenter.csv"), "fz"), 0.0);
    // Every shared face carries shear at the end: the 2·5·4 faces between neighbouring
    // blocks, the 20 between the border blocks and the frame, and the indenter's.
    const auto [pairs, boundaries] = contactsWithShear(scene, dir.file("serial/checkpoint.lsdem"));
    EXPECT_EQ(pairs, 40);
    EXPECT_EQ(boundaries, 21);
    std::printf("serial: %g contact nodes, %d block pairs and %d block-boundary pairs carrying "
                "shear at the end\n",
                contactNodes, pairs, boundaries);
    for (int ranks = 2; ranks <= 4; ++ranks) {
        // Threads inside the ranks too: 2 ranks of 2 threads.
        const std::string threads = ranks == 2 ? "2" : "1";
        const std::string out = dir.file("ranks" + std::to_string(ranks));
        const CommandResult r = runCommand(
            onRanks(ranks, "-q --threads " + threads + " " + scene + steps + " --out " + out));
        ASSERT_EQ(r.exitCode, 130) << r.output;
        expectSameFiles(dir.file("serial"), out, "slab on " + std::to_string(ranks) + " ranks");
        EXPECT_NE(r.output.find("split over " + std::to_string(ranks) + " ranks"),
                  std::string::npos)
            << r.output;
        // Rank 0 held ghosts of its neighbours' blocks: faces in contact across the cuts.
        EXPECT_GT(numberBefore(r.output, "ghosts at the end"), 0) << r.output;
        std::printf("%d ranks: rank 0 owns %lld blocks and holds %lld ghosts at the end; %lld "
                    "migrated in, %lld out, %lld redraws of the sub-domains\n",
                    ranks, numberBefore(r.output, "grains owned"),
                    numberBefore(r.output, "ghosts at the end"),
                    numberBefore(r.output, "grains migrated in"), numberBefore(r.output, "out, "),
                    numberBefore(r.output, "redraws of"));
    }
}

// Three grains on four ranks: at every step a rank owns no grain; the files are still the
// single process's.
TEST(LsdemRunOnMpi, ARankWithoutGrainsChangesNothing)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    const std::string scene = writeScene(dir, "three.toml", threeSpheres());
    const CommandResult serial = runCommand(kRun + " -q " + scene + " --out " + dir.file("serial"));
    ASSERT_EQ(serial.exitCode, 0) << serial.output;
    const CommandResult four = runCommand(onRanks(4, "-q " + scene + " --out " + dir.file("four")));
    ASSERT_EQ(four.exitCode, 0) << four.output;
    expectSameFiles(dir.file("serial"), dir.file("four"), "3 grains on 4 ranks");
}

// A checkpoint is the replicated state: stopped on 2 ranks, continued on 3, the run ends with
// the files of one uninterrupted process; and a single process's checkpoint continues on 4.
TEST(LsdemRunOnMpi, ACheckpointRestartsOnAnotherRankCount)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    const std::string scene = writeScene(dir, "column.toml", column(5, 0.03));
    const CommandResult straight =
        runCommand(kRun + " -q " + scene + " --out " + dir.file("straight"));
    ASSERT_EQ(straight.exitCode, 0) << straight.output;

    const CommandResult first =
        runCommand(onRanks(2, "-q " + scene + " --stop-at-step 3000 --out " + dir.file("two")));
    ASSERT_EQ(first.exitCode, 130) << first.output;
    EXPECT_EQ(count(first.output, "stopped at step 3000"), 1u) << first.output;
    const CommandResult second =
        runCommand(onRanks(3, "-q --restart " + dir.file("two/checkpoint.lsdem")));
    ASSERT_EQ(second.exitCode, 0) << second.output;
    expectSameFiles(dir.file("straight"), dir.file("two"), "2 ranks, then 3");

    const CommandResult alone =
        runCommand(kRun + " -q " + scene + " --stop-at-step 2000 --out " + dir.file("one"));
    ASSERT_EQ(alone.exitCode, 130) << alone.output;
    const CommandResult four =
        runCommand(onRanks(4, "-q --restart " + dir.file("one/checkpoint.lsdem")));
    ASSERT_EQ(four.exitCode, 0) << four.output;
    expectSameFiles(dir.file("straight"), dir.file("one"), "1 process, then 4 ranks");
}

// A bad scene fails on every rank alike: one message (rank 0's), exit code 1, nothing written.
// A failure on rank 0 only (it cannot make the output folder) is voted to the others, so the
// whole job ends the same way, with rank 0's message, rather than leaving them waiting.
TEST(LsdemRunOnMpi, FailuresEndTheJobWithOneMessage)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    std::string bad = column(2, 0.01);
    bad.replace(bad.find("radius = 2.5"), 12, "radius = -2.5");
    const std::string badScene = writeScene(dir, "bad.toml", bad);
    const CommandResult r = runCommand(onRanks(3, "-q " + badScene + " --out " + dir.file("bad")));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_EQ(count(r.output, "lsdem-run: error:"), 1u) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("bad/energy.csv")));

    const std::string scene = writeScene(dir, "column.toml", column(2, 0.01));
    std::ofstream(dir.file("a-file")) << "not a folder";
    const CommandResult one =
        runCommand(onRanks(2, "-q " + scene + " --out " + dir.file("a-file/out")));
    EXPECT_EQ(one.exitCode, 1) << one.output;
    EXPECT_EQ(count(one.output, "lsdem-run: error:"), 1u) << one.output;
    EXPECT_NE(one.output.find("cannot create the output folder"), std::string::npos)
        << one.output;

}

// A periodic cell split by space: a rank holds as ghosts the grains whose images across a face
// reach its sub-domain, and the cell's stress (which steers it) is summed in one process's
// order. On 2 ranks of 2 threads and on 3, every file is the single process's, byte for byte
// (cell.csv, micromechanics.csv, grains.csv, the checkpoint); and stopped on 2 ranks, continued
// on 3, too.
TEST(LsdemRunOnMpi, PeriodicCellGivesTheSerialBytesOnTwoAndThreeRanks)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    const std::string scene = writeScene(dir, "cell.toml", periodicCell(0.03));
    const CommandResult serial = runCommand(kRun + " -q " + scene + " --out " + dir.file("serial"));
    ASSERT_EQ(serial.exitCode, 0) << serial.output;
    // A packing, not a gas: the cell compressed along z and the grains touching (measured:
    // 17.6 mm, 118 contacts at the end), the servo moving x and y.
    EXPECT_LT(lastValue(dir.file("serial/cell.csv"), "size_z"), 0.85 * 22.4);
    EXPECT_GT(lastValue(dir.file("serial/micromechanics.csv"), "grain_contacts"), 60.0);
    EXPECT_GT(lastValue(dir.file("serial/cell.csv"), "stress_x"), 0.0);
    expectSerialBytesOnTwoAndThreeRanks(dir, scene, dir.file("serial"));
    // tools/plots/shear_band.py reads a frame split into pieces whole (where matplotlib is).
    if (runCommand("/usr/bin/python3 -c 'import matplotlib, numpy'").exitCode == 0) {
        const std::string png = dir.file("band.png");
        const CommandResult band = runCommand("/usr/bin/python3 " LSDEM_SOURCE_DIR
                                              "/tools/plots/shear_band.py " +
                                              dir.file("ranks2") + " --out " + png);
        EXPECT_EQ(band.exitCode, 0) << band.output;
        EXPECT_NE(band.output.find("frame 3 at t = 0.03"), std::string::npos) << band.output;
        // (z strained at 8 /s for 0.03 s: 1 − e^(−0.24) = 0.2134.)
        EXPECT_NE(band.output.find(": 64 grains, axial strain 0.2134"), std::string::npos)
            << band.output;
        EXPECT_TRUE(std::filesystem::exists(png));
    }
    expectRestartOnOtherRanks(dir, scene, 6000, 2, 3, dir.file("serial"));
}

// A membrane split by space: every rank holds it whole and moves it alike, each grain's contact
// with it is its owner's, and the grains' reactions on its vertices are gathered and added in
// one process's order. The bundled sleeve (12 beads in a latex sleeve pressed by a lid, with
// micromechanics) on 2 ranks of 2 threads and on 3 gives the single process's bytes: the
// membrane's history and frames, the lid's, the energies, the checkpoint; and stopped on 3,
// continued on 2, too.
TEST(LsdemRunOnMpi, MembraneGivesTheSerialBytesOnTwoAndThreeRanks)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    std::string text = readFile(LSDEM_SOURCE_DIR "/assets/scenes/sleeve.toml");
    ASSERT_FALSE(text.empty());
    text += "micromechanics = true\n";  // (the last section is [output])
    const std::string scene = writeScene(dir, "sleeve.toml", text);
    const CommandResult serial = runCommand(kRun + " -q " + scene + " --out " + dir.file("serial"));
    ASSERT_EQ(serial.exitCode, 0) << serial.output;
    // The beads press on the membrane by the end (measured: 2.29 N summed over its vertices).
    EXPECT_GT(lastValue(dir.file("serial/membrane_sleeve.csv"), "grain_force_magnitude_sum"), 0.5);
    EXPECT_TRUE(std::filesystem::exists(dir.file("serial/frames_membranes_3.vtu")));
    const std::string two = expectSerialBytesOnTwoAndThreeRanks(dir, scene, dir.file("serial"));
    // The membranes' frames are whole files, listed as part 2 beside the pieces.
    EXPECT_NE(readFile(two + "/frames.pvd").find("part=\"2\" file=\"frames_membranes_3.vtu\""),
              std::string::npos);
    expectRestartOnOtherRanks(dir, scene, 1000, 3, 2, dir.file("serial"));
}

// Micromechanics under MPI: rank 0 sums the whole simulation in one process's order, so
// micromechanics.csv has the single process's bytes on 2 and 3 ranks; each rank's piece of a
// frame carries its grains' measures (worked out for the whole simulation: D²min needs
// neighbours that may live on other ranks).
TEST(LsdemRunOnMpi, MicromechanicsGiveTheSerialBytesOnTwoAndThreeRanks)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    const std::string scene =
        writeScene(dir, "micro.toml", column(5, 0.03) + "micromechanics = true\n");
    const CommandResult serial = runCommand(kRun + " -q " + scene + " --out " + dir.file("serial"));
    ASSERT_EQ(serial.exitCode, 0) << serial.output;
    // The grains touch each other and the walls: the rows measure contacts, not an empty sample.
    const auto rows = lsdem::readCsvRecords(readFile(dir.file("serial/micromechanics.csv")), "");
    const auto most = [&](const std::string& name) {
        const size_t at = size_t(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
        double m = 0.0;
        for (size_t k = 1; k < rows.size(); ++k) m = std::max(m, std::stod(rows[k].at(at)));
        return m;
    };
    EXPECT_GE(most("grain_contacts"), 2.0);     // measured: 5
    EXPECT_GE(most("boundary_contacts"), 2.0);  // measured: 3
    for (int ranks : {2, 3}) {
        const std::string out = dir.file("ranks" + std::to_string(ranks));
        const CommandResult r = runCommand(onRanks(ranks, "-q " + scene + " --out " + out));
        ASSERT_EQ(r.exitCode, 0) << r.output;
        expectSameFiles(dir.file("serial"), out, std::to_string(ranks) + " ranks");
        const std::vector<std::string> pieces = piecesOf(out + "/frames_grains_2.pvtu");
        ASSERT_EQ(pieces.size(), size_t(ranks));
        // The pieces' values together are the single frame's, each exactly (as multisets:
        // the pieces order the grains by rank).
        for (const char* measure : {"displacement", "rotation", "d2min", "stress"}) {
            std::vector<double> whole = float64Array(dir.file("serial/frames_grains_2.vtu"), measure);
            std::vector<double> split;
            for (const std::string& piece : pieces) {
                const std::vector<double> part = float64Array(out + "/" + piece, measure);
                split.insert(split.end(), part.begin(), part.end());
            }
            std::sort(whole.begin(), whole.end());
            std::sort(split.begin(), split.end());
            EXPECT_FALSE(whole.empty()) << measure;
            EXPECT_GT(std::abs(whole.back()) + std::abs(whole.front()), 0.0) << measure;
            EXPECT_TRUE(whole == split) << ranks << " ranks: " << measure << " differs";
        }
    }
}

// kill -9 at a random moment (seeded: LSDEM_KILL_SEED=N for other moments), for every pair of
// process counts among 1, 2 and 3: the run started on the first, continued from its checkpoint
// on the second, ends with the uninterrupted run's files, byte for byte. Under mpirun only
// mpirun itself is killed, as a user or a scheduler does: its ranks run on for a while,
// writing checkpoints, and a restart at once must refuse to continue beside them (it used to
// continue, its history rows from one checkpoint and its state from a newer one: rows lost;
// or on several ranks from different checkpoints: a job that never ended); once they are
// killed too, it continues.
TEST(LsdemRunOnMpi, AKilledRunContinuesOnAnyCountWithTheUninterruptedBytes)
{
    SKIP_WITHOUT_MPI();
    ScratchDir dir;
    const std::string scene = writeScene(dir, "shapes.toml", shapesUnderASphere());
    const CommandResult straight =
        runCommand(kRun + " -q " + scene + " --out " + dir.file("straight"));
    ASSERT_EQ(straight.exitCode, 0) << straight.output;
    const std::set<std::string> outputs = outputsIn(dir.file("straight"));

    const char* seedText = std::getenv("LSDEM_KILL_SEED");
    std::mt19937 random(seedText ? std::stoul(seedText) : 2026);
    std::uniform_int_distribution<int> delayMs(0, 400);
    for (int start = 1; start <= 3; ++start) {
        for (int restart = 1; restart <= 3; ++restart) {
            const std::string name = std::to_string(start) + "to" + std::to_string(restart);
            const std::string out = dir.file(name);
            const int delay = delayMs(random);
            const std::string what = name + ", killed " + std::to_string(delay) +
                                     " ms after its first checkpoint";
            const pid_t job = startInOwnSession(onProcesses(start, {"-q", scene, "--out", out}),
                                                dir.file(name + "-first.log"));
            for (int i = 0; i < 3000 && !std::filesystem::exists(out + "/checkpoint.lsdem"); ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            std::this_thread::sleep_for(std::chrono::milliseconds(delay));
            kill(job, SIGKILL);  // the program, or mpirun alone
            waitpid(job, nullptr, 0);
            if (liveProcessesOf(job).empty()) expectHistoriesNotBehindTheCheckpoint(out, what);

            const std::vector<std::string> restartCommand =
                onProcesses(restart, {"-q", "--restart", out + "/checkpoint.lsdem"});
            const std::string log = dir.file(name + "-restart.log");
            CommandResult r = runInOwnSession(restartCommand, log, 60.0);
            const bool refused = r.exitCode == 1 &&
                                 r.output.find("another run is still writing this folder") !=
                                     std::string::npos;
            if (refused) {
                // The ranks of the killed mpirun were still writing: kill them too.
                killSession(job);
                expectHistoriesNotBehindTheCheckpoint(out, what);
                r = runInOwnSession(restartCommand, log, 60.0);
            }
            killSession(job);  // none should be left, whatever happened
            std::printf("%s: %s\n", what.c_str(),
                        refused ? "refused beside the ranks still running, then continued"
                                : "continued");
            ASSERT_EQ(r.exitCode, 0) << what << "\n" << r.output << "\nthe killed run's log:\n"
                                     << readFile(dir.file(name + "-first.log"));
            EXPECT_EQ(outputsIn(out), outputs) << what;
            for (const std::string& file : outputs)
                EXPECT_TRUE(readFile(dir.file("straight/" + file)) == readFile(out + "/" + file))
                    << what << ": " << file << " differs";
        }
    }
}
