// Tiny command-line parser shared by the subcommands: options are declared once
// (name, value name, default, help) and that declaration drives parsing and --help.
#pragma once

#include <map>
#include <stdexcept>
#include <optional>
#include <string>
#include <vector>

namespace pathlet::cli {

// Thrown for bad command lines; main() prints it with the subcommand's usage and exits 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Args {
public:
    Args(std::string command, std::string summary) : command_(std::move(command)), summary_(std::move(summary)) {}

    // A flag without a value (--orbit-off), or an option with one (--size WxH).
    Args& flag(const std::string& name, const std::string& help);
    Args& option(const std::string& name, const std::string& value_name, const std::string& def, const std::string& help);
    // Repeatable option (--set a=b --set c=d).
    Args& multi(const std::string& name, const std::string& value_name, const std::string& help);
    Args& positional(const std::string& name, const std::string& help, bool required = true);
    Args& example(const std::string& line, const std::string& what);
    // A one-letter alias for the option declared last: .option("output", ...).short_name('o')
    Args& short_name(char c);

    // Returns false when --help was asked for (help already printed to stdout).
    bool parse(const std::vector<std::string>& argv);

    bool has(const std::string& name) const;          // flag given, or option given explicitly
    std::string get(const std::string& name) const;   // value or default
    double number(const std::string& name) const;     // parses, UsageError naming the option
    long integer(const std::string& name) const;
    std::vector<std::string> all(const std::string& name) const;
    std::string pos(const std::string& name) const;   // "" if an optional positional is absent
    std::string help() const;

private:
    struct Opt {
        std::string name, value_name, def, help;
        bool is_flag = false, is_multi = false;
        char short_name = 0;
    };
    struct Pos {
        std::string name, help;
        bool required;
    };
    std::string command_, summary_;
    std::vector<Opt> opts_;
    std::vector<Pos> pos_;
    std::vector<std::pair<std::string, std::string>> examples_;
    std::map<std::string, std::vector<std::string>> values_;
    std::map<std::string, std::string> positionals_;
    const Opt* find(const std::string& name) const;
};

}  // namespace pathlet::cli
