// Units of a data set (pathlet::Units): what the formats carry (VTK field data LengthUnit,
// TimeUnit, VelocityUnit; the native cache's units block), what the user gives with
// --units LENGTH[,VELOCITY], and how a derived quantity's unit follows from the others.
#pragma once

#include <pathlet/scene.hpp>

#include <string>
#include <string_view>

namespace pathlet::io {

// Field-data array names for the three units, in the order length, time, velocity.
inline constexpr const char* kUnitArrays[3] = {"LengthUnit", "TimeUnit", "VelocityUnit"};
// Which unit a field-data array name stands for (case-insensitive, also length_unit ...):
// 0 length, 1 time, 2 velocity, -1 none.
int unit_array_index(std::string_view name);
std::string& unit_slot(Units& u, int index);

// A unit string as read from a file, or "" when it is not one we can show (empty, longer
// than 24 bytes, or with control or non-printable bytes).
std::string sanitize_unit(std::string_view raw);

// Velocity derived from positions over time: "mm" over "s" is "mm/s"; "" unless both known.
std::string derived_velocity_unit(const Units& u);

// --units LENGTH[,VELOCITY] applied over what the file said: the length, and the velocity
// (given; else the file's; else LENGTH/TIME when the data's time unit is known). Throws
// std::invalid_argument naming the problem for a bad spec. An empty spec changes nothing.
void apply_units_option(Units& u, const std::string& spec);

// "length mm, time s, velocity mm/s" (the known ones) or "not given".
std::string describe_units(const Units& u);

}  // namespace pathlet::io
