// The error raised for bad user input (scene files, command-line overrides, missing files).
#pragma once

#include <stdexcept>
#include <string>

namespace ddafem
{
/// Bad user input. The message names the file, the line (when known), the key, the value found
/// and what was expected. The command line turns it into exit code 2.
class InputError : public std::runtime_error
{
public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}

  /// "FILE:LINE: key 'KEY' = 'VALUE': EXPECTED". line <= 0 omits the line number; an empty
  /// key or value omits that part.
  static InputError at(const std::string& file, int line, const std::string& key,
                       const std::string& value, const std::string& expected)
  {
    std::string m = file;
    if (line > 0)
      m += ":" + std::to_string(line);
    m += ": ";
    if (!key.empty())
    {
      m += "key '" + key + "'";
      if (!value.empty())
        m += " = '" + value + "'";
      m += ": ";
    }
    m += expected;
    return InputError(m);
  }
};

} // namespace ddafem
