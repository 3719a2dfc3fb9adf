#include "common/HelpFormatter.h"

#include <sstream>
#include <vector>

namespace lsdem::cli {

std::string HelpFormatter::make_help(const CLI::App* app, std::string name,
                                     CLI::AppFormatMode mode) const
{
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    return make_usage(app, name) + "\n" + make_description(app) + make_positionals(app) +
           groups(app, mode) + make_subcommands(app, mode) + "\n" + make_footer(app);
}

std::string HelpFormatter::make_subcommand(const CLI::App* sub) const
{
    const std::string& description = sub->get_description();
    const std::string firstLine = description.substr(0, description.find('\n'));
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_name(), firstLine, column_width_);
    return out.str();
}

std::string HelpFormatter::make_option_usage(const CLI::Option* positional) const
{
    return "[" + positional->get_type_name() + "]";
}

std::string HelpFormatter::make_option_name(const CLI::Option* option, bool positional) const
{
    return positional ? option->get_type_name() : Formatter::make_option_name(option, false);
}

std::string HelpFormatter::make_option_opts(const CLI::Option* option) const
{
    return option->get_positional() ? "" : Formatter::make_option_opts(option);
}

std::string HelpFormatter::groups(const CLI::App* app, CLI::AppFormatMode mode) const
{
    std::string out;
    for (const std::string& group : app->get_groups()) {
        const std::vector<const CLI::Option*> options =
            app->get_options([&](const CLI::Option* o) {
                const bool help = o == app->get_help_ptr() || o == app->get_help_all_ptr();
                return o->get_group() == group && o->nonpositional() &&
                       (mode != CLI::AppFormatMode::Sub || !help);
            });
        if (!group.empty() && !options.empty()) out += make_group(group, false, options);
    }
    return out;
}

} // namespace lsdem::cli
