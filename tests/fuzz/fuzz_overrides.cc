// libFuzzer harness (issue 20): `--set key=value` overrides on a valid scene. The input's first
// line names the scene (a path below the source directory, one of the examples or
// tests/app/scenes), each further line is one --set argument, parsed by parse_override and
// applied by read_scene in order. Inputs naming another scene are rejected (kept out of the
// corpus). Corpus: tests/fuzz/corpus/overrides; docs/testing.md.
#include "tests/fuzz/fuzz_reading.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace
{
namespace fs = std::filesystem;

/// The text of every scene the inputs may name, by its path below the source directory.
std::map<std::string, std::string> read_scenes()
{
  const fs::path top = DDAFEM_SOURCE_DIR;
  std::map<std::string, std::string> scenes;
  for (const fs::path& folder : {top / "examples", top / "tests/app/scenes"})
    for (const auto& entry : fs::recursive_directory_iterator(folder))
      if (entry.path().extension() == ".yaml")
      {
        std::ostringstream text;
        text << std::ifstream(entry.path()).rdbuf();
        scenes[fs::relative(entry.path(), top).string()] = text.str();
      }
  return scenes;
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  static const std::map<std::string, std::string> scenes = read_scenes();
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::string name;
  std::getline(in, name);
  const auto scene = scenes.find(name);
  if (scene == scenes.end())
    return -1;
  std::vector<ddafem::Override> overrides;
  try
  {
    for (std::string line; std::getline(in, line);)
      overrides.push_back(ddafem::parse_override(line));
  }
  catch (const ddafem::InputError&)
  {
    return 0;
  }
  ddafem::fuzz::read_or_refuse(scene->second, DDAFEM_SOURCE_DIR "/" + name, overrides);
  return 0;
}
