/// @file CommandLine.h
/// @brief A small strict command-line reader shared by the lsdem tools: every value is checked
///        (numbers must parse completely and be finite), and mistakes become lsdem::Error with
///        the option named.
#pragma once

#include "lsdem/ls/Error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace lsdem::cli {

class Arguments
{
public:
    Arguments(int argc, char** argv) : mArgs(argv + 1, argv + argc) {}

    bool done() const { return mPos >= mArgs.size(); }
    const std::string& peek() const { return mArgs[mPos]; }
    std::string next() { return mArgs[mPos++]; }

    /// The value after option @a option, which must exist.
    std::string value(const std::string& option)
    {
        if (done()) throw Error("", "option " + option + " needs a value");
        return next();
    }

    double number(const std::string& option) { return parseNumber(value(option), option); }

    /// The values after option @a option up to the next option, at least one. A leading minus
    /// followed by a digit or a dot is a value ("-0.5"), otherwise an option ("--x", "-q").
    std::vector<std::string> values(const std::string& option)
    {
        std::vector<std::string> out;
        while (!done() && !looksLikeOption(peek())) out.push_back(next());
        if (out.empty()) throw Error("", "option " + option + " needs at least one value");
        return out;
    }

    std::vector<double> numbers(const std::string& option)
    {
        std::vector<double> out;
        for (const std::string& text : values(option)) out.push_back(parseNumber(text, option));
        return out;
    }

    /// Whole positive numbers after @a option (node counts and the like).
    std::vector<int> positiveCounts(const std::string& option)
    {
        std::vector<int> out;
        for (const std::string& text : values(option)) {
            const double n = parseNumber(text, option);
            if (n != std::floor(n)) throw Error("", option + " wants whole numbers, got " + text);
            if (n <= 0) throw Error("", option + " must be positive, got " + text);
            out.push_back(int(std::min(n, 1e9)));
        }
        return out;
    }

    long long integer(const std::string& option)
    {
        const std::string text = value(option);
        char* end = nullptr;
        const long long v = std::strtoll(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0')
            throw Error("", "option " + option + " wants a whole number, got '" + text + "'");
        return v;
    }

    static double parseNumber(const std::string& text, const std::string& option)
    {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0')
            throw Error("", "option " + option + " wants a number, got '" + text + "'");
        if (!std::isfinite(v))
            throw Error("", "option " + option + " wants a finite number, got '" + text + "'");
        return v;
    }

private:
    static bool looksLikeOption(const std::string& text)
    {
        return text.size() > 1 && text[0] == '-' &&
               !(std::isdigit(static_cast<unsigned char>(text[1])) || text[1] == '.');
    }

    std::vector<std::string> mArgs;
    size_t mPos = 0;
};

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
