#include "xml_scan.hpp"

#include "byte_reader.hpp"

namespace pathlet::io {

const std::string_view* XmlTag::find(std::string_view key) const {
    for (auto& a : attrs)
        if (a.first == key) return &a.second;
    return nullptr;
}

std::string_view XmlTag::attr(std::string_view key, std::string_view def) const {
    auto* v = find(key);
    return v ? *v : def;
}

static bool name_char(char c) { return !is_space(c) && c != '=' && c != '>' && c != '/' && c != '<' && c != '"' && c != '\''; }

XmlTag parse_xml_tag(std::string_view s, size_t pos, const std::string& file) {
    XmlTag t;
    t.begin = pos;
    size_t i = pos + 1;
    auto fail = [&](const std::string& m) -> void { fail_at(file, at_byte(i), m); };
    if (i < s.size() && s[i] == '/') { t.closing = true; ++i; }
    size_t b = i;
    while (i < s.size() && name_char(s[i])) ++i;
    t.name = s.substr(b, i - b);
    if (t.name.empty()) fail("malformed XML tag (no element name)");
    while (true) {
        while (i < s.size() && is_space(s[i])) ++i;
        if (i >= s.size()) fail("XML tag <" + std::string(t.name) + "> is not closed (file truncated?)");
        if (s[i] == '>') { t.end = i + 1; return t; }
        if (s[i] == '/' && i + 1 < s.size() && s[i + 1] == '>') { t.self_closing = true; t.end = i + 2; return t; }
        size_t kb = i;
        while (i < s.size() && name_char(s[i])) ++i;
        auto key = s.substr(kb, i - kb);
        if (key.empty()) fail("malformed attribute in <" + std::string(t.name) + ">");
        while (i < s.size() && is_space(s[i])) ++i;
        if (i >= s.size() || s[i] != '=') fail("attribute '" + std::string(key) + "' has no value");
        ++i;
        while (i < s.size() && is_space(s[i])) ++i;
        if (i >= s.size() || (s[i] != '"' && s[i] != '\'')) fail("attribute '" + std::string(key) + "' value is not quoted");
        char q = s[i++];
        size_t vb = i;
        while (i < s.size() && s[i] != q) ++i;
        if (i >= s.size()) fail("attribute '" + std::string(key) + "' value is not terminated (file truncated?)");
        t.attrs.emplace_back(key, s.substr(vb, i - vb));
        ++i;
    }
}

std::vector<XmlTag> scan_xml(std::string_view s, const std::string& file) {
    std::vector<XmlTag> out;
    size_t i = 0;
    while ((i = s.find('<', i)) != std::string_view::npos) {
        auto rest = s.substr(i);
        auto skip_to = [&](std::string_view end_mark, const char* what) {
            size_t e = s.find(end_mark, i);
            if (e == std::string_view::npos) fail_at(file, at_byte(i), std::string(what) + " is not closed (file truncated?)");
            i = e + end_mark.size();
        };
        if (rest.substr(0, 4) == "<!--") skip_to("-->", "XML comment");
        else if (rest.substr(0, 9) == "<![CDATA[") skip_to("]]>", "CDATA section");
        else if (rest.substr(0, 2) == "<?") skip_to("?>", "XML declaration");
        else if (rest.substr(0, 2) == "<!") skip_to(">", "DOCTYPE");
        else {
            out.push_back(parse_xml_tag(s, i, file));
            i = out.back().end;
        }
    }
    return out;
}

}  // namespace pathlet::io
