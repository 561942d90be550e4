#include "oit_lists.hpp"

#include <cstring>

namespace pathlet {

OitLists read_oit_lists(const Executor& ex) {
    OitLists l;
    const Texture h = ex.texture("heads");
    l.width = h.width;
    l.height = h.height;
    l.heads.resize(size_t(h.width) * size_t(h.height));
    glGetTextureImage(h.id, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(l.heads.size() * 4), l.heads.data());
    const Buffer b = ex.buffer("nodes");
    l.nodes.resize(b.bytes / 16);
    glGetNamedBufferSubData(b.id, 0, GLsizeiptr(l.nodes.size() * 16), l.nodes.data());
    return l;
}

glm::dvec4 node_color(GLuint c) {
    return glm::dvec4(c & 255u, (c >> 8) & 255u, (c >> 16) & 255u, c >> 24) / 255.0;
}

double node_depth(const glm::uvec4& n) {
    float d;
    std::memcpy(&d, &n.y, 4);
    return d;
}

}  // namespace pathlet
