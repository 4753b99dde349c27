#include "app/scene/scene_text.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace ddafem::scene_reading
{
namespace
{
/// Levenshtein distance (insertions, deletions, substitutions).
std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      current[j] = std::min(
          {previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(previous, current);
  }
  return previous[b.size()];
}
} // namespace

std::string trim(const std::string& s)
{
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
    return "";
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& s, char separator)
{
  std::vector<std::string> parts;
  std::string::size_type begin = 0;
  while (true)
  {
    const auto end = s.find(separator, begin);
    parts.push_back(s.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos)
      return parts;
    begin = end + 1;
  }
}

std::string join(const std::vector<std::string>& items, const std::string& separator)
{
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i)
    s += (i == 0 ? "" : separator) + items[i];
  return s;
}

std::string format_point(const dda::Point& p)
{
  return "[" + format_number(p.x()) + ", " + format_number(p.y()) + "]";
}

std::string quoted_list(const std::vector<std::string>& names)
{
  std::vector<std::string> q;
  for (const std::string& n : names)
    q.push_back("'" + n + "'");
  return join(q, ", ");
}

std::string suggestion(const std::string& name, const std::vector<std::string>& candidates)
{
  const std::size_t threshold = std::max<std::size_t>(2, name.size() / 3);
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  for (const std::string& c : candidates)
  {
    const std::size_t d = edit_distance(name, c);
    if (d <= threshold && d < std::max(name.size(), c.size()) && (!best || d < best_distance))
    {
      best = c;
      best_distance = d;
    }
  }
  return best ? "; did you mean '" + *best + "'?" : "";
}

std::string yaml_text(const YAML::Node& node)
{
  if (!node.IsDefined() || node.IsNull())
    return "";
  std::string text;
  if (node.IsScalar())
    text = node.Scalar();
  else
  {
    YAML::Emitter emitter;
    emitter << YAML::Flow << node;
    text = emitter.c_str();
  }
  if (text.size() > 80)
    text = text.substr(0, 77) + "...";
  return text;
}

std::optional<double> parse_double(const std::string& text)
{
  const std::string t = trim(text);
  if (t.empty())
    return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size() || errno == ERANGE || !std::isfinite(v))
    return std::nullopt;
  return v;
}

std::optional<double> parse_double(const YAML::Node& node)
{
  if (!node.IsDefined() || !node.IsScalar())
    return std::nullopt;
  return parse_double(node.Scalar());
}

std::optional<long long> parse_integer(const YAML::Node& node)
{
  if (!node.IsDefined() || !node.IsScalar())
    return std::nullopt;
  const std::string t = trim(node.Scalar());
  if (t.empty())
    return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  if (end != t.c_str() + t.size() || errno == ERANGE)
    return std::nullopt;
  return v;
}

YAML::Node child(const YAML::Node& map, const std::string& key)
{
  const YAML::Node& const_map = map;
  return const_map[key];
}

YAML::Node nested(const YAML::Node& node, const std::vector<std::string>& keys)
{
  YAML::Node n = node;
  for (const std::string& k : keys)
  {
    if (!n.IsMap())
      return YAML::Node(YAML::NodeType::Undefined);
    const YAML::Node next = child(n, k);
    if (!next.IsDefined())
      return YAML::Node(YAML::NodeType::Undefined);
    n.reset(next);
  }
  return n;
}

} // namespace ddafem::scene_reading
