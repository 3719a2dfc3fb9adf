#include "common/CommandLine.h"

#include "common/HelpFormatter.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

namespace lsdem::cli {

void applyConventions(CLI::App& app)
{
    auto help = std::make_shared<HelpFormatter>();
    help->column_width(30);  // the option column; descriptions fit in the 70 after it
    app.formatter(help);
    // A repeated option's last value wins (rather than CLI11's refusal), so a script can
    // override an option by appending it, as it always could (lists too: lastListWins).
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

double parseNumber(const std::string& text, const std::string& option)
{
    // strtod rather than CLI11's conversion: CLI11 reads through long double (a second
    // rounding) and takes "nan" and "inf".
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0')
        throw Error("", "option " + option + " wants a number, got '" + text + "'");
    if (!std::isfinite(v))
        throw Error("", "option " + option + " wants a finite number, got '" + text + "'");
    return v;
}

long long parseInteger(const std::string& text, const std::string& option)
{
    // Base 10: CLI11's conversion reads "010" as octal 8.
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0')
        throw Error("", "option " + option + " wants a whole number, got '" + text + "'");
    return v;
}

std::string showNumber(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

std::string showList(const std::vector<std::string>& values)
{
    std::string text = "[";
    for (size_t i = 0; i < values.size(); ++i) text += (i ? "," : "") + values[i];
    return text + "]";
}

namespace {

std::vector<std::string> shown(const std::vector<double>& values)
{
    std::vector<std::string> out;
    for (double v : values) out.push_back(showNumber(v));
    return out;
}

std::vector<std::string> shown(const std::vector<int>& values)
{
    std::vector<std::string> out;
    for (int v : values) out.push_back(std::to_string(v));
    return out;
}

} // namespace

CLI::Option* addNumber(CLI::App& app, const std::string& name, double& value,
                       const std::string& help)
{
    return app
        .add_option_function<std::string>(
            name, [&value, name](const std::string& text) { value = parseNumber(text, name); },
            help)
        ->type_name("FLOAT")
        ->default_str(showNumber(value));
}

CLI::Option* lastListWins(CLI::Option* option)
{
    // Each occurrence goes to the callback as it is parsed (an empty value too, to be refused
    // as such), rather than all of them joined at the end.
    option->trigger_on_parse();
    return option;
}

CLI::Option* addTexts(CLI::App& app, const std::string& name, std::vector<std::string>& values,
                      const std::string& help)
{
    return lastListWins(app.add_option_function<std::vector<std::string>>(
                            name,
                            [&values](const std::vector<std::string>& given) { values = given; },
                            help))
        ->default_str(values.empty() ? "" : showList(values));
}

CLI::Option* addNumbers(CLI::App& app, const std::string& name, std::vector<double>& values,
                        const std::string& help, int group)
{
    CLI::Option* option =
        app.add_option_function<std::vector<std::string>>(
               name,
               [&values, name, group](const std::vector<std::string>& texts) {
                   if (group > 0 && texts.size() % size_t(group) != 0)
                       throw Error("", "option " + name + " wants " + std::to_string(group) +
                                           " numbers, got " + std::to_string(texts.size()));
                   values.clear();
                   for (const std::string& text : texts) values.push_back(parseNumber(text, name));
               },
               help)
            ->type_name("FLOAT")
            ->default_str(values.empty() ? "" : showList(shown(values)));
    // A group stops at its last number, so a positional argument may follow it.
    if (group > 0) option->type_size(1)->expected(group)->allow_extra_args(false);
    else lastListWins(option);
    return option;
}

CLI::Option* addInteger(CLI::App& app, const std::string& name, long long& value,
                        const std::string& help)
{
    return app
        .add_option_function<std::string>(
            name, [&value, name](const std::string& text) { value = parseInteger(text, name); },
            help)
        ->type_name("INT")
        ->default_str(std::to_string(value));
}

void checkThreads(long long threads)
{
    if (threads < 0 || threads > kMaxThreads)
        throw Error("", "--threads wants 0 (all cores) or a number up to " +
                            std::to_string(kMaxThreads) + ", got " + std::to_string(threads),
                    "leave it out to use every core");
}

CLI::Option* addThreads(CLI::App& app, long long& threads, const std::string& help)
{
    return app
        .add_option_function<std::string>(
            "--threads",
            [&threads](const std::string& text) {
                const long long n = parseInteger(text, "--threads");
                checkThreads(n);
                threads = n;
            },
            help)
        ->type_name("N");
}

CLI::Option* addInteger(CLI::App& app, const std::string& name, int& value,
                        const std::string& help)
{
    return app
        .add_option_function<std::string>(
            name,
            [&value, name](const std::string& text) {
                using Limits = std::numeric_limits<int>;
                value = int(std::clamp<long long>(parseInteger(text, name), Limits::min(),
                                                  Limits::max()));
            },
            help)
        ->type_name("INT")
        ->default_str(std::to_string(value));
}

CLI::Option* addIntegers(CLI::App& app, const std::string& name, std::vector<long long>& values,
                         const std::string& help)
{
    std::vector<std::string> defaults;
    for (long long v : values) defaults.push_back(std::to_string(v));
    return lastListWins(
        app.add_option_function<std::vector<std::string>>(
            name,
            [&values, name](const std::vector<std::string>& texts) {
                values.clear();
                for (const std::string& text : texts) values.push_back(parseInteger(text, name));
            },
            help))
        ->type_name("INT")
        ->default_str(defaults.empty() ? "" : showList(defaults));
}

CLI::Option* addCounts(CLI::App& app, const std::string& name, std::vector<int>& values,
                       const std::string& help)
{
    return lastListWins(
        app.add_option_function<std::vector<std::string>>(
            name,
            [&values, name](const std::vector<std::string>& texts) {
                values.clear();
                for (const std::string& text : texts) {
                    const double n = parseNumber(text, name);
                    if (n != std::floor(n))
                        throw Error("", name + " wants whole numbers, got " + text);
                    if (n <= 0) throw Error("", name + " must be positive, got " + text);
                    values.push_back(int(std::min(n, 1e9)));
                }
            },
            help))
        ->type_name("N")
        ->default_str(values.empty() ? "" : showList(shown(values)));
}

std::optional<int> parse(CLI::App& app, int argc, char** argv)
{
    // CLI11 takes "-5" for a value but "-.5" for the short option "-." followed by "5"; the
    // tools always read it as a number, so it is handed on as "-0.5". CLI11 wants the
    // arguments last first.
    std::vector<std::string> arguments;
    for (int i = argc - 1; i > 0; --i) {
        std::string argument = argv[i];
        if (argument.size() > 2 && argument[0] == '-' && argument[1] == '.' &&
            std::isdigit(static_cast<unsigned char>(argument[2])))
            argument.insert(1, "0");
        arguments.push_back(std::move(argument));
    }
    try {
        app.parse(std::move(arguments));
        return std::nullopt;
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return 0;
    } catch (const CLI::CallForAllHelp&) {
        std::cout << app.help("", CLI::AppFormatMode::All);
        return 0;
    } catch (const CLI::ParseError& e) {
        std::string command = app.get_name();
        for (const CLI::App* sub : app.get_subcommands()) command += " " + sub->get_name();
        const std::string fix = "see " + command + " --help";
        // CLI11 lists every argument it could not place (in reverse, in a subcommand); the
        // first one is the mistake.
        const std::vector<std::string> extras = app.remaining(true);
        if (dynamic_cast<const CLI::ExtrasError*>(&e) && !extras.empty()) {
            const std::string& first = extras.front();
            throw Error("", (first[0] == '-' ? "unknown option '" : "unexpected argument '") +
                                first + "'",
                        fix);
        }
        throw Error("", e.what(), fix);
    }
}

namespace {

/// Whether @a a and @a b name one file: the same file by two names (links included), or, when
/// one does not exist yet, the same path once resolved.
bool sameFile(const std::string& a, const std::string& b)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::equivalent(a, b, ec)) return true;
    const fs::path first = fs::weakly_canonical(a, ec);
    if (ec) return false;
    const fs::path second = fs::weakly_canonical(b, ec);
    return !ec && first == second;
}

} // namespace

void refuseOutputOverInput(const std::string& output, const std::string& option,
                           const std::vector<std::string>& inputs)
{
    if (output.empty()) return;
    for (const std::string& input : inputs)
        if (sameFile(output, input))
            throw Error(output, "is also an input (" + input + "): writing " + option +
                                    " there would destroy it",
                        "give " + option + " another file");
}

} // namespace lsdem::cli
