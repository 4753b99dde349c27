// Text helpers of the scene reader: trimming, splitting, numbers as typed and as shown, the
// nearest name for "did you mean", YAML nodes in messages.
#pragma once

#include "common/format.h"
#include "dda/types.h"

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace ddafem::scene_reading
{
std::string trim(const std::string& s);
std::vector<std::string> split(const std::string& s, char separator);
std::string join(const std::vector<std::string>& items, const std::string& separator);
/// "'a', 'b'".
std::string quoted_list(const std::vector<std::string>& names);
/// "[x, y]": a point as a scene spells it (a YAML flow sequence), where common/format.h's
/// format_point writes "(x, y)" for messages.
std::string format_point(const dda::Point& p);

/// "; did you mean 'X'?" for the candidate closest to `name`, if it is close; else "".
std::string suggestion(const std::string& name, const std::vector<std::string>& candidates);

/// A node as it would be written in flow style, shortened for messages.
std::string yaml_text(const YAML::Node& node);

/// The number a text holds (all of it, finite), if any.
std::optional<double> parse_double(const std::string& text);
std::optional<double> parse_double(const YAML::Node& node);
std::optional<long long> parse_integer(const YAML::Node& node);

/// The child of a map (without the side effects of non-const operator[]).
YAML::Node child(const YAML::Node& map, const std::string& key);
/// The node at `keys` below `node`, or an undefined node if some map on the way is missing.
YAML::Node nested(const YAML::Node& node, const std::vector<std::string>& keys);

} // namespace ddafem::scene_reading
