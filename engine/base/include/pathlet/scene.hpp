// Scene model: what the importers produce and what passes draw.
// CPU side only (no GL here); engine/sdk/src/gpu_scene.* uploads it once.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlet {

// Error for bad input files: carries the file and a location (byte offset or line).
struct DataError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Bounds {
    glm::vec3 lo{0.0f}, hi{0.0f};
    bool valid() const { return lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z; }
    glm::vec3 center() const { return 0.5f * (lo + hi); }
    float radius() const { return 0.5f * glm::length(hi - lo); }
};

struct LineRange {
    uint32_t first = 0;  // index of the first point
    uint32_t count = 0;  // number of points (>= 2 for a drawable line)
};

// Units of a data set where its source says them ("mm", "s", "mm/s"); "" = not known, and
// then nothing shows one (the legend says "speed", the time label has no "s").
struct Units {
    std::string length, time, velocity;
    bool operator==(const Units&) const = default;
};

// A point array of a data file beside time and velocity (pressure, vorticity, ...): one value
// per point, a vector array as its magnitude. Importers keep them with their points through
// repair; the native .pathlet cache does not store them.
struct PointArray {
    std::string name;
    std::vector<float> values;
};

// Pathlines: per point position, time and velocity; lines are ranges of points.
// Time increases along each line (importers sort or reject otherwise).
struct Pathlines {
    std::vector<glm::vec3> position;
    std::vector<float> time;
    std::vector<glm::vec3> velocity;
    std::vector<LineRange> lines;
    std::vector<PointArray> arrays;  // the file's other point arrays, one value per point
    Units units;
    // Streamlines without a time of their own (tractography, centrelines): `time` is a
    // pseudo-time along the arc length and `velocity` the tangent at a constant pseudo-speed;
    // line passes draw these lines whole and the overlay shows no time or speed legend.
    bool timeless = false;

    size_t point_count() const { return position.size(); }
    size_t line_count() const { return lines.size(); }
    bool empty() const { return lines.empty(); }

    Bounds bounds() const;            // over finite positions
    float time_min() const;           // 0 when empty
    float time_max() const;
    float speed_min() const;          // |velocity|, 0 when empty
    float speed_max() const;
    const PointArray* array(const std::string& name) const;  // nullptr when there is none of that name
    // Throws DataError naming `what` if sizes disagree or a range is out of bounds.
    void check_consistent(const std::string& what) const;
};

// Triangle mesh (vessel wall). Normals are optional (computed when empty).
struct Mesh {
    std::vector<glm::vec3> position;
    std::vector<glm::vec3> normal;
    std::vector<uint32_t> index;  // triangles, 3 per face

    bool empty() const { return index.empty(); }
    Bounds bounds() const;
    void compute_normals();  // area-weighted vertex normals
    // Vertex clustering on a grid of `cell` world units: the vertices of a cell merge into
    // their mean (normals averaged), triangles that collapse or repeat are dropped. Keeps the
    // winding. For context geometry drawn far more finely than the screen shows it.
    Mesh simplified(float cell) const;
};

struct Scene {
    Pathlines lines;
    std::optional<Mesh> mesh;
    std::string source;  // where it came from, for logs and reports

    Bounds bounds() const;  // lines and mesh together
};

}  // namespace pathlet
