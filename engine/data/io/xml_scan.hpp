// A minimal XML tag scanner for VTK XML files (no dependency): yields start/end tags with
// attributes and their byte positions; character data is taken by the caller between
// tags. Comments, processing instructions and DOCTYPEs are skipped. Entities are not
// expanded (VTK writes none in the places we read).
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pathlet::io {

struct XmlTag {
    std::string_view name;
    std::vector<std::pair<std::string_view, std::string_view>> attrs;
    bool closing = false;       // </name>
    bool self_closing = false;  // <name/>
    size_t begin = 0, end = 0;  // '<' and one past '>'

    const std::string_view* find(std::string_view key) const;
    std::string_view attr(std::string_view key, std::string_view def = {}) const;
};

// Parses the tag whose '<' is at `pos`. Fails with "<file>: byte N: ..." on malformed tags.
XmlTag parse_xml_tag(std::string_view text, size_t pos, const std::string& file);

// All tags in text, in order.
std::vector<XmlTag> scan_xml(std::string_view text, const std::string& file);

}  // namespace pathlet::io
