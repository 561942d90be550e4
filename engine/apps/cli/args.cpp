#include "args.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace pathlet::cli {

Args& Args::flag(const std::string& name, const std::string& help) {
    opts_.push_back({name, "", "", help, true, false});
    return *this;
}
Args& Args::option(const std::string& name, const std::string& value_name, const std::string& def,
                   const std::string& help) {
    opts_.push_back({name, value_name, def, help, false, false});
    return *this;
}
Args& Args::multi(const std::string& name, const std::string& value_name, const std::string& help) {
    opts_.push_back({name, value_name, "", help, false, true});
    return *this;
}
Args& Args::positional(const std::string& name, const std::string& help, bool required) {
    pos_.push_back({name, help, required});
    return *this;
}
Args& Args::example(const std::string& line, const std::string& what) {
    examples_.emplace_back(line, what);
    return *this;
}

Args& Args::short_name(char c) {
    if (!opts_.empty()) opts_.back().short_name = c;
    return *this;
}

const Args::Opt* Args::find(const std::string& name) const {
    for (const auto& o : opts_)
        if (o.name == name) return &o;
    return nullptr;
}

bool Args::parse(const std::vector<std::string>& argv) {
    size_t next_pos = 0;
    for (size_t i = 0; i < argv.size(); ++i) {
        std::string a = argv[i];
        if (a.size() == 2 && a[0] == '-' && a[1] != '-')
            for (const auto& o : opts_)
                if (o.short_name == a[1]) a = "--" + o.name;
        if (a == "--help" || a == "-h") {
            std::fputs(help().c_str(), stdout);
            return false;
        }
        if (a.rfind("--", 0) == 0 && a.size() > 2) {
            std::string name = a.substr(2), value;
            bool inline_value = false;
            if (auto eq = name.find('='); eq != std::string::npos) {
                value = name.substr(eq + 1);
                name = name.substr(0, eq);
                inline_value = true;
            }
            const Opt* o = find(name);
            if (!o) {
                std::string best;
                size_t best_d = 99;
                for (const auto& c : opts_) {
                    // cheap "did you mean": shared prefix length / edit distance is overkill here
                    size_t common = 0;
                    while (common < c.name.size() && common < name.size() && c.name[common] == name[common]) ++common;
                    size_t d = std::max(c.name.size(), name.size()) - common;
                    if (d < best_d) best_d = d, best = c.name;
                }
                std::string msg = "unknown option --" + name;
                if (!best.empty() && best_d <= 4) msg += " (did you mean --" + best + "?)";
                throw UsageError(msg);
            }
            if (o->is_flag) {
                if (inline_value) throw UsageError("--" + name + " takes no value");
                values_[name].push_back("1");
                continue;
            }
            if (!inline_value) {
                if (i + 1 >= argv.size()) throw UsageError("--" + name + " needs a value (" + o->value_name + ")");
                value = argv[++i];
            }
            if (!o->is_multi) values_[name].clear();
            values_[name].push_back(value);
            continue;
        }
        if (next_pos >= pos_.size()) throw UsageError("unexpected argument '" + a + "'");
        positionals_[pos_[next_pos++].name] = a;
    }
    for (size_t k = next_pos; k < pos_.size(); ++k)
        if (pos_[k].required) throw UsageError("missing " + pos_[k].name);
    return true;
}

bool Args::has(const std::string& name) const { return values_.count(name) > 0; }

std::string Args::get(const std::string& name) const {
    auto it = values_.find(name);
    if (it != values_.end() && !it->second.empty()) return it->second.back();
    const Opt* o = find(name);
    return o ? o->def : std::string();
}

double Args::number(const std::string& name) const {
    std::string v = get(name);
    try {
        size_t used = 0;
        double d = std::stod(v, &used);
        if (used != v.size()) throw std::invalid_argument("");
        return d;
    } catch (const std::exception&) {
        throw UsageError("--" + name + " expects a number, got '" + v + "'");
    }
}

long Args::integer(const std::string& name) const {
    std::string v = get(name);
    try {
        size_t used = 0;
        long d = std::stol(v, &used);
        if (used != v.size()) throw std::invalid_argument("");
        return d;
    } catch (const std::exception&) {
        throw UsageError("--" + name + " expects an integer, got '" + v + "'");
    }
}

std::vector<std::string> Args::all(const std::string& name) const {
    auto it = values_.find(name);
    return it == values_.end() ? std::vector<std::string>{} : it->second;
}

std::string Args::pos(const std::string& name) const {
    auto it = positionals_.find(name);
    return it == positionals_.end() ? std::string() : it->second;
}

std::string Args::help() const {
    std::ostringstream s;
    s << "usage: pathlet " << command_;
    for (const auto& p : pos_) s << (p.required ? " " : " [") << p.name << (p.required ? "" : "]");
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
            if (!o.is_flag) s << " " << o.value_name;
            if (o.is_multi) s << "  (repeatable)";
            s << "\n      " << o.help;
            if (!o.is_flag && !o.def.empty()) s << " [default: " << o.def << "]";
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
