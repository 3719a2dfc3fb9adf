/// @file Error.h
/// @brief The one exception type lsdem throws for bad input: it names the file, the problem and
///        the fix, so a command-line tool can print it as is and exit non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace lsdem {

class Error : public std::runtime_error
{
public:
    /// @param where  the file (and place in it) the problem is about, or "" if none
    /// @param problem what is wrong, in one sentence
    /// @param fix    what the user can do about it, or "" if nothing obvious
    Error(const std::string& where, const std::string& problem, const std::string& fix = "")
        : std::runtime_error(compose(where, problem, fix)), mWhere(where), mProblem(problem),
          mFix(fix)
    {
    }

    const std::string& where() const { return mWhere; }
    const std::string& problem() const { return mProblem; }
    const std::string& fix() const { return mFix; }

private:
    static std::string compose(const std::string& where, const std::string& problem,
                               const std::string& fix)
    {
        std::string text = where.empty() ? problem : where + ": " + problem;
        if (!fix.empty()) text += "\n  fix: " + fix;
        return text;
    }

    std::string mWhere, mProblem, mFix;
};

} // namespace lsdem
