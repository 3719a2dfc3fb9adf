/// @file CommandLine.h
/// @brief What the lsdem tools add to CLI11: numbers read strictly (the whole text must parse,
///        base 10, finite: no nan, no inf), their defaults shown in --help, and one way to end:
///        mistakes become lsdem::Error naming the option, printed once with the documented exit
///        codes (0 done or --help, 1 bad input, 3 internal error).
#pragma once

#include "lsdem/core/Error.h"
#include "lsdem/core/ThreadLimit.h"

#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
} // namespace CLI

namespace lsdem::cli {

/// Give @a app (before its options and subcommands are added) the tools' conventions: a
/// repeated option keeps its last value, and the help reads usage, description, options.
void applyConventions(CLI::App& app);

/// @a text as a finite number; Error naming @a option otherwise.
double parseNumber(const std::string& text, const std::string& option);

/// @a text as a whole number in base 10; Error naming @a option otherwise.
long long parseInteger(const std::string& text, const std::string& option);

/// Option @a name taking one finite number into @a value; its current value is the default
/// shown in the help.
CLI::Option* addNumber(CLI::App& app, const std::string& name, double& value,
                       const std::string& help);

/// Option @a name taking one or more finite numbers (exactly @a group of them if @a group > 0,
/// "--box A B C"), which replace @a values.
CLI::Option* addNumbers(CLI::App& app, const std::string& name, std::vector<double>& values,
                        const std::string& help, int group = 0);

/// Option @a name taking one whole number into @a value; a number beyond the range of int is
/// clamped to it, so the range check downstream reports it.
CLI::Option* addInteger(CLI::App& app, const std::string& name, int& value,
                        const std::string& help);
CLI::Option* addInteger(CLI::App& app, const std::string& name, long long& value,
                        const std::string& help);

/// Option `--threads N` into @a threads: 0 for all cores (as when it is left out: @a threads
/// keeps its value, 0) or a whole number up to kMaxThreads; an Error naming --threads otherwise.
/// Every tool's --threads takes the same values.
CLI::Option* addThreads(CLI::App& app, long long& threads, const std::string& help);

/// The check of addThreads, for a count set otherwise (an options struct built in code).
/// @throw Error naming --threads unless 0 ≤ @a threads ≤ kMaxThreads.
void checkThreads(long long threads);

/// Option @a name taking one or more whole numbers, which replace @a values (range checks are
/// the caller's, so the message can say what the numbers are for).
CLI::Option* addIntegers(CLI::App& app, const std::string& name, std::vector<long long>& values,
                         const std::string& help);

/// Option @a name taking one or more whole positive numbers (node counts: "1e4" is allowed),
/// which replace @a values.
CLI::Option* addCounts(CLI::App& app, const std::string& name, std::vector<int>& values,
                       const std::string& help);

/// Option @a name taking one or more texts (paths, names), which replace @a values; the
/// current ones are the default shown in the help.
CLI::Option* addTexts(CLI::App& app, const std::string& name, std::vector<std::string>& values,
                      const std::string& help);

/// Make the list option @a option keep only its last occurrence's values, as a single value's
/// last occurrence wins (applyConventions): CLI11 would join "--nodes 1 2 --nodes 3" into
/// 1 2 3. Its callback then runs once per occurrence, each replacing the values.
CLI::Option* lastListWins(CLI::Option* option);

/// @a value as the help shows defaults ("0.05", "1e+09").
std::string showNumber(double value);

/// @a values as the help shows defaults ("[0.25,0.5,1]").
std::string showList(const std::vector<std::string>& values);

/// Parse @a argc, @a argv into @a app. Returns the exit code if the program should stop here
/// (0 after --help, which is printed), nothing to go on. A mistake throws Error with the
/// problem as CLI11 words it and the fix "see <command> --help".
std::optional<int> parse(CLI::App& app, int argc, char** argv);

/// Refuse, before any work, an output file @a output (given with @a option) that is the same
/// file as one of @a inputs, however spelt: writing it would destroy that input. The output
/// need not exist yet; an empty @a output (none asked for) passes.
void refuseOutputOverInput(const std::string& output, const std::string& option,
                           const std::vector<std::string>& inputs);

/// Run a tool's @a body, turning exceptions into one clear message and the exit codes the
/// tools document: 1 for bad input (lsdem::Error), 3 for an internal error.
template <typename Body>
int runTool(const char* toolName, Body body)
{
    try {
        return body();
    } catch (const Error& e) {
        std::fprintf(stderr, "%s: error: %s\n", toolName, e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: internal error: %s\n", toolName, e.what());
        return 3;
    }
}

} // namespace lsdem::cli
