// The command-line parser shared by the subcommands. Each option is declared once, bound to a
// typed variable (name, value name, help; the variable's initial value is the default), and
// that declaration drives parsing, conversion and --help. A command reads its variables, never
// option names, so an option it did not declare cannot be asked for.
//
// Errors: a bad command line (unknown option, missing or malformed value, a value out of its
// range, a single-valued option given twice) throws UsageError, which main() prints with the command's name and exits 2. A bad
// declaration (an option declared twice, a short name used twice) throws DeclarationError: a
// programming error (exit 70), caught by the test that runs every command's --help.
#pragma once

#include <glm/vec2.hpp>

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {
struct TimeRange;
enum class TimingBackend;
}  // namespace pathlet

namespace pathlet::cli {

struct Shard;

// Thrown for bad command lines; main() prints it with the subcommand's usage and exits 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Input that names what is not there or does not fit (a time outside the data): main() prints
// "error: MESSAGE" (one line that names what was given and the fix) and exits 2. A graph name
// that names nothing (GraphNotFound) is printed the same way.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A bug in a command's option declarations, never the user's fault.
struct DeclarationError : std::logic_error {
    using std::logic_error::logic_error;
};

// A value with a default that also knows whether the command line gave it (bench: a --size on
// the command line overrides the experiment's sizes, the default does not).
template <class T>
struct Given {
    T value{};
    bool given = false;
};

// Text -> value, for the types options are bound to. Each throws std::invalid_argument with
// what was expected; a message that starts with "--" is used as it is.
void convert(const std::string& text, std::string& out);
void convert(const std::string& text, double& out);
void convert(const std::string& text, float& out);
void convert(const std::string& text, int& out);
void convert(const std::string& text, long& out);
void convert(const std::string& text, glm::ivec2& out);  // WxH, as --size (1..16384)
void convert(const std::string& text, TimeRange& out);   // T, A:B or A:B:STEP, as --time
void convert(const std::string& text, TimingBackend& out);  // auto, gpu, finish
void convert(const std::string& text, Shard& out);       // I/N
template <class T>
void convert(const std::string& text, std::optional<T>& out) {
    T v{};
    convert(text, v);
    out = v;
}
template <class T>
void convert(const std::string& text, Given<T>& out) {
    convert(text, out.value);
    out.given = true;
}
// The default as --help shows it ("" for none).
std::string shown(const std::string& v);
std::string shown(double v);
std::string shown(float v);
std::string shown(int v);
std::string shown(long v);
std::string shown(const glm::ivec2& v);
std::string shown(const TimeRange& v);
std::string shown(TimingBackend v);
std::string shown(const Shard& v);
template <class T>
std::string shown(const std::optional<T>& v) { return v ? shown(*v) : std::string(); }
template <class T>
std::string shown(const Given<T>& v) { return shown(v.value); }

class Args {
public:
    Args(std::string command, std::string summary) : command_(std::move(command)), summary_(std::move(summary)) {}

    // An option with a value (--size WxH), converted into `out` when given.
    template <class T>
    Args& option(const std::string& name, T& out, const std::string& value_name, const std::string& help) {
        return add({name, value_name, help, shown(out), Kind::Value,
                    [&out](const std::string& v) { convert(v, out); }});
    }
    // A flag without a value (--quiet): sets `out` to true.
    Args& flag(const std::string& name, bool& out, const std::string& help);
    // A repeatable option (--set a=b --set c=d): every value, in order.
    Args& multi(const std::string& name, std::vector<std::string>& out, const std::string& value_name,
                const std::string& help);
    // An option that takes every argument after it up to the next option (--data a.tck b.tck,
    // what a shell glob expands to), repeatable: every value, in order.
    Args& list(const std::string& name, std::vector<std::string>& out, const std::string& value_name,
               const std::string& help);
    // A one-letter alias for the option declared last: .option("output", ...).short_name('o')
    Args& short_name(char c);
    // Positional arguments, in order. `rest` takes every remaining one (at least one).
    Args& positional(const std::string& name, std::string& out, const std::string& help, bool required = true);
    Args& rest(const std::string& name, std::vector<std::string>& out, const std::string& help);
    Args& example(const std::string& line, const std::string& what);

    // Returns false when --help was asked for (help already printed to stdout). The whole command
    // line is read before any value is converted, so a single-valued option given twice is
    // named ("--size given twice: 640x360 and 1280x720") whatever its values.
    bool parse(const std::vector<std::string>& argv);
    // After parse: whether the command line gave the option --name.
    bool given(const std::string& name) const;
    // An option a command would ignore is an error, not silence: throws UsageError
    // "--NAME does nothing WHY" for the first of `names` the command line gave
    // (e.g. unused_here({"threshold"}, "without --compare")).
    void unused_here(const std::vector<std::string>& names, const std::string& why) const;
    std::string help() const;

private:
    enum class Kind { Value, Flag, Multi, List };
    struct Opt {
        std::string name, value_name, help, def;
        Kind kind = Kind::Value;
        std::function<void(const std::string&)> set;
        char short_name = 0;
    };
    struct Pos {
        std::string name, help;
        bool required = true, rest = false;
        std::function<void(const std::string&)> set;
    };
    Args& add(Opt o);
    const Opt* find(const std::string& name) const;
    const Opt& find_given(const std::string& name) const;  // an option the command line names, else UsageError
    void assign(const Opt& o, const std::string& value) const;

    std::string command_, summary_;
    std::vector<Opt> opts_;
    std::vector<Pos> pos_;
    std::vector<std::pair<std::string, std::string>> examples_;
    std::vector<std::string> given_;  // options the command line gave, in order
};

}  // namespace pathlet::cli
