// Replays files through a fuzz target without libFuzzer: every file named on the command line,
// and every file inside each folder named there, in sorted order. The ordinary (gcc) build runs
// this under ctest, so the committed corpus and every crash reproducer are checked on each
// test run. A crash, an abort or an escaping exception fails the test, as in the fuzzer.
#include "FuzzSupport.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

int main(int argc, char** argv)
{
    std::vector<fs::path> files;
    for (int i = 1; i < argc; ++i) {
        const fs::path arg(argv[i]);
        if (fs::is_directory(arg)) {
            for (const auto& entry : fs::directory_iterator(arg))
                if (entry.is_regular_file()) files.push_back(entry.path());
        } else if (fs::is_regular_file(arg)) {
            files.push_back(arg);
        } else {
            std::fprintf(stderr, "replay: %s is neither a file nor a folder\n", argv[i]);
            return 2;
        }
    }
    // An empty corpus would pass without testing anything.
    if (files.empty()) {
        std::fprintf(stderr, "usage: %s FILE_OR_FOLDER... (at least one input file)\n", argv[0]);
        return 2;
    }
    std::sort(files.begin(), files.end());

    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    double slowest = 0.0;
    fs::path slowestFile;
    for (const fs::path& file : files) {
        std::ifstream in(file, std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                      std::istreambuf_iterator<char>());
        if (!in.good() && !in.eof()) {
            std::fprintf(stderr, "replay: cannot read %s\n", file.c_str());
            return 2;
        }
        // Printed first, so a crash names its input.
        std::fprintf(stderr, "replay: %s\n", file.c_str());
        const auto begin = Clock::now();
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        const double seconds = std::chrono::duration<double>(Clock::now() - begin).count();
        if (seconds > slowest) {
            slowest = seconds;
            slowestFile = file;
        }
    }
    const double total = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("replayed %zu inputs in %.2f s (slowest %.3f s: %s)\n", files.size(), total,
                slowest, slowestFile.filename().c_str());
    return 0;
}
