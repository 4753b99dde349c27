// `tunnel.bolts`: a pattern of radial rock bolts from the opening's surface into the rock,
// written into the scene as `bolts` entries before the blocks are read (docs/support.md).
#pragma once

#include "app/scene/map_reader.h"
#include "dda/rock_mass.h"

#include <yaml-cpp/yaml.h>

#include <vector>

namespace ddafem
{
/// The pattern of `tunnel.bolts` (its count or spacing: pattern_count in tunnel_bolts.cc).
struct BoltPattern
{
  double length = 0.0;      ///< of each bolt [m]
  double from_angle = 30.0; ///< first bolt's direction, anticlockwise from +x [deg]
  double to_angle = 150.0;  ///< last bolt's direction [deg]
};

/// One radial bolt's line.
struct RadialBolt
{
  double angle = 0.0; ///< direction, anticlockwise from +x [deg]
  dda::Point head;    ///< where the ray from the centre leaves the opening [m]
  dda::Point anchor;  ///< head + length (cos angle, sin angle) [m]
};

/// The centre the pattern radiates from: a circle's centre, a horseshoe's roof centre (the
/// middle of its springline), a polygon's bounding-box centre [m].
dda::Point pattern_centre(const dda::Opening& opening);

/// Where the ray from `centre` at `angle` [deg] first leaves the polygon [m] (the centre lies
/// inside it); the centre itself if the ray meets no edge.
dda::Point ray_exit(const std::vector<dda::Point>& polygon, const dda::Point& centre, double angle);

/// The perimeter length [m] of the polygon between the rays at from and to [deg] (the polyline
/// through the rays' exits every 0.1 deg, at least).
double perimeter_between(const std::vector<dda::Point>& polygon, const dda::Point& centre,
                         double from, double to);

/// `count` bolts of `length` [m] equally spaced in angle from `from` to `to` [deg] (one bolt: at
/// their middle).
std::vector<RadialBolt> radial_bolts(const std::vector<dda::Point>& polygon,
                                     const dda::Point& centre, double from, double to,
                                     std::size_t count, double length);

/// Reads `tunnel.bolts` (r) and appends its bolts to root["bolts"] (after the scene's own).
void write_tunnel_bolts(const scene_reading::MapReader& r, const dda::Opening& opening,
                        double chord_tolerance, YAML::Node& root);

} // namespace ddafem
