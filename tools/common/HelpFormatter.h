/// @file HelpFormatter.h
/// @brief The layout of the tools' --help on top of CLI11's: the usage first, then what the
///        program does, then the options by group with one blank line between groups; a
///        positional argument shown once, by its metavariable (MESH); a subcommand listed by
///        the first line of its description.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace lsdem::cli {

class HelpFormatter : public CLI::Formatter
{
public:
    std::string make_help(const CLI::App* app, std::string name,
                          CLI::AppFormatMode mode) const override;
    std::string make_subcommand(const CLI::App* sub) const override;
    std::string make_option_usage(const CLI::Option* positional) const override;
    std::string make_option_name(const CLI::Option* option, bool positional) const override;
    std::string make_option_opts(const CLI::Option* option) const override;

private:
    /// Formatter::make_groups (not virtual) without its second blank line between groups.
    std::string groups(const CLI::App* app, CLI::AppFormatMode mode) const;
};

} // namespace lsdem::cli
