#include "args.hpp"

#include "bench/shard.hpp"
#include "renderer.hpp"
#include "util/text.hpp"
#include <pathlet/text.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace pathlet::cli {

namespace {

// Whole-text numbers: "9" and "1e3" but not "9s", "x" or "" (std::stod alone accepts "9s").
template <class T, class F>
T whole(const std::string& text, F parse, const char* expected) {
    try {
        size_t used = 0;
        T v = parse(text, &used);
        if (used == text.size()) return v;
    } catch (const std::exception&) {
    }
    throw std::invalid_argument(std::string("expects ") + expected + ", got '" + text + "'");
}

std::string number_text(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

}  // namespace

void convert(const std::string& text, std::string& out) { out = text; }
void convert(const std::string& text, double& out) {
    out = whole<double>(text, [](const std::string& s, size_t* n) { return std::stod(s, n); }, "a number");
    if (!std::isfinite(out)) throw std::invalid_argument("expects a finite number, got '" + text + "'");
}
void convert(const std::string& text, float& out) {
    double d = 0;
    convert(text, d);
    if (std::fabs(d) > 3.0e38) throw std::invalid_argument("expects a number within a float's range, got '" + text + "'");
    out = float(d);
}
void convert(const std::string& text, long& out) {
    out = whole<long>(text, [](const std::string& s, size_t* n) { return std::stol(s, n); }, "an integer");
}
void convert(const std::string& text, int& out) {
    out = whole<int>(text, [](const std::string& s, size_t* n) { return std::stoi(s, n); }, "an integer");
}
void convert(const std::string& text, glm::ivec2& out) { out = parse_size(text); }
void convert(const std::string& text, TimeRange& out) { out = parse_time_range(text); }
void convert(const std::string& text, TimingBackend& out) {
    try {
        out = parse_timing_backend(text);
    } catch (const std::exception&) {
        throw std::invalid_argument("expects auto, gpu, finish or cpu, got '" + text + "'");
    }
}
void convert(const std::string& text, Shard& out) { out = parse_shard(text); }

std::string shown(const std::string& v) { return v; }
std::string shown(double v) { return number_text(v); }
std::string shown(float v) { return number_text(v); }
std::string shown(int v) { return std::to_string(v); }
std::string shown(long v) { return std::to_string(v); }
std::string shown(const glm::ivec2& v) { return std::to_string(v.x) + "x" + std::to_string(v.y); }
std::string shown(const TimeRange& v) {
    return v.end == v.start ? number_text(v.start)
                            : number_text(v.start) + ":" + number_text(v.end) + ":" + number_text(v.step);
}
std::string shown(TimingBackend v) { return to_string(v); }
std::string shown(const Shard&) { return ""; }

Args& Args::add(Opt o) {
    if (o.name.empty() || o.name.rfind("-", 0) == 0 || o.name == "help")
        throw DeclarationError("pathlet " + command_ + ": option name '" + o.name + "' (give it without dashes; --help is built in)");
    if (find(o.name)) throw DeclarationError("pathlet " + command_ + ": option --" + o.name + " is declared twice");
    opts_.push_back(std::move(o));
    return *this;
}

Args& Args::flag(const std::string& name, bool& out, const std::string& help) {
    return add({name, "", help, "", Kind::Flag, [&out](const std::string&) { out = true; }});
}

Args& Args::multi(const std::string& name, std::vector<std::string>& out, const std::string& value_name,
                  const std::string& help) {
    return add({name, value_name, help, "", Kind::Multi, [&out](const std::string& v) { out.push_back(v); }});
}

Args& Args::short_name(char c) {
    if (opts_.empty()) throw DeclarationError("pathlet " + command_ + ": short_name before any option");
    for (const auto& o : opts_)
        if (o.short_name == c || c == 'h')
            throw DeclarationError("pathlet " + command_ + ": short name -" + std::string(1, c) + " is used twice");
    opts_.back().short_name = c;
    return *this;
}

Args& Args::positional(const std::string& name, std::string& out, const std::string& help, bool required) {
    if (!pos_.empty() && (pos_.back().rest || (!pos_.back().required && required)))
        throw DeclarationError("pathlet " + command_ + ": positional " + name + " follows an optional or repeating one");
    pos_.push_back({name, help, required, false, [&out](const std::string& v) { out = v; }});
    return *this;
}

Args& Args::rest(const std::string& name, std::vector<std::string>& out, const std::string& help) {
    if (!pos_.empty() && (pos_.back().rest || !pos_.back().required))
        throw DeclarationError("pathlet " + command_ + ": positional " + name + " follows an optional or repeating one");
    pos_.push_back({name, help, true, true, [&out](const std::string& v) { out.push_back(v); }});
    return *this;
}

Args& Args::example(const std::string& line, const std::string& what) {
    examples_.emplace_back(line, what);
    return *this;
}

const Args::Opt* Args::find(const std::string& name) const {
    for (const auto& o : opts_)
        if (o.name == name) return &o;
    return nullptr;
}

void Args::assign(const Opt& o, const std::string& value) const {
    try {
        o.set(value);
    } catch (const std::invalid_argument& e) {
        const std::string why = e.what();
        throw UsageError(why.rfind("--", 0) == 0 ? why : "--" + o.name + " " + why);
    } catch (const std::out_of_range&) {
        throw UsageError("--" + o.name + " '" + value + "' is out of range");
    }
}

bool Args::parse(const std::vector<std::string>& argv) {
    size_t next_pos = 0;
    bool rest_seen = false, options_end = false;
    for (size_t i = 0; i < argv.size(); ++i) {
        std::string a = argv[i];
        if (!options_end && a == "--") {
            options_end = true;
            continue;
        }
        if (!options_end && a.size() == 2 && a[0] == '-' && a[1] != '-' && a[1] != 'h') {
            const Opt* s = nullptr;
            for (const auto& o : opts_)
                if (o.short_name == a[1]) s = &o;
            if (!s) throw UsageError("unknown option " + a);
            a = "--" + s->name;
        }
        if (!options_end && (a == "--help" || a == "-h")) {
            std::fputs(help().c_str(), stdout);
            return false;
        }
        if (!options_end && a.rfind("--", 0) == 0) {
            std::string name = a.substr(2), value;
            bool inline_value = false;
            if (auto eq = name.find('='); eq != std::string::npos) {
                value = name.substr(eq + 1);
                name = name.substr(0, eq);
                inline_value = true;
            }
            const Opt* o = find(name);
            if (!o) {
                std::vector<std::string> names, longer;
                for (const auto& c : opts_) {
                    names.push_back(c.name);
                    if (name.size() >= 3 && c.name.rfind(name, 0) == 0) longer.push_back(c.name);
                }
                std::string best = text::closest_match(name, names);
                if (best.empty() && longer.size() == 1) best = longer[0];  // --plugin: --plugin-dir
                throw UsageError("unknown option --" + name + (best.empty() ? "" : " (did you mean --" + best + "?)"));
            }
            given_.push_back(o->name);
            if (o->kind == Kind::Flag) {
                if (inline_value) throw UsageError("--" + name + " takes no value");
                o->set("");
                continue;
            }
            if (!inline_value) {
                if (i + 1 >= argv.size()) throw UsageError("--" + name + " needs a value (" + o->value_name + ")");
                value = argv[++i];
            }
            assign(*o, value);
            continue;
        }
        if (next_pos >= pos_.size()) throw UsageError("unexpected argument '" + a + "'");
        pos_[next_pos].set(a);
        if (pos_[next_pos].rest) rest_seen = true;
        else ++next_pos;
    }
    for (size_t k = next_pos; k < pos_.size(); ++k)
        if (pos_[k].required && !(pos_[k].rest && rest_seen)) throw UsageError("missing " + pos_[k].name);
    return true;
}

bool Args::given(const std::string& name) const {
    return std::find(given_.begin(), given_.end(), name) != given_.end();
}

void Args::unused_here(const std::vector<std::string>& names, const std::string& why) const {
    for (const auto& n : names) {
        if (!find(n)) throw DeclarationError("Args::unused_here: --" + n + " is not an option of " + command_);
        if (given(n)) throw UsageError("--" + n + " does nothing " + why);
    }
}

std::string Args::help() const {
    std::ostringstream s;
    s << "usage: pathlet " << command_;
    for (const auto& p : pos_) s << (p.required ? " " : " [") << p.name << (p.rest ? "..." : "") << (p.required ? "" : "]");
    if (!opts_.empty()) s << " [options]";
    s << "\n\n" << summary_ << "\n";
    if (!pos_.empty()) {
        s << "\narguments:\n";
        for (const auto& p : pos_) s << "  " << p.name << "\n      " << p.help << "\n";
    }
    if (!opts_.empty()) {
        s << "\noptions:\n";
        for (const auto& o : opts_) {
            s << "  " << (o.short_name ? std::string("-") + o.short_name + ", " : std::string()) << "--" << o.name;
            if (o.kind != Kind::Flag) s << " " << o.value_name;
            if (o.kind == Kind::Multi) s << "  (repeatable)";
            s << "\n      " << o.help;
            if (o.kind == Kind::Value && !o.def.empty()) s << " [default: " << o.def << "]";
            s << "\n";
        }
    }
    if (!examples_.empty()) {
        s << "\nexamples:\n";
        for (const auto& [line, what] : examples_) s << "  " << line << "\n      " << what << "\n";
    }
    return s.str();
}

}  // namespace pathlet::cli
